// Particle domains drawn with OpenCV and the raster cross-check of the fragment labelling.
#include "fragmpm/analysis/fragment_raster.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <opencv2/imgproc.hpp>
#include <set>
#include <stdexcept>

#include "fragmpm/analysis/particle_domain.hpp"

namespace fragmpm::analysis {

namespace {
constexpr int kShift = 8;  // fillConvexPoly sub-pixel bits
constexpr double kMaxPixels = 2e8;
}  // namespace

ParticleRaster draw_particle_domains(const mpm::Particles<2>& P,
                                     std::span<const std::size_t> subset, double pixel_size,
                                     int pad_pixels) {
  if (!(pixel_size > 0.0) || !std::isfinite(pixel_size))
    throw std::invalid_argument(
        fmt::format("raster pixel size must be positive, got {}", pixel_size));
  if (subset.empty()) throw std::invalid_argument("no particles to draw");
  pad_pixels = std::max(pad_pixels, 0);
  double xmin = INFINITY, ymin = INFINITY, xmax = -INFINITY, ymax = -INFINITY;
  for (const std::size_t p : subset)
    for (const auto& c : particle_corners(P, p)) {
      xmin = std::min(xmin, c(0));
      xmax = std::max(xmax, c(0));
      ymin = std::min(ymin, c(1));
      ymax = std::max(ymax, c(1));
    }
  if (!std::isfinite(xmin + xmax + ymin + ymax))
    throw std::invalid_argument("particle domains are not finite");
  const double cols = std::ceil((xmax - xmin) / pixel_size) + 2.0 * pad_pixels;
  const double rows = std::ceil((ymax - ymin) / pixel_size) + 2.0 * pad_pixels;
  if (cols * rows > kMaxPixels)
    throw std::invalid_argument(
        fmt::format("a raster of {:.0f} x {:.0f} pixels at {:.4g} m per pixel is too large (limit "
                    "{:.0e} pixels)",
                    cols, rows, pixel_size, kMaxPixels));
  ParticleRaster r;
  r.pixel_size = pixel_size;
  r.x0 = xmin - pad_pixels * pixel_size;
  r.y0 = ymin - pad_pixels * pixel_size;
  r.mask = cv::Mat::zeros(static_cast<int>(rows), static_cast<int>(cols), CV_8UC1);
  // fillConvexPoly draws the polygon closed, with vertices rounded to pixel centres: a pixel whose
  // centre is within half a pixel of the polygon is filled. Each domain is inset by half a pixel
  // first, so a pixel is (up to rounding) filled when its centre lies in the domain, and domains
  // that share an edge tile the raster without gaps or double cover. A domain thinner than a pixel
  // collapses to its centre line and still marks the pixels along it.
  const double delta = 0.5 * pixel_size;
  const double scale = static_cast<double>(1 << kShift) / pixel_size;
  cv::Point vertices[4];
  for (const std::size_t p : subset) {
    const auto c = particle_corners(P, p);
    const mpm::Vec<2> r1 = c[1] - c[0], r2 = c[3] - c[0];
    const double area = std::abs(r1(0) * r2(1) - r1(1) * r2(0));
    const double n1 = r1.norm(), n2 = r2.norm();
    // Sides parallel to r2 are area/|r2| apart; insetting both by δ scales r1 by (1 − 2δ|r2|/area).
    const double f1 = area > 0.0 ? std::max(0.0, 1.0 - 2.0 * delta * n2 / area) : 0.0;
    const double f2 = area > 0.0 ? std::max(0.0, 1.0 - 2.0 * delta * n1 / area) : 0.0;
    const mpm::Vec<2> centre = 0.25 * (c[0] + c[1] + c[2] + c[3]);
    const mpm::Vec<2> a = 0.5 * f1 * r1, b = 0.5 * f2 * r2;
    const mpm::Vec<2> corners[4] = {centre - a - b, centre + a - b, centre + a + b, centre - a + b};
    for (int k = 0; k < 4; ++k) {
      // Continuous pixel coordinate u = (x − x0)/s has pixel centres at integer + ½; OpenCV puts
      // them at integers.
      const double u = (corners[k](0) - r.x0) * scale - 0.5 * (1 << kShift);
      const double v = (corners[k](1) - r.y0) * scale - 0.5 * (1 << kShift);
      vertices[k] = cv::Point(static_cast<int>(std::lround(u)), static_cast<int>(std::lround(v)));
    }
    cv::fillConvexPoly(r.mask, vertices, 4, cv::Scalar(255), cv::LINE_8, kShift);
  }
  return r;
}

cv::Point raster_pixel(const ParticleRaster& r, double x, double y) {
  const double col = std::floor((x - r.x0) / r.pixel_size);
  const double row = std::floor((y - r.y0) / r.pixel_size);
  if (!(col >= 0 && row >= 0 && col < r.mask.cols && row < r.mask.rows)) return {-1, -1};
  return {static_cast<int>(col), static_cast<int>(row)};
}

double default_raster_pixel_size(const mpm::Particles<2>& P, const FragmentLabels& labels) {
  std::vector<double> spacing;
  for (std::size_t p = 0; p < labels.fragment.size(); ++p)
    if (labels.fragment[p] >= 0) spacing.push_back(particle_spacing(P, p));
  if (spacing.empty()) return 0.0;
  auto mid = spacing.begin() + static_cast<std::ptrdiff_t>(spacing.size() / 2);
  std::nth_element(spacing.begin(), mid, spacing.end());
  return 0.25 * *mid;
}

RasterLabels raster_fragments(const mpm::Particles<2>& P, const FragmentLabels& labels,
                              double pixel_size) {
  RasterLabels out;
  out.component.assign(labels.fragment.size(), -1);
  std::vector<std::size_t> subset;
  for (std::size_t p = 0; p < labels.fragment.size(); ++p)
    if (labels.fragment[p] >= 0) subset.push_back(p);
  if (subset.empty()) return out;
  if (!(pixel_size > 0.0)) pixel_size = default_raster_pixel_size(P, labels);
  out.raster = draw_particle_domains(P, subset, pixel_size);
  out.count = cv::connectedComponents(out.raster.mask, out.components, 4, CV_32S) - 1;
  for (const std::size_t p : subset) {
    const cv::Point px = raster_pixel(out.raster, P.x[p](0), P.x[p](1));
    if (px.x < 0) continue;
    const std::int32_t c = out.components.at<std::int32_t>(px);
    out.component[p] = c > 0 ? c : -1;
  }
  return out;
}

std::string LabellingComparison::summary() const {
  if (agree()) return fmt::format("raster and graph agree: {} fragments", graph_fragments);
  return fmt::format(
      "raster: {} connected components, graph: {} fragments ({} components join several fragments, "
      "e.g. "
      "pieces pressed together; {} fragments split in the raster; {} components hold no particle "
      "centre)",
      raster_components, graph_fragments, merged, split, empty);
}

LabellingComparison compare_labellings(const FragmentLabels& graph, const RasterLabels& raster) {
  LabellingComparison c;
  c.graph_fragments = graph.count();
  c.raster_components = static_cast<std::size_t>(raster.count);
  std::vector<std::set<std::int32_t>> components_of(graph.count());
  std::map<std::int32_t, std::set<std::int32_t>> fragments_of;
  for (std::size_t p = 0; p < graph.fragment.size(); ++p) {
    const std::int32_t f = graph.fragment[p];
    if (f < 0) continue;
    // A centre outside every drawn pixel (cannot happen for a drawn domain, but rounding) counts
    // as its own component −1, which makes the fragment "split" if it has other components.
    const std::int32_t k = p < raster.component.size() ? raster.component[p] : -1;
    components_of[static_cast<std::size_t>(f)].insert(k);
    fragments_of[k].insert(f);
  }
  for (const auto& s : components_of) c.split += s.size() > 1 ? 1 : 0;
  for (const auto& [k, s] : fragments_of) c.merged += (k > 0 && s.size() > 1) ? 1 : 0;
  for (std::int32_t k = 1; k <= raster.count; ++k) c.empty += fragments_of.count(k) ? 0 : 1;
  return c;
}

}  // namespace fragmpm::analysis
