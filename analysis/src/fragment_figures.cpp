#include "fragmpm/analysis/fragment_figures.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "fragmpm/analysis/figure_error.hpp"
#include "fragmpm/analysis/si_format.hpp"

namespace fragmpm::analysis {

namespace {

/// Scales every x (or y) of the series to one SI prefix of `unit`; returns the prefixed unit.
std::string rescale(std::vector<LineSeries>& series, bool x, const std::string& unit) {
  double largest = 0.0;
  for (const LineSeries& s : series)
    for (const double v : x ? s.x : s.y) largest = std::max(largest, std::abs(v));
  const SiPrefix p = si_prefix(largest);
  for (LineSeries& s : series)
    for (double& v : x ? s.x : s.y) v *= p.factor;
  return p.prefix + unit;
}

constexpr std::size_t kMarkerLimit = 30;  // draw markers on series with few points

}  // namespace

PlotSpec cdf_plot_spec(std::span<const CdfCurve> curves, CdfQuantity quantity,
                       CdfWeighting weighting) {
  const bool diameter = quantity == CdfQuantity::equivalent_diameter;
  const bool mass = weighting == CdfWeighting::mass;
  PlotSpec spec;
  spec.title = fmt::format("{} of fragments, {}", diameter ? "Equivalent diameter" : "Roundness",
                           mass ? "mass-weighted" : "by number");
  for (const CdfCurve& c : curves) {
    if (c.cdf.value.empty()) continue;
    // Empirical CDF as a staircase: F jumps at each value, starting from 0.
    LineSeries s;
    s.label = c.label;
    const auto& F = mass ? c.cdf.mass_fraction : c.cdf.number_fraction;
    double previous = 0.0;
    for (std::size_t k = 0; k < c.cdf.value.size(); ++k) {
      s.x.push_back(c.cdf.value[k]);
      s.y.push_back(previous);
      s.x.push_back(c.cdf.value[k]);
      s.y.push_back(F[k]);
      previous = F[k];
    }
    spec.series.push_back(std::move(s));
  }
  if (spec.series.empty())
    throw FigureError("CDF figure: no analysed frame has a resolved fragment");
  spec.x_label = diameter ? fmt::format("equivalent diameter [{}]", rescale(spec.series, true, "m"))
                          : std::string("roundness (ImageJ: minor / major axis)");
  spec.y_label = mass ? "cumulative mass fraction" : "cumulative number fraction";
  return spec;
}

PlotSpec fragment_count_spec(std::span<const FragmentSeriesPoint> points) {
  if (points.empty()) throw FigureError("fragment count figure: no frames");
  PlotSpec spec;
  spec.title = "Fragments against time";
  LineSeries resolved{"resolved fragments", {}, {}, points.size() <= kMarkerLimit};
  LineSeries fines{"fines", {}, {}, points.size() <= kMarkerLimit};
  for (const FragmentSeriesPoint& p : points) {
    resolved.x.push_back(p.time);
    resolved.y.push_back(static_cast<double>(p.summary.fragments));
    fines.x.push_back(p.time);
    fines.y.push_back(static_cast<double>(p.summary.fines));
  }
  spec.series = {resolved, fines};
  spec.x_label = fmt::format("time [{}]", rescale(spec.series, true, "s"));
  spec.y_label = "number of fragments";
  return spec;
}

PlotSpec fragment_size_spec(std::span<const FragmentSeriesPoint> points) {
  PlotSpec spec;
  spec.title = "Fragment size against time";
  std::size_t n = 0;
  for (const FragmentSeriesPoint& p : points) n += p.summary.fragments > 0 ? 1 : 0;
  const bool markers = n <= kMarkerLimit;
  LineSeries mean{"mean (by number)", {}, {}, markers};
  LineSeries mass{"mean (mass-weighted)", {}, {}, markers};
  LineSeries largest{"largest fragment", {}, {}, markers};
  for (const FragmentSeriesPoint& p : points) {
    if (p.summary.fragments == 0) continue;
    for (LineSeries* s : {&mean, &mass, &largest}) s->x.push_back(p.time);
    mean.y.push_back(p.summary.mean_equivalent_diameter);
    mass.y.push_back(p.summary.mass_mean_equivalent_diameter);
    largest.y.push_back(p.summary.largest_equivalent_diameter);
  }
  if (mean.x.empty()) throw FigureError("fragment size figure: no frame has a resolved fragment");
  spec.series = {mean, mass, largest};
  spec.x_label = fmt::format("time [{}]", rescale(spec.series, true, "s"));
  spec.y_label = fmt::format("equivalent diameter [{}]", rescale(spec.series, false, "m"));
  return spec;
}

}  // namespace fragmpm::analysis
