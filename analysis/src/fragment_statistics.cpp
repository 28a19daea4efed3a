#include "fragmpm/analysis/fragment_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "fragmpm/analysis/convex_hull_measures.hpp"
#include "fragmpm/analysis/fragment_raster.hpp"
#include "fragmpm/analysis/particle_domain.hpp"
#include "fragmpm/analysis/region_shape.hpp"

namespace fragmpm::analysis {

namespace {

double median_spacing(const mpm::Particles<2>& P, std::span<const std::size_t> members) {
  std::vector<double> s;
  s.reserve(members.size());
  for (const std::size_t p : members) s.push_back(particle_spacing(P, p));
  auto mid = s.begin() + static_cast<std::ptrdiff_t>(s.size() / 2);
  std::nth_element(s.begin(), mid, s.end());
  return *mid;
}

double raster_perimeter(const mpm::Particles<2>& P, std::span<const std::size_t> members,
                        double pixel_size, double smoothing) {
  const double sigma = smoothing / pixel_size;  // [pixels]
  ParticleRaster r =
      draw_particle_domains(P, members, pixel_size, 3 + static_cast<int>(std::ceil(3.0 * sigma)));
  cv::Mat blurred;
  r.mask.convertTo(blurred, CV_32F, 1.0 / 255.0);
  if (sigma > 0.0)
    cv::GaussianBlur(blurred, blurred, cv::Size(0, 0), sigma, sigma, cv::BORDER_CONSTANT);
  cv::Mat labels = cv::Mat::zeros(blurred.size(), CV_32S);
  labels.setTo(1, blurred >= 0.5f);
  // One label for the whole fragment (its raster may be in pieces if domains moved apart without
  // the bond being cut): the perimeter is that of all its pixels.
  const auto regions = label_region_shapes(labels, pixel_size);
  return regions.empty() ? 0.0 : regions.front().shape.perimeter;
}

}  // namespace

FragmentStatistics fragment_statistics(const mpm::Particles<2>& P,
                                       std::span<const std::size_t> members,
                                       const StatisticsOptions& options) {
  FragmentStatistics s;
  s.particles = static_cast<std::int64_t>(members.size());
  if (members.empty()) return s;
  RegionMoments moments;
  std::vector<Eigen::Vector2d> corners;
  corners.reserve(4 * members.size());
  double mass = 0.0, mvx = 0.0, mvy = 0.0, mtheta = 0.0;
  const bool thermal = !P.temperature.empty();
  for (const std::size_t p : members) {
    const auto c = particle_corners(P, p);
    const mpm::Vec<2> r1 = c[1] - c[0], r2 = c[3] - c[0];
    ShapeCell cell = parallelogram_cell(P.x[p](0), P.x[p](1), r1(0), r1(1), r2(0), r2(1));
    cell.area = particle_area(P, p);  // the mass's area; the domain gives the shape of its moments
    moments.add(cell);
    for (const auto& k : c) corners.emplace_back(k(0), k(1));
    const double m = P.mass[p];
    mass += m;
    mvx += m * P.v[p](0);
    mvy += m * P.v[p](1);
    if (thermal) mtheta += m * P.temperature[p];
  }
  const double spacing = median_spacing(P, members);
  const double pixel = spacing / options.perimeter_pixels_per_spacing;
  const RegionShape shape = region_shape(
      moments, raster_perimeter(P, members, pixel, options.perimeter_smoothing * spacing));
  s.area = shape.area;
  s.equivalent_diameter = shape.equivalent_diameter;
  s.roundness = shape.roundness;
  s.aspect_ratio = shape.aspect_ratio;
  s.major_axis = shape.major_axis;
  s.minor_axis = shape.minor_axis;
  s.orientation = shape.orientation;
  s.perimeter = shape.perimeter;
  s.centroid_x = shape.centroid_x;
  s.centroid_y = shape.centroid_y;
  const ConvexMeasures hull = convex_hull_measures(corners);
  s.convex_area = hull.hull_area;
  s.solidity = hull.hull_area > 0.0 ? std::min(1.0, s.area / hull.hull_area) : 1.0;
  s.feret_max = hull.feret_max;
  s.feret_min = hull.feret_min;
  s.mass = mass;
  if (mass > 0.0) {
    s.velocity_x = mvx / mass;
    s.velocity_y = mvy / mass;
    if (thermal) s.temperature = mtheta / mass;
  }
  return s;
}

std::vector<FragmentStatistics> fragment_statistics(const mpm::Particles<2>& P,
                                                    const FragmentLabels& labels,
                                                    const StatisticsOptions& options) {
  const auto members = fragment_members(labels);
  std::vector<FragmentStatistics> out(members.size());
#pragma omp parallel for schedule(dynamic)
  for (std::size_t f = 0; f < members.size(); ++f) {
    out[f] = fragment_statistics(P, members[f], options);
    out[f].id = static_cast<std::int32_t>(f);
    out[f].fine = labels.fine[f] != 0;
  }
  return out;
}

}  // namespace fragmpm::analysis
