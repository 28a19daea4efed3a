// Scene file → mpm::Problem<2> (docs/design.md; format in scenes/README.md). Reads every section
// with strict keys and units, then samples the bodies and runs the cross-checks of
// scene_validate.cpp.
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

#include "fragmpm/mpm/run_file.hpp"
#include "fragmpm/mpm/wave_speed.hpp"
#include "fragmpm/pipeline/scene.hpp"
#include "fragmpm/pipeline/scene_shapes.hpp"
#include "scene_cracks.hpp"
#include "scene_fracture.hpp"
#include "scene_grains.hpp"
#include "scene_thermal.hpp"
#include "scene_toml.hpp"
#include "scene_validate.hpp"

namespace fragmpm::pipeline {
namespace {

using namespace scene_detail;
using QK = QuantityKind;

constexpr int kMaxParticlesPerCell = 16;

std::string quoted_list(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "\"" : ", \"") + n + "\"";
  return out;
}

/// Remembers names per kind of entry so that duplicates are reported with the first definition.
class NameRegistry {
 public:
  explicit NameRegistry(std::string what) : what_(std::move(what)) {}
  void add(const Section& s, const std::string& name) {
    const auto [it, inserted] = lines_.emplace(name, s.line_of("name"));
    if (!inserted)
      s.fail("name", "expected a " + what_ + " name not used before, got \"" + name +
                         "\" (already defined at line " + std::to_string(it->second) + ")");
    order_.push_back(name);
  }
  const std::vector<std::string>& names() const { return order_; }
  int index(const std::string& name) const {
    const auto it = std::find(order_.begin(), order_.end(), name);
    return it == order_.end() ? -1 : static_cast<int>(it - order_.begin());
  }

 private:
  std::string what_;
  std::map<std::string, int> lines_;
  std::vector<std::string> order_;
};

int read_grid(const Section& g, mpm::GridSpec<2>& grid) {
  g.allow_only({"cell_size", "min", "max", "shape_function", "particles_per_cell", "outside"});
  grid.cell_size = g.quantity("cell_size", QK::length);
  if (!(grid.cell_size > 0.0)) g.expected("cell_size", "a positive length");
  grid.min = g.vector("min", QK::length);
  grid.max = g.vector("max", QK::length);
  for (int d = 0; d < 2; ++d)
    if (!(grid.max[d] > grid.min[d]))
      g.fail("max", "expected max > min in x and y, got max = [" + si(grid.max.x(), "m") + ", " +
                        si(grid.max.y(), "m") + "] and min = [" + si(grid.min.x(), "m") + ", " +
                        si(grid.min.y(), "m") + "]");
  const Vec2 extent = grid.max - grid.min;
  if (grid.cell_size > extent.minCoeff())
    g.fail("cell_size", "expected a cell size no larger than the domain (" + si(extent.x(), "m") +
                            " x " + si(extent.y(), "m") + "), got " + si(grid.cell_size, "m"));
  const std::string sf = g.optional_string("shape_function").value_or("cpdi");
  if (sf == "cpdi")
    grid.shape_function = mpm::ShapeFunctionKind::cpdi;
  else if (sf == "linear")
    grid.shape_function = mpm::ShapeFunctionKind::linear;
  else if (sf == "ugimp")
    grid.shape_function = mpm::ShapeFunctionKind::ugimp;
  else if (sf == "bspline2")
    grid.shape_function = mpm::ShapeFunctionKind::bspline2;
  else
    g.expected("shape_function", "one of \"cpdi\", \"linear\", \"ugimp\", \"bspline2\"");
  const std::string outside = g.optional_string("outside").value_or("stop");
  if (outside == "stop")
    grid.outside = mpm::OutsidePolicy::stop;
  else if (outside == "remove")
    grid.outside = mpm::OutsidePolicy::remove;
  else
    g.expected("outside",
               "one of \"stop\" (a particle leaving the domain stops the run) or \"remove\" (it "
               "is taken out of the run and booked in /series lost_mass and lost_kinetic)");
  const long long n = g.optional_integer("particles_per_cell").value_or(2);
  if (n < 1 || n > kMaxParticlesPerCell)
    g.expected("particles_per_cell",
               "an integer from 1 to " + std::to_string(kMaxParticlesPerCell) + " (per direction)");
  return static_cast<int>(n);
}

void read_time(const Section& t, mpm::TimeSpec& time) {
  t.allow_only({"cfl", "dt", "transfer", "pic_fraction", "thermal_pic_fraction", "damping"});
  time.cfl = t.optional_number("cfl").value_or(0.4);
  if (!(time.cfl > 0.0 && time.cfl <= 1.0)) t.expected("cfl", "a Courant number 0 < cfl <= 1");
  if (auto dt = t.optional_quantity("dt", QK::time)) {
    if (!(*dt > 0.0)) t.expected("dt", "a positive time step");
    time.fixed_dt = *dt;
  }
  const std::string transfer = t.optional_string("transfer").value_or("flip");
  if (transfer == "flip")
    time.transfer = mpm::Transfer::flip;
  else if (transfer == "apic")
    time.transfer = mpm::Transfer::apic;
  else
    t.expected("transfer", "one of \"flip\" ([XLS21] eq. (64)), \"apic\" ([JSS15])");
  if (time.transfer == mpm::Transfer::apic && t.has("pic_fraction"))
    t.expected("pic_fraction",
               "no pic_fraction with transfer = \"apic\" (the FLIP/PIC blend is FLIP's)");
  time.pic_fraction = t.optional_number("pic_fraction").value_or(0.0);
  if (!(time.pic_fraction >= 0.0 && time.pic_fraction <= 1.0))
    t.expected("pic_fraction", "a PIC fraction 0 <= pic_fraction <= 1 ([XLS21] eq. (64))");
  time.thermal_pic_fraction = t.optional_number("thermal_pic_fraction").value_or(0.0);
  if (!(time.thermal_pic_fraction >= 0.0 && time.thermal_pic_fraction <= 1.0))
    t.expected("thermal_pic_fraction",
               "a PIC fraction 0 <= thermal_pic_fraction <= 1 (0 = [XLS21] eq. (62))");
  time.damping = t.optional_quantity("damping", QK::frequency).value_or(0.0);
  if (!(time.damping >= 0.0 && std::isfinite(time.damping)))
    t.expected("damping", "a mass-proportional damping coefficient >= 0 (e.g. \"1e6 1/s\")");
}

mpm::MaterialSpec read_material(const Section& m, std::optional<double> thickness,
                                const mpm::GridSpec<2>& grid, double particle_spacing) {
  std::vector<std::string_view> keys = {"name", "model", "E", "nu", "K", "G", "density"};
  keys.insert(keys.end(), damage_keys().begin(), damage_keys().end());
  keys.insert(keys.end(), thermal_material_keys().begin(), thermal_material_keys().end());
  m.allow_only(keys);
  mpm::MaterialSpec spec;
  spec.name = m.name("name");
  const std::string model = m.optional_string("model").value_or("neo-hookean");
  if (model != "neo-hookean")
    m.expected("model", "\"neo-hookean\" (the only material model so far)");
  const bool young = m.has("E") || m.has("nu");
  const bool bulk = m.has("K") || m.has("G");
  if (young && bulk)
    m.fail(m.has("K") ? "K" : "G",
           "expected either (E, nu) or (K, G), got both kinds of elastic constants");
  if (!young && !bulk) m.fail("E", "missing required key: expected either E and nu, or K and G");
  if (young) {
    const double E = m.quantity("E", QK::pressure);
    if (!(E > 0.0)) m.expected("E", "a positive Young's modulus");
    const double nu = m.number("nu");
    if (!(nu > -1.0 && nu < 0.5)) m.expected("nu", "a Poisson's ratio -1 < nu < 0.5");
    spec.bulk_modulus = E / (3.0 * (1.0 - 2.0 * nu));
    spec.shear_modulus = E / (2.0 * (1.0 + nu));
  } else {
    spec.bulk_modulus = m.quantity("K", QK::pressure);
    if (!(spec.bulk_modulus > 0.0)) m.expected("K", "a positive bulk modulus");
    spec.shear_modulus = m.quantity("G", QK::pressure);
    if (!(spec.shear_modulus > 0.0)) m.expected("G", "a positive shear modulus");
  }
  spec.density = m.quantity("density", QK::density);
  if (!(spec.density > 0.0)) m.expected("density", "a positive density");
  read_damage(m, spec, thickness, grid, particle_spacing);
  return spec;
}

/// Plane stress (mpm::plane_stress_bulk_modulus): exact for the Hencky energy, which is quadratic
/// in the log strains; the neo-Hookean energy is not, so damaging neo-Hookean materials are
/// refused at `plane`, as are the thermal stress and the crushed flow, written for plane strain.
void apply_plane_stress(mpm::Problem<2>& problem, const Section& physics) {
  if (problem.thermal.active())
    physics.fail("plane", "expected plane = \"strain\" in a scene whose thermal module is on (" +
                              problem.thermal.reason +
                              "): the thermal stress is written for plane strain");
  for (mpm::MaterialSpec& m : problem.materials) {
    // An elastic material (no damage law) is Hencky-elastic in plane stress: the two energies
    // agree to second order in the strain, and the Hencky one reduces exactly.
    if (!m.damages()) m.degradation = mpm::Degradation::hencky_spectral;
    if (mpm::elastic_law(m) != mpm::ElasticLaw::hencky)
      physics.fail("plane",
                   "expected every damaging material to be Hencky-elastic for plane = \"stress\" "
                   "(damage = \"phase-field\" or degradation = \"hencky-spectral\"), "
                   "got material '" +
                       m.name + "'");
    if (m.crushed_friction_angle > 0.0)
      physics.fail("plane",
                   "expected no crushed_friction_angle for plane = \"stress\" (material '" +
                       m.name + "'): the crushed flow is written for plane strain");
    m.bulk_modulus = mpm::plane_stress_bulk_modulus(m.bulk_modulus, m.shear_modulus);
  }
}

Shape read_shape(const Section& b) {
  Shape s;
  const std::string kind = b.string("shape");
  const std::vector<std::string_view> common = {"name",     "material",         "shape",
                                                "velocity", "angular_velocity", "temperature"};
  auto allow = [&](std::initializer_list<std::string_view> extra) {
    std::vector<std::string_view> keys = common;
    keys.insert(keys.end(), extra);
    b.allow_only(keys);
  };
  if (kind == "disk") {
    allow({"center", "radius", "inner_radius"});
    s.kind = ShapeKind::disk;
    s.center = b.vector("center", QK::length);
    s.radius = b.quantity("radius", QK::length);
    if (!(s.radius > 0.0)) b.expected("radius", "a positive length");
    s.inner_radius = b.optional_quantity("inner_radius", QK::length).value_or(0.0);
    if (!(s.inner_radius >= 0.0 && s.inner_radius < s.radius))
      b.fail("inner_radius", "expected a length from 0 up to the radius " + si(s.radius, "m") +
                                 " (a ring's hole), got " + si(s.inner_radius, "m"));
  } else if (kind == "box") {
    allow({"min", "max"});
    s.kind = ShapeKind::box;
    s.min = b.vector("min", QK::length);
    s.max = b.vector("max", QK::length);
    if (!(s.max.x() > s.min.x() && s.max.y() > s.min.y()))
      b.fail("max", "expected max > min in x and y, got max = [" + si(s.max.x(), "m") + ", " +
                        si(s.max.y(), "m") + "] and min = [" + si(s.min.x(), "m") + ", " +
                        si(s.min.y(), "m") + "]");
  } else if (kind == "polygon") {
    allow({"vertices"});
    s.kind = ShapeKind::polygon;
    s.vertices = b.point_list("vertices", QK::length);
    if (s.vertices.size() < 3)
      b.fail("vertices", "expected at least 3 vertices, got " + std::to_string(s.vertices.size()));
    const auto [e1, e2] = polygon_self_intersection(s.vertices);
    if (e1 >= 0) {
      const auto n = s.vertices.size();
      auto edge = [&](int e) {
        return std::to_string(e) + "-" + std::to_string((static_cast<std::size_t>(e) + 1) % n);
      };
      b.fail("vertices", "expected a simple polygon, got edges between vertices " + edge(e1) +
                             " and " + edge(e2) +
                             (e1 == e2 ? " (a repeated vertex)" : " that meet or fold back"));
    }
    if (!(polygon_area(s.vertices) > 0.0))
      b.fail("vertices", "expected a polygon with positive area, got zero area");
  } else {
    b.expected("shape", "one of \"disk\", \"box\", \"polygon\"");
  }
  return s;
}

int read_body_material(const Section& b, const NameRegistry& materials) {
  const int m = materials.index(b.string("material"));
  if (m < 0)
    b.expected("material", "the name of a material defined in [[materials]] (" +
                               quoted_list(materials.names()) + ")");
  return m;
}

BodyEntry read_body(const Section& b, const NameRegistry& materials) {
  BodyEntry body{b.name("name"), {}, b};
  body.sample.material = read_body_material(b, materials);
  body.sample.shape = read_shape(b);
  body.sample.velocity = b.optional_vector("velocity", QK::velocity).value_or(Vec2::Zero());
  body.sample.angular_velocity =
      b.optional_quantity("angular_velocity", QK::angular_velocity).value_or(0.0);
  return body;
}

mpm::VelocityHistory<2> read_history(const Section& h) {
  mpm::VelocityHistory<2> v;
  const std::string type = h.string("type");
  if (type == "constant") {
    h.allow_only({"type", "value"});
    v.kind = mpm::HistoryKind::constant;
    v.from = h.vector("value", QK::velocity);
  } else if (type == "ramp") {
    h.allow_only({"type", "from", "to", "t_start", "t_end"});
    v.kind = mpm::HistoryKind::ramp;
    v.from = h.vector("from", QK::velocity);
    v.to = h.vector("to", QK::velocity);
    v.t_start = h.optional_quantity("t_start", QK::time).value_or(0.0);
    if (!(v.t_start >= 0.0)) h.expected("t_start", "a time t_start >= 0");
    v.t_end = h.quantity("t_end", QK::time);
    if (!(v.t_end > v.t_start))
      h.expected("t_end", "a time t_end > t_start = " + si(v.t_start, "s"));
  } else if (type == "sinusoid") {
    h.allow_only({"type", "offset", "amplitude", "frequency", "phase", "t_start"});
    v.kind = mpm::HistoryKind::sinusoid;
    v.t_start = h.optional_quantity("t_start", QK::time).value_or(0.0);
    if (!(v.t_start >= 0.0))
      h.expected("t_start", "a time t_start >= 0 (the sinusoid starts then)");
    v.from = h.optional_vector("offset", QK::velocity).value_or(Vec2::Zero());
    v.amplitude = h.vector("amplitude", QK::velocity);
    v.frequency = h.quantity("frequency", QK::frequency);
    if (!(v.frequency > 0.0)) h.expected("frequency", "a positive frequency");
    v.phase = h.optional_quantity("phase", QK::angle).value_or(0.0);
  } else {
    h.expected("type", "one of \"constant\", \"ramp\", \"sinusoid\"");
  }
  return v;
}

mpm::WallSpec<2> read_wall(const Section& w) {
  w.allow_only({"name", "point", "normal", "kind", "friction", "velocity", "thermal", "region",
                "stiffness", "gap_test"});
  mpm::WallSpec<2> wall;
  wall.name = w.name("name");
  wall.point = w.vector("point", QK::length);
  const Vec2 n = w.vector("normal", std::nullopt);
  if (!(n.norm() > 0.0))
    w.expected("normal", "a non-zero normal vector pointing into the material side");
  wall.normal = n / n.norm();
  const std::string kind = w.optional_string("kind").value_or("contact");
  if (kind == "contact")
    wall.kind = mpm::WallKind::contact;
  else if (kind == "roller")
    wall.kind = mpm::WallKind::roller;
  else if (kind == "fixed")
    wall.kind = mpm::WallKind::fixed;
  else if (kind == "penalty")
    wall.kind = mpm::WallKind::penalty;
  else if (kind == "thermal")
    wall.kind = mpm::WallKind::contact;  // a plane for a thermal condition only (parse_scene)
  else
    w.expected("kind", "one of \"contact\", \"roller\", \"fixed\", \"penalty\", \"thermal\"");
  if (wall.kind == mpm::WallKind::penalty) {
    wall.penalty_stiffness = w.quantity("stiffness", QK::stiffness);
    if (!(wall.penalty_stiffness > 0.0 && std::isfinite(wall.penalty_stiffness)))
      w.expected("stiffness",
                 "a positive penalty stiffness kappa_n ([XLS21] eq. (83)), e.g. \"100 GPa/mm\"");
  } else if (w.has("stiffness")) {
    w.fail("stiffness", "expected no stiffness for kind = \"" + kind +
                            "\" (the penalty stiffness belongs to kind = \"penalty\")");
  }
  if (w.has("friction")) {
    if (wall.kind != mpm::WallKind::contact)
      w.fail("friction", "expected no friction for kind = \"" + kind +
                             "\" (friction applies to contact walls only)");
    wall.friction = read_friction(w, "friction");
  }
  if (w.has("gap_test")) {
    if (kind != "contact")
      w.fail("gap_test", "expected no gap_test for kind = \"" + kind +
                             "\" (the position test applies to contact walls only)");
    wall.gap_test = w.optional_bool("gap_test").value_or(false);
  }
  if (auto h = w.optional_table("velocity")) wall.velocity = read_history(*h);
  if (auto r = w.optional_table("region")) {
    r->allow_only({"min", "max"});
    wall.region.bounded = true;
    wall.region.min = r->vector("min", QK::length);
    wall.region.max = r->vector("max", QK::length);
    if (!(wall.region.max.array() > wall.region.min.array()).all())
      r->expected("max", "a corner above and to the right of min = (" +
                             si(wall.region.min.x(), "m") + ", " + si(wall.region.min.y(), "m") +
                             ")");
  }
  return wall;
}

/// Appends `src` to `dst`, shifting body ids by `first_body`.
void append_particles(mpm::Particles<2>& dst, const mpm::Particles<2>& src,
                      std::int32_t first_body) {
  auto cat = [](auto& a, const auto& b) { a.insert(a.end(), b.begin(), b.end()); };
  cat(dst.x, src.x);
  cat(dst.v, src.v);
  cat(dst.affine, src.affine);
  cat(dst.F, src.F);
  cat(dst.volume0, src.volume0);
  cat(dst.mass, src.mass);
  cat(dst.domain, src.domain);
  cat(dst.stress, src.stress);
  cat(dst.damage, src.damage);
  cat(dst.damage_history, src.damage_history);
  cat(dst.surface, src.surface);
  const std::size_t at = dst.body.size();
  cat(dst.body, src.body);
  for (std::size_t p = at; p < dst.body.size(); ++p) dst.body[p] += first_body;
  cat(dst.material, src.material);
  cat(dst.strength, src.strength);
  cat(dst.temperature, src.temperature);
}

bool never_moves(const mpm::VelocityHistory<2>& v) {
  switch (v.kind) {
    case mpm::HistoryKind::constant:
      return v.from.isZero(0.0);
    case mpm::HistoryKind::ramp:
      return v.from.isZero(0.0) && v.to.isZero(0.0);
    case mpm::HistoryKind::sinusoid:
      return v.from.isZero(0.0) && v.amplitude.isZero(0.0);
  }
  return false;
}

void read_stop(const Section& s, const NameRegistry& walls,
               const std::vector<mpm::WallSpec<2>>& wall_specs, mpm::StopSpec& stop) {
  s.allow_only({"end_time", "max_steps", "platen_displacement", "platen"});
  if (!s.has("end_time") && !s.has("max_steps") && !s.has("platen_displacement"))
    s.fail_table(
        "no stop condition: expected at least one of end_time, max_steps, platen_displacement");
  if (auto t = s.optional_quantity("end_time", QK::time)) {
    if (!(*t > 0.0)) s.expected("end_time", "a positive time");
    stop.end_time = *t;
  }
  if (auto n = s.optional_integer("max_steps")) {
    if (*n < 1) s.expected("max_steps", "a positive number of steps");
    stop.max_steps = *n;
  }
  if (auto d = s.optional_quantity("platen_displacement", QK::length)) {
    if (!(*d > 0.0)) s.expected("platen_displacement", "a positive length");
    if (!s.has("platen"))
      s.fail("platen", "missing required key: platen_displacement needs platen = \"<wall name>\"");
    stop.platen_displacement = *d;
  }
  if (s.has("platen")) {
    if (!s.has("platen_displacement"))
      s.fail("platen",
             "expected platen only together with platen_displacement, got platen without it");
    const std::string name = s.string("platen");
    stop.platen = walls.index(name);
    if (stop.platen < 0)
      s.expected("platen", walls.names().empty()
                               ? std::string("the name of a wall, but no [[walls]] are defined")
                               : "the name of a wall defined in [[walls]] (" +
                                     quoted_list(walls.names()) + ")");
    if (!s.has("end_time") && !s.has("max_steps") &&
        never_moves(wall_specs[static_cast<std::size_t>(stop.platen)].velocity))
      s.fail("platen", "expected a platen that moves (it is the only stop condition), got wall '" +
                           name + "' whose velocity is zero at all times");
  }
}

void read_output(const std::optional<Section>& o, const mpm::StopSpec& stop, mpm::OutputSpec& out) {
  out.interval = std::isfinite(stop.end_time) ? stop.end_time / 20.0 : 0.0;
  if (!o) return;
  o->allow_only({"interval", "fields"});
  if (auto iv = o->optional_quantity("interval", QK::time)) {
    if (!(*iv >= 0.0))
      o->expected("interval", "a time interval >= 0 (0 = first and last frame only)");
    out.interval = *iv;
  }
  if (!o->has("fields")) return;
  const std::vector<std::string> fields = o->string_list("fields");
  const std::vector<std::string>& known = mpm::all_frame_fields();
  if (fields.empty()) o->expected("fields", "at least one frame field (leave the key out for all)");
  for (std::size_t i = 0; i < fields.size(); ++i) {
    const std::string ek = "fields[" + std::to_string(i) + "]";
    const int line = static_cast<int>(o->find("fields")->as_array()->get(i)->source().begin.line);
    if (std::find(known.begin(), known.end(), fields[i]) == known.end())
      scene_detail::fail(o->file(), line, o->key(ek),
                         "expected one of " + quoted_list(known) + ", got \"" + fields[i] + "\"");
    if (std::find(fields.begin(), fields.begin() + static_cast<std::ptrdiff_t>(i), fields[i]) !=
        fields.begin() + static_cast<std::ptrdiff_t>(i))
      scene_detail::fail(o->file(), line, o->key(ek),
                         "expected each field once, got \"" + fields[i] + "\" twice");
  }
  out.fields = fields;
}

}  // namespace

mpm::Problem<2> parse_scene(const std::string& text, const std::string& path) {
  toml::table root;
  try {
    root = toml::parse(std::string_view(text), std::string_view(path));
  } catch (const toml::parse_error& e) {
    throw SceneError(path, static_cast<int>(e.source().begin.line), "",
                     "TOML syntax error (column " + std::to_string(e.source().begin.column) +
                         "): " + std::string(e.description()));
  }
  const Section top(root, "", path);
  top.allow_only({"grid", "time", "physics", "materials", "bodies", "walls", "contact", "loads",
                  "cracks", "stop", "output"});

  mpm::Problem<2> problem;
  problem.scene_path = path;
  problem.scene_text = text;

  const int per_cell = read_grid(top.table("grid"), problem.grid);
  const std::optional<Section> time = top.optional_table("time");
  if (time) read_time(*time, problem.time);
  std::optional<double> thickness;  // out-of-plane thickness, only for Weibull volumes in 2D
  const std::optional<Section> physics = top.optional_table("physics");
  if (physics) {
    physics->allow_only({"gravity", "thickness", "plane"});
    const std::string plane = physics->optional_string("plane").value_or("strain");
    if (plane != "strain" && plane != "stress")
      physics->expected("plane", "\"strain\" (default) or \"stress\"");
    problem.plane_stress = plane == "stress";
    problem.gravity = physics->optional_vector("gravity", QK::acceleration).value_or(Vec2::Zero());
    thickness = physics->optional_quantity("thickness", QK::length);
    if (thickness && !(*thickness > 0.0))
      physics->expected("thickness", "a positive out-of-plane thickness");
  }

  NameRegistry material_names("material");
  const std::vector<Section> material_sections = top.array_of_tables("materials", true);
  for (const Section& m : material_sections) {
    problem.materials.push_back(
        read_material(m, thickness, problem.grid, problem.grid.cell_size / per_cell));
    material_names.add(m, problem.materials.back().name);
  }

  // Shape bodies and grain sources (image or grain file) in file order; a grain source gives one
  // body per grain, so body ids follow the file order with each source's grains in label order.
  NameRegistry entry_names("body");
  std::vector<BodyEntry> bodies;
  std::vector<GrainEntry> grain_entries;
  std::vector<std::pair<bool, std::size_t>> entry_order;  // {is grain source, index in its list}
  for (const Section& b : top.array_of_tables("bodies", true)) {
    if (is_grain_source(b)) {
      const int m = read_body_material(b, material_names);
      entry_names.add(b, b.name("name"));
      grain_entries.push_back(read_grain_entry(
          b, path, m, problem.materials[static_cast<std::size_t>(m)], problem.grid, per_cell));
      entry_order.emplace_back(true, grain_entries.size() - 1);
    } else {
      bodies.push_back(read_body(b, material_names));
      entry_names.add(b, bodies.back().name);
      entry_order.emplace_back(false, bodies.size() - 1);
    }
  }
  std::vector<std::int32_t> shape_body_id(bodies.size()), grain_first_id(grain_entries.size());
  {
    std::map<std::string, std::string>
        owner;  // body name -> entry name, for clashes with grain names
    auto add_name = [&](const std::string& name, const Section& entry) {
      if (!owner.emplace(name, entry.path()).second)
        entry.fail("name", "expected body names not used before, got body '" + name +
                               "' also defined by " + owner[name]);
      problem.body_names.push_back(name);
    };
    for (const auto& [grain, i] : entry_order) {
      if (grain) {
        grain_first_id[i] = static_cast<std::int32_t>(problem.body_names.size());
        for (const std::string& n : grain_entries[i].body_names)
          add_name(n, grain_entries[i].section);
      } else {
        shape_body_id[i] = static_cast<std::int32_t>(problem.body_names.size());
        add_name(bodies[i].name, bodies[i].section);
      }
    }
  }

  NameRegistry wall_names("wall");
  NameRegistry thermal_plane_names("wall");
  std::vector<mpm::ThermalWallCondition<2>> wall_thermal;
  for (const Section& w : top.array_of_tables("walls", false)) {
    const mpm::WallSpec<2> wall = read_wall(w);
    if (w.optional_string("kind") == std::optional<std::string>("thermal")) {
      // A plane that only carries a thermal condition: no force, not a platen, not in the series.
      if (!w.has("thermal"))
        w.fail("thermal",
               "missing required key: a wall of kind = \"thermal\" exists only to carry thermal = "
               "{ ... }");
      if (w.has("friction"))
        w.fail("friction", "expected no friction for kind = \"thermal\" (it exerts no force)");
      if (wall_names.index(wall.name) >= 0) wall_names.add(w, wall.name);  // reports the duplicate
      thermal_plane_names.add(w, wall.name);
      wall_thermal.push_back(*read_wall_thermal(w, wall));
      continue;
    }
    if (thermal_plane_names.index(wall.name) >= 0)
      thermal_plane_names.add(w, wall.name);  // duplicate
    problem.walls.push_back(wall);
    wall_names.add(w, wall.name);
    if (auto c = read_wall_thermal(w, wall)) wall_thermal.push_back(*c);
  }
  const std::optional<Section> contact = top.optional_table("contact");
  if (contact) {
    problem.contact = read_contact(*contact);
    read_contact_conductance(*contact, problem.thermal);
  }
  // An AT2 phase field approaches d = 1 only as H grows without bound (phase_field.hpp), so a
  // crack of a phase-field material becomes separable at D_cr = 0.95 unless the scene says
  // otherwise.
  const bool phase_field = std::any_of(
      problem.materials.begin(), problem.materials.end(),
      [](const mpm::MaterialSpec& m) { return std::holds_alternative<mpm::PhaseField>(m.damage); });
  if (phase_field && !(contact && contact->has("critical_damage")))
    problem.contact.critical_damage = mpm::phase_field_critical_damage;

  if (!top.has("stop"))
    top.fail("stop",
             "missing required table [stop]: expected at least one of end_time, max_steps, "
             "platen_displacement");
  read_stop(top.table("stop"), wall_names, problem.walls, problem.stop);
  read_output(top.optional_table("output"), problem.stop, problem.output);

  // Geometry: every body inside the domain, sampled on the sub-cell lattice, none empty.
  for (const BodyEntry& b : bodies) check_body_in_domain(b, problem.grid);
  std::vector<BodySample> samples;
  for (const BodyEntry& b : bodies) samples.push_back(b.sample);
  // Roller walls are bilateral (the solver removes the normal velocity both ways): a body face on
  // one is a symmetry plane of the model, not a free surface.
  std::vector<MirrorPlane> mirrors;
  for (const mpm::WallSpec<2>& w : problem.walls)
    if (w.kind == mpm::WallKind::roller) mirrors.push_back({w.point, w.normal.normalized()});
  SampleResult sampled = sample_bodies(samples, problem.materials, problem.grid, per_cell, mirrors);
  check_sampling(bodies, sampled, problem.grid.cell_size / per_cell);
  problem.particles = std::move(sampled.particles);
  for (auto& id : problem.particles.body) id = shape_body_id[static_cast<std::size_t>(id)];
  for (std::size_t g = 0; g < grain_entries.size(); ++g)
    append_particles(problem.particles, grain_entries[g].bodies.particles, grain_first_id[g]);
  assign_strengths(problem, material_sections);

  // Loads name a body, or an image/grain entry for all of its grains.
  std::map<std::string, std::vector<std::int32_t>> load_bodies;
  for (std::size_t b = 0; b < problem.body_names.size(); ++b)
    load_bodies[problem.body_names[b]].push_back(static_cast<std::int32_t>(b));
  for (std::size_t g = 0; g < grain_entries.size(); ++g)
    for (std::size_t k = 0; k < grain_entries[g].body_names.size(); ++k)
      load_bodies[grain_entries[g].name].push_back(grain_first_id[g] +
                                                   static_cast<std::int32_t>(k));
  const std::vector<Section> load_sections = top.array_of_tables("loads", false);
  for (std::size_t i = 0; i < load_sections.size(); ++i)
    if (is_heat_load(load_sections[i]))
      problem.thermal.edge_loads.push_back(
          read_heat_load(load_sections[i], i, problem, load_bodies));
    else
      problem.loads.push_back(read_load(load_sections[i], i, problem, load_bodies));
  apply_initial_cracks(problem, top.array_of_tables("cracks", false), load_bodies);
  {
    std::vector<std::optional<double>> body_temperature(problem.body_names.size());
    for (std::size_t i = 0; i < bodies.size(); ++i)
      body_temperature[static_cast<std::size_t>(shape_body_id[i])] =
          read_body_temperature(bodies[i].section);
    for (std::size_t g = 0; g < grain_entries.size(); ++g)
      for (std::size_t k = 0; k < grain_entries[g].body_names.size(); ++k)
        body_temperature[static_cast<std::size_t>(grain_first_id[g]) + k] =
            read_body_temperature(grain_entries[g].section);
    compile_thermal(problem, material_sections, body_temperature, wall_thermal);
  }
  // The phase field has no damage heating and its split does not carry the thermal stress.
  if (problem.thermal.active())
    for (std::size_t m = 0; m < problem.materials.size(); ++m)
      if (std::holds_alternative<mpm::PhaseField>(problem.materials[m].damage))
        material_sections[m].fail(
            "damage",
            "expected a damage law other than \"phase-field\" in a scene whose thermal "
            "module is on (" +
                problem.thermal.reason +
                "): the phase field has no damage heating and its tension-compression "
                "split carries no thermal stress yet");

  if (problem.plane_stress) apply_plane_stress(problem, *physics);

  if (time) check_fixed_dt(problem, *time);
  return problem;
}

mpm::Problem<2> load_scene(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw SceneError(path, 0, "", "cannot read scene file: it is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw SceneError(path, 0, "", std::string("cannot open scene file: ") + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw SceneError(path, 0, "", "cannot read scene file");
  return parse_scene(text.str(), path);
}

}  // namespace fragmpm::pipeline
