// Series plots of a run file (see series_figures.hpp).
#include "fragmpm/analysis/series_figures.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string_view>

#include "fragmpm/analysis/figure_error.hpp"
#include "fragmpm/analysis/si_format.hpp"
#include "fragmpm/mpm/run_file_reader.hpp"

namespace fragmpm::analysis {

namespace {

double largest_magnitude(const std::vector<LineSeries>& series, bool x) {
  double m = 0.0;
  for (const LineSeries& s : series)
    for (double v : x ? s.x : s.y) m = std::max(m, std::abs(v));
  return m;
}

/// Rescales x (or y) of every series to a common SI prefix; returns the prefixed unit.
std::string rescale(std::vector<LineSeries>& series, bool x, const std::string& unit) {
  const SiPrefix p = si_prefix(largest_magnitude(series, x));
  for (LineSeries& s : series)
    for (double& v : x ? s.x : s.y) v *= p.factor;
  return p.prefix + unit;
}

/// Magnitudes of the rows of a steps × 2 dataset.
std::vector<double> row_norms(const std::vector<double>& flat) {
  std::vector<double> out(flat.size() / 2);
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = std::hypot(flat[2 * i], flat[2 * i + 1]);
  return out;
}

/// Runs longer than this many steps are plotted as window means (see WindowMeans).
constexpr std::size_t max_plotted_rows = 1000;
constexpr std::size_t plotted_windows = 400;

/// Step forces of a wall are impulses over Δt: a step shortened to land on an output time, or the
/// step in which the wall plane passes a row of grid nodes and their velocities are projected at
/// once, shows as a spike of |J|/Δt many times the mean force (a 5 µm-cell crush gave 1.4 MN/m
/// spikes over a 0.01 MN/m mean). The mean force over a window, Σ F Δt / Σ Δt = impulse / duration,
/// is what a load cell reads; the wall position is averaged the same way. Windows are equal slices
/// of the run time.
struct WindowMeans {
  std::vector<std::size_t> window;  ///< window of each row
  std::vector<double> weight;       ///< Δt of each row
  std::size_t count = 0;
  std::vector<double> operator()(const std::vector<double>& values) const {
    std::vector<double> sum(count, 0.0), total(count, 0.0);
    for (std::size_t i = 0; i < values.size(); ++i) {
      sum[window[i]] += values[i] * weight[i];
      total[window[i]] += weight[i];
    }
    std::vector<double> out;
    for (std::size_t w = 0; w < count; ++w)
      if (total[w] > 0) out.push_back(sum[w] / total[w]);
    return out;
  }
};

/// Window means for a long run; nullopt for a short one (every step plotted) or a run without Δt.
std::optional<WindowMeans> window_means(const mpm::RunSeries& run, std::size_t rows) {
  if (rows <= max_plotted_rows) return std::nullopt;
  const std::vector<double>& time = run.column("time");
  const std::vector<double>& dt = run.column("dt");
  if (time.size() != rows || dt.size() != rows) return std::nullopt;
  const double t0 = time.front() - dt.front(), span = time.back() - t0;
  if (!(span > 0)) return std::nullopt;
  WindowMeans m;
  m.count = plotted_windows;
  m.weight = dt;
  for (std::size_t i = 0; i < rows; ++i) {
    const double u = (time[i] - 0.5 * dt[i] - t0) / span;  // the middle of the step
    m.window.push_back(std::min(plotted_windows - 1,
                                static_cast<std::size_t>(std::max(0.0, u) * plotted_windows)));
  }
  return m;
}

}  // namespace

PlotSpec energy_plot_spec(const mpm::RunSeries& run) {
  const std::string& run_path = run.source;
  const std::vector<double>& time = run.column("time");
  if (time.empty())
    throw FigureError(run_path + ": /series has no rows yet (no step was recorded)");
  PlotSpec spec;
  spec.title = "Energy balance";
  // Every term of the balance (docs/design.md §2.4) that the run has: the stores, the losses, the
  // work put in, then the error. A term that only some scenes have (the crack energy of a phase
  // field, the work of loads or gravity, crushed flow) is drawn when it is not zero throughout, so
  // that no part of the balance is left off the figure and no flat zero line is added.
  struct Column {
    const char* name;
    const char* label;
    bool only_when_nonzero;
    bool may_be_absent;  ///< booked after run files existed without it
  };
  const Column columns[] = {{"kinetic", "kinetic", false, false},
                            {"strain", "strain", false, false},
                            {"fracture_energy", "crack energy (phase field)", true, true},
                            {"dissipated", "dissipated (damage)", false, false},
                            {"flow_dissipation", "crushed flow", true, true},
                            {"friction_work", "friction work", false, false},
                            {"contact_dissipation", "contact loss", false, true},
                            {"transfer_dissipation", "transfer loss", false, true},
                            {"wall_work", "wall work", false, false},
                            {"load_work", "load work", true, false},
                            {"gravity_work", "gravity work", true, false},
                            {"history_excess", "history excess (phase field, put in)", true, true},
                            {"balance_error", "balance error", false, false}};
  for (const Column& c : columns) {
    if (c.may_be_absent && !run.has(c.name)) continue;
    if (c.only_when_nonzero) {
      const std::vector<double>& values = run.column(c.name);
      if (std::all_of(values.begin(), values.end(), [](double e) { return e == 0.0; })) continue;
    }
    LineSeries s;
    s.label = c.label;
    s.x = time;
    s.y = run.column(c.name);
    if (s.y.size() != time.size())
      throw FigureError(fmt::format("{}: /series/{} has {} rows but /series/time has {}", run_path,
                                    c.name, s.y.size(), time.size()));
    spec.series.push_back(std::move(s));
  }
  // What particles removed after leaving the domain carried out, when some did: without it the
  // kinetic energy drops at a removal with nothing to show where it went.
  if (run.has("lost_kinetic") && run.has("lost_strain")) {
    LineSeries s;
    s.label = "left the domain";
    s.x = time;
    s.y = run.column("lost_kinetic");
    const std::vector<double>& strain = run.column("lost_strain");
    if (s.y.size() == time.size() && strain.size() == time.size() &&
        s.y.back() + strain.back() > 0) {
      for (std::size_t k = 0; k < s.y.size(); ++k) s.y[k] += strain[k];
      spec.series.insert(spec.series.end() - 1, std::move(s));  // before the balance error
    }
  }
  spec.x_label = fmt::format("time [{}]", rescale(spec.series, true, "s"));
  spec.y_label = fmt::format("energy [{}]", rescale(spec.series, false, "J/m"));
  return spec;
}

PlotSpec force_displacement_spec(const mpm::RunSeries& run,
                                 const std::vector<std::string>& wall_names) {
  const std::string& run_path = run.source;
  if (wall_names.empty())
    throw FigureError(run_path + ": the run has no walls, so no force-displacement curve");
  std::vector<std::vector<double>> force, travel;
  for (const std::string& w : wall_names) {
    force.push_back(row_norms(run.column(mpm::RunSeries::wall_force(w))));
    travel.push_back(row_norms(run.column(mpm::RunSeries::wall_displacement(w))));
    if (force.back().size() != travel.back().size())
      throw FigureError(fmt::format("{}: wall '{}' has {} force rows but {} displacement rows",
                                    run_path, w, force.back().size(), travel.back().size()));
  }
  if (force.front().empty())
    throw FigureError(run_path + ": /series has no rows yet (no step was recorded)");
  std::string averaged;
  if (const std::optional<WindowMeans> means = window_means(run, force.front().size())) {
    for (auto& f : force) f = (*means)(f);
    for (auto& u : travel) u = (*means)(u);
    const std::vector<double>& time = run.column("time");
    averaged = fmt::format(
        " (means over {} windows)",
        format_si((time.back() - time.front()) / static_cast<double>(plotted_windows), "s", 2));
  }
  std::size_t mover = 0;
  double farthest = 0.0;
  for (std::size_t i = 0; i < travel.size(); ++i) {
    const double m = *std::max_element(travel[i].begin(), travel[i].end());
    if (m > farthest) farthest = m, mover = i;
  }
  PlotSpec spec;
  if (farthest == 0.0) {
    // No wall moves (an impact on a fixed wall): a force-displacement curve would be a vertical
    // line, so the reactions are shown against time instead.
    std::vector<double> time = run.column("time");
    if (!averaged.empty()) time = window_means(run, time.size()).value()(time);
    spec.title = "Wall reaction forces (no wall moves)" + averaged;
    for (std::size_t i = 0; i < wall_names.size(); ++i) {
      if (force[i].size() != time.size())
        throw FigureError(fmt::format("{}: wall '{}' has {} force rows but /series/time has {}",
                                      run_path, wall_names[i], force[i].size(), time.size()));
      spec.series.push_back(LineSeries{wall_names[i], time, force[i], false});
    }
    spec.x_label = fmt::format("time [{}]", rescale(spec.series, true, "s"));
    spec.y_label = fmt::format("reaction force |F| [{}]", rescale(spec.series, false, "N/m"));
    return spec;
  }
  spec.title = "Force - displacement of the walls" + averaged;
  for (std::size_t i = 0; i < wall_names.size(); ++i) {
    LineSeries s;
    const bool moves = *std::max_element(travel[i].begin(), travel[i].end()) > 0.0;
    s.label =
        moves ? wall_names[i] : fmt::format("{} (vs {} travel)", wall_names[i], wall_names[mover]);
    s.x = moves ? travel[i] : travel[mover];
    s.y = force[i];
    spec.series.push_back(std::move(s));
  }
  spec.x_label = fmt::format("wall displacement |u| [{}]", rescale(spec.series, true, "m"));
  spec.y_label = fmt::format("reaction force |F| [{}]", rescale(spec.series, false, "N/m"));
  return spec;
}

PlotSpec energy_plot_spec(const std::string& run_path) {
  return energy_plot_spec(mpm::RunFileReader::open(run_path).read_series());
}

PlotSpec force_displacement_spec(const std::string& run_path,
                                 const std::vector<std::string>& wall_names) {
  return force_displacement_spec(mpm::RunFileReader::open(run_path).read_series(), wall_names);
}

}  // namespace fragmpm::analysis
