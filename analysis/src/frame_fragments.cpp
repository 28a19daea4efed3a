#include "fragmpm/analysis/frame_fragments.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "fragmpm/analysis/particle_domain.hpp"

namespace fragmpm::analysis {

FragmentSummary summarize_fragments(const mpm::Particles<2>& P, const FragmentLabels& labels) {
  FragmentSummary s;
  s.masked_particles = labels.masked;
  std::vector<double> area(labels.count(), 0.0), mass(labels.count(), 0.0);
  for (std::size_t p = 0; p < labels.fragment.size(); ++p) {
    const std::int32_t f = labels.fragment[p];
    if (f < 0) continue;
    area[static_cast<std::size_t>(f)] += particle_area(P, p);
    mass[static_cast<std::size_t>(f)] += P.mass[p];
  }
  double sum_d = 0.0, sum_md = 0.0;
  for (std::size_t f = 0; f < labels.count(); ++f) {
    if (labels.fine[f]) {
      ++s.fines;
      s.fine_particles += labels.particles[f];
      s.fines_mass += mass[f];
      s.fines_area += area[f];
      continue;
    }
    const double d = std::sqrt(4.0 * area[f] / std::numbers::pi);  // equivalent diameter
    ++s.fragments;
    sum_d += d;
    sum_md += mass[f] * d;
    s.fragment_mass += mass[f];
    s.largest_equivalent_diameter = std::max(s.largest_equivalent_diameter, d);
  }
  if (s.fragments > 0) s.mean_equivalent_diameter = sum_d / static_cast<double>(s.fragments);
  if (s.fragment_mass > 0.0) s.mass_mean_equivalent_diameter = sum_md / s.fragment_mass;
  return s;
}

FrameFragments analyze_fragments(const mpm::Particles<2>& reference,
                                 const mpm::Particles<2>& current, const FragmentOptions& options,
                                 bool raster_check, const StatisticsOptions& statistics) {
  FrameFragments out;
  out.labels = label_fragments(reference, current, options);
  out.summary = summarize_fragments(current, out.labels);
  out.has_temperature = !current.temperature.empty();
  for (FragmentStatistics& s : fragment_statistics(current, out.labels, statistics))
    (s.fine ? out.fines : out.fragments).push_back(s);
  std::vector<double> d, r, m;
  for (const FragmentStatistics& s : out.fragments) {
    d.push_back(s.equivalent_diameter);
    r.push_back(s.roundness);
    m.push_back(s.mass);
  }
  if (!out.fragments.empty()) {
    // Fragments without mass (a frame without the mass field) are weighted by area instead, so the
    // mass-weighted CDF is still defined; with uniform density the two coincide.
    double total = 0.0;
    for (const double w : m) total += w;
    if (!(total > 0.0))
      for (std::size_t k = 0; k < m.size(); ++k) m[k] = out.fragments[k].area;
    out.equivalent_diameter = empirical_cdf(d, m);
    out.roundness = empirical_cdf(r, m);
  }
  if (raster_check) {
    try {
      const RasterLabels raster = raster_fragments(current, out.labels);
      out.raster = compare_labellings(out.labels, raster);
      out.raster_pixel_size = raster.raster.pixel_size;
      out.raster_checked = true;
    } catch (const std::invalid_argument& e) {
      out.raster_note = e.what();
    }
  }
  return out;
}

}  // namespace fragmpm::analysis
