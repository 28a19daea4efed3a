// Shape tests and lattice sampling of bodies into material points.
#include "fragmpm/pipeline/scene_shapes.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>

namespace fragmpm::pipeline {
namespace {

double cross(const Vec2& a, const Vec2& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// Sign of the turn a → b → c: +1 left, −1 right, 0 collinear.
int orientation(const Vec2& a, const Vec2& b, const Vec2& c) {
  const double t = cross(b - a, c - a);
  return (t > 0.0) - (t < 0.0);
}

/// q on the segment [a, b], given that a, b, q are collinear.
bool on_segment(const Vec2& a, const Vec2& b, const Vec2& q) {
  return q.x() >= std::min(a.x(), b.x()) && q.x() <= std::max(a.x(), b.x()) &&
         q.y() >= std::min(a.y(), b.y()) && q.y() <= std::max(a.y(), b.y());
}

/// Closed segments [a, b] and [c, d] share at least one point.
bool segments_meet(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const int o1 = orientation(a, b, c), o2 = orientation(a, b, d);
  const int o3 = orientation(c, d, a), o4 = orientation(c, d, b);
  if (o1 != o2 && o3 != o4) return true;
  return (o1 == 0 && on_segment(a, b, c)) || (o2 == 0 && on_segment(a, b, d)) ||
         (o3 == 0 && on_segment(c, d, a)) || (o4 == 0 && on_segment(c, d, b));
}

bool polygon_contains(const std::vector<Vec2>& v, const Vec2& p) {
  // Crossing number with a horizontal ray to +x; points exactly on an edge count as inside.
  bool inside = false;
  const std::size_t n = v.size();
  for (std::size_t k = 0, j = n - 1; k < n; j = k++) {
    const Vec2& a = v[j];
    const Vec2& b = v[k];
    if (orientation(a, b, p) == 0 && on_segment(a, b, p)) return true;
    if ((a.y() > p.y()) != (b.y() > p.y())) {
      const double x_cross = a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
      if (p.x() < x_cross) inside = !inside;
    }
  }
  return inside;
}

}  // namespace

bool contains(const Shape& shape, const Vec2& p) {
  switch (shape.kind) {
    case ShapeKind::disk: {
      const double r2 = (p - shape.center).squaredNorm();
      return r2 <= shape.radius * shape.radius && r2 >= shape.inner_radius * shape.inner_radius;
    }
    case ShapeKind::box:
      return p.x() >= shape.min.x() && p.x() <= shape.max.x() && p.y() >= shape.min.y() &&
             p.y() <= shape.max.y();
    case ShapeKind::polygon:
      return polygon_contains(shape.vertices, p);
  }
  return false;
}

std::pair<Vec2, Vec2> bounding_box(const Shape& shape) {
  switch (shape.kind) {
    case ShapeKind::disk:
      return {shape.center - Vec2::Constant(shape.radius),
              shape.center + Vec2::Constant(shape.radius)};
    case ShapeKind::box:
      return {shape.min, shape.max};
    case ShapeKind::polygon: {
      Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity());
      Vec2 hi = -lo;
      for (const Vec2& v : shape.vertices) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
      }
      return {lo, hi};
    }
  }
  return {Vec2::Zero(), Vec2::Zero()};
}

double polygon_area(const std::vector<Vec2>& v) {
  double twice = 0.0;
  for (std::size_t k = 0, n = v.size(); k < n; ++k) twice += cross(v[k], v[(k + 1) % n]);
  return std::abs(twice) / 2.0;
}

std::pair<int, int> polygon_self_intersection(const std::vector<Vec2>& v) {
  const int n = static_cast<int>(v.size());
  auto a = [&](int k) -> const Vec2& { return v[static_cast<std::size_t>(k)]; };
  auto b = [&](int k) -> const Vec2& { return v[static_cast<std::size_t>((k + 1) % n)]; };
  for (int k = 0; k < n; ++k) {
    if (a(k) == b(k)) return {k, k};  // repeated vertex: zero-length edge
    // Neighbouring edges share a vertex by construction; they are bad only when they fold back.
    const int next = (k + 1) % n;
    const Vec2 d0 = b(k) - a(k), d1 = b(next) - a(next);
    if (cross(d0, d1) == 0.0 && d0.dot(d1) < 0.0) return {k, next};
  }
  for (int k = 0; k < n; ++k)
    for (int m = k + 2; m < n; ++m) {
      if (k == 0 && m == n - 1) continue;  // neighbours through vertex 0
      if (segments_meet(a(k), b(k), a(m), b(m))) return {k, m};
    }
  return {-1, -1};
}

SampleResult sample_bodies(const std::vector<BodySample>& bodies,
                           const std::vector<mpm::MaterialSpec>& materials,
                           const mpm::GridSpec<2>& grid, int particles_per_cell,
                           const std::vector<MirrorPlane>& mirrors) {
  const double s = grid.cell_size / particles_per_cell;
  // Lattice points x = min + (i + 1/2) s inside the domain: i + 1/2 < L/s.
  std::int64_t n_lattice[2];
  for (int d = 0; d < 2; ++d)
    n_lattice[d] = std::max<std::int64_t>(
        0, static_cast<std::int64_t>(std::ceil((grid.max[d] - grid.min[d]) / s - 0.5)));
  auto point = [&](std::int64_t i, std::int64_t j) {
    return Vec2(grid.min.x() + (static_cast<double>(i) + 0.5) * s,
                grid.min.y() + (static_cast<double>(j) + 0.5) * s);
  };
  auto owner = [&](const Vec2& p, std::size_t up_to) -> std::ptrdiff_t {
    for (std::size_t b = 0; b < up_to; ++b)
      if (contains(bodies[b].shape, p)) return static_cast<std::ptrdiff_t>(b);
    return -1;
  };

  SampleResult out;
  const std::size_t nb = bodies.size();
  out.count.assign(nb, 0);
  out.in_shape.assign(nb, 0);
  out.overlap.assign(nb, std::vector<std::size_t>(nb, 0));

  struct Site {
    std::int64_t i, j;
  };
  std::vector<Site> sites;
  std::vector<std::int32_t> site_body;
  for (std::size_t b = 0; b < nb; ++b) {
    const auto [lo, hi] = bounding_box(bodies[b].shape);
    std::int64_t first[2], last[2];
    for (int d = 0; d < 2; ++d) {
      first[d] = std::max<std::int64_t>(
          0, static_cast<std::int64_t>(std::ceil((lo[d] - grid.min[d]) / s - 0.5)));
      last[d] = std::min<std::int64_t>(
          n_lattice[d] - 1, static_cast<std::int64_t>(std::floor((hi[d] - grid.min[d]) / s - 0.5)));
    }
    for (std::int64_t j = first[1]; j <= last[1]; ++j)
      for (std::int64_t i = first[0]; i <= last[0]; ++i) {
        const Vec2 p = point(i, j);
        if (!contains(bodies[b].shape, p)) continue;
        ++out.in_shape[b];
        const std::ptrdiff_t earlier = owner(p, b);
        if (earlier >= 0) {
          ++out.overlap[b][static_cast<std::size_t>(earlier)];
          continue;
        }
        sites.push_back({i, j});
        site_body.push_back(static_cast<std::int32_t>(b));
        ++out.count[b];
      }
  }

  // Which body holds each lattice site, for the surface flags.
  std::unordered_map<std::int64_t, std::int32_t> holder;
  holder.reserve(sites.size() * 2);
  auto key = [&](std::int64_t i, std::int64_t j) { return j * n_lattice[0] + i; };
  for (std::size_t k = 0; k < sites.size(); ++k)
    holder.emplace(key(sites[k].i, sites[k].j), site_body[k]);

  mpm::Particles<2>& P = out.particles;
  P.resize(sites.size());
  const double volume = s * s;  // per unit thickness (plane strain)
  for (std::size_t k = 0; k < sites.size(); ++k) {
    const std::int32_t b = site_body[k];
    const auto& body = bodies[static_cast<std::size_t>(b)];
    P.x[k] = point(sites[k].i, sites[k].j);
    P.F[k] = mpm::Mat<2>::Identity();
    P.domain[k] = s * mpm::Mat<2>::Identity();  // columns r1 = (s, 0), r2 = (0, s)
    P.volume0[k] = volume;
    P.mass[k] = materials[static_cast<std::size_t>(body.material)].density * volume;
    P.stress[k].setZero();
    P.damage[k] = 0.0;
    P.damage_history[k] = 0.0;
    P.body[k] = b;
    P.material[k] = body.material;
    P.strength[k] = std::numeric_limits<double>::infinity();
    std::uint8_t surface = 0;
    for (int dj = -1; dj <= 1 && !surface; ++dj)
      for (int di = -1; di <= 1 && !surface; ++di) {
        if (di == 0 && dj == 0) continue;
        const std::int64_t i = sites[k].i + di, j = sites[k].j + dj;
        // Beyond a symmetry plane the neighbour is the mirror image of a point of the model:
        // present when that image lies in this body. The plane is then no surface, as in the full
        // (unmirrored) body, so the damage field does not partition the body along it ([HH17] §2.4
        // flags the surfaces that may open or touch; a face on a bilateral roller can do neither).
        const Vec2 q = point(i, j);
        bool mirrored = false;
        for (const MirrorPlane& m : mirrors) {
          const double depth = (q - m.point).dot(m.normal);
          if (depth >= 0.0) continue;
          mirrored = true;
          const Vec2 image = q - 2.0 * depth * m.normal;
          if (!contains(body.shape, image) || owner(image, static_cast<std::size_t>(b)) >= 0)
            surface = 1;
          break;
        }
        if (mirrored) continue;
        if (i < 0 || j < 0 || i >= n_lattice[0] || j >= n_lattice[1]) {
          surface = 1;
          continue;
        }
        const auto it = holder.find(key(i, j));
        if (it == holder.end() || it->second != b) surface = 1;
      }
    P.surface[k] = surface;
  }

  // Rigid initial motion about the centroid of each body's particles (equal masses within a body),
  // so the angular part carries no net momentum: v = v0 + ω e_z × (x − x_c).
  std::vector<Vec2> centroid(nb, Vec2::Zero());
  for (std::size_t k = 0; k < sites.size(); ++k)
    centroid[static_cast<std::size_t>(site_body[k])] += P.x[k];
  for (std::size_t b = 0; b < nb; ++b)
    if (out.count[b] > 0) centroid[b] /= static_cast<double>(out.count[b]);
  for (std::size_t k = 0; k < sites.size(); ++k) {
    const auto b = static_cast<std::size_t>(site_body[k]);
    const Vec2 r = P.x[k] - centroid[b];
    P.v[k] = bodies[b].velocity + bodies[b].angular_velocity * Vec2(-r.y(), r.x());
    // The velocity gradient of that motion, the affine field an APIC run starts from (FLIP drops
    // it).
    P.affine[k] << 0.0, -bodies[b].angular_velocity, bodies[b].angular_velocity, 0.0;
  }
  return out;
}

}  // namespace fragmpm::pipeline
