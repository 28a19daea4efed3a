// Run-file reading and frame selection for `fragmpm analyze` (see analyze_frames.hpp).
#include "analyze_frames.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>

#include "fragmpm/analysis/si_format.hpp"
#include "fragmpm/pipeline/units.hpp"

namespace fragmpm::pipeline::analyze_detail {

namespace {

std::string list(const std::vector<std::string>& names) {
  return names.empty() ? std::string("none") : fmt::format("{}", fmt::join(names, ", "));
}

std::string frame_range(const RunIndex& run) {
  const FrameInfo& a = run.frames.front();
  const FrameInfo& b = run.frames.back();
  return fmt::format("{} frames, {} (t = {}) to {} (t = {})", run.frames.size(), a.index,
                     analysis::format_si(a.time, "s", 4), b.index,
                     analysis::format_si(b.time, "s", 4));
}

/// Position of the frame nearest to `target` among `values` (one per frame); AnalyzeError when
/// `target` lies more than half a mean frame interval outside their range.
std::size_t nearest(const std::vector<double>& values, double target, const std::string& what,
                    const std::string& available) {
  const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
  const double span = *hi - *lo;
  const double tolerance = values.size() > 1 ? 0.5 * span / double(values.size() - 1)
                                             : 1e-9 * std::max(std::abs(*hi), 1e-30);
  if (!(target >= *lo - tolerance && target <= *hi + tolerance))
    throw AnalyzeError(fmt::format("no frame near {}: {}", what, available));
  std::size_t best = 0;
  for (std::size_t k = 1; k < values.size(); ++k)
    if (std::abs(values[k] - target) < std::abs(values[best] - target)) best = k;
  return best;
}

/// True when `text` is a number with no unit after it ("20", "1e-5").
bool is_bare_number(const std::string& text) {
  char* end = nullptr;
  std::strtod(text.c_str(), &end);
  if (end == text.c_str()) return false;
  return std::all_of(static_cast<const char*>(end), text.c_str() + text.size(),
                     [](unsigned char c) { return std::isspace(c); });
}

}  // namespace

std::string frame_group(int index) {
  return fmt::format("/frames/{:06d}", index);
}

RunIndex read_run_index(const mpm::RunFileReader& file) {
  const std::string& path = file.path();
  if (file.dimension() != 2)
    throw AnalyzeError(
        fmt::format("{}: a {}D run; fragment analysis handles 2D runs", path, file.dimension()));
  RunIndex run;
  run.path = path;
  run.walls = file.wall_names();
  run.frames = file.frames();
  if (run.frames.empty()) throw AnalyzeError(path + ": the run has no frames yet");
  return run;
}

mpm::Particles<2> read_analysis_frame(const mpm::RunFileReader& file, const RunIndex& run,
                                      int index) {
  const std::string name = frame_group(index);
  const mpm::FrameEntry* frame = file.find_frame(index);
  for (const char* field : {"damage", "volume0"})
    if (frame && !frame->has(field))
      throw AnalyzeError(
          fmt::format("{}: {} has no '{}' dataset: the run was written without {} data, so its "
                      "fragments cannot be "
                      "found (list \"{}\" in the scene's output fields and run it again)",
                      run.path, name, field,
                      field == std::string("damage") ? "damage" : "reference volume", field));
  return file.read_frame<2>(index);
}

std::vector<std::string> platen_series(const RunIndex& run) {
  std::vector<std::string> names{"time", "step"};
  for (const std::string& w : run.walls) names.push_back(mpm::RunSeries::wall_displacement(w));
  return names;
}

std::string choose_platen(const mpm::RunSeries& series, const RunIndex& run,
                          const std::string& requested, std::vector<std::string>& moving) {
  moving.clear();
  for (const std::string& w : run.walls) {
    const std::string name = mpm::RunSeries::wall_displacement(w);
    if (!series.has(name)) continue;
    const std::vector<double>& u = series.column(name);
    for (std::size_t k = 0; k + 1 < u.size(); k += 2)
      if (std::hypot(u[k], u[k + 1]) > 0.0) {
        moving.push_back(w);
        break;
      }
  }
  if (!requested.empty()) {
    if (std::find(run.walls.begin(), run.walls.end(), requested) == run.walls.end())
      throw AnalyzeError(fmt::format("--platen '{}': the run has no such wall (its walls: {})",
                                     requested, list(run.walls)));
    return requested;
  }
  return moving.size() == 1 ? moving.front() : std::string();
}

std::vector<double> platen_travel(const mpm::RunSeries& series, const RunIndex& run,
                                  const std::string& wall) {
  const std::string name = mpm::RunSeries::wall_displacement(wall);
  if (!series.has(name) || !series.has("time") || !series.has("step"))
    throw AnalyzeError(fmt::format("{}: /series/{} (with /series/time and /series/step) is missing",
                                   run.path, name));
  const std::vector<double>& u = series.column(name);
  const std::vector<double>& time = series.column("time");
  std::vector<std::int64_t> step;
  for (const double s : series.column("step")) step.push_back(static_cast<std::int64_t>(s));
  const std::size_t rows = std::min({u.size() / 2, time.size(), step.size()});
  if (rows == 0) throw AnalyzeError(fmt::format("{}: /series/{} has no rows", run.path, name));
  std::vector<double> travel(rows);
  for (std::size_t k = 0; k < rows; ++k) travel[k] = std::hypot(u[2 * k], u[2 * k + 1]);
  std::map<std::int64_t, std::size_t> row_of_step;
  for (std::size_t k = 0; k < rows; ++k) row_of_step[step[k]] = k;
  std::vector<double> out;
  for (const FrameInfo& f : run.frames) {
    if (const auto it = row_of_step.find(f.step); it != row_of_step.end()) {
      out.push_back(travel[it->second]);
      continue;
    }
    // No row for this step: interpolate linearly in time (clamped at the ends).
    const auto hi =
        std::lower_bound(time.begin(), time.begin() + static_cast<std::ptrdiff_t>(rows), f.time);
    if (hi == time.begin())
      out.push_back(travel.front());
    else if (hi == time.begin() + static_cast<std::ptrdiff_t>(rows))
      out.push_back(travel[rows - 1]);
    else {
      const std::size_t b = static_cast<std::size_t>(hi - time.begin()), a = b - 1;
      const double w = time[b] > time[a] ? (f.time - time[a]) / (time[b] - time[a]) : 1.0;
      out.push_back((1.0 - w) * travel[a] + w * travel[b]);
    }
  }
  return out;
}

std::vector<Selected> select_frames(const AnalyzeOptions& o, const RunIndex& run,
                                    const std::vector<double>& travel,
                                    const std::vector<std::string>& moving) {
  std::vector<Selected> picked;
  std::vector<double> times;
  for (const FrameInfo& f : run.frames) times.push_back(f.time);
  auto by_displacement = [&](double u, const std::string& text, const std::string& request) {
    if (travel.empty())
      throw AnalyzeError(fmt::format(
          "{} '{}' is a platen displacement, but {}; give --platen NAME (walls of this run: {})",
          request, text,
          moving.empty() ? "no wall of this run moves"
                         : "several walls move (" + list(moving) + ")",
          list(run.walls)));
    if (!(u >= 0.0))
      throw AnalyzeError(fmt::format("{} '{}': a platen displacement is a distance travelled, >= 0",
                                     request, text));
    const auto [lo, hi] = std::minmax_element(travel.begin(), travel.end());
    const std::size_t k =
        nearest(travel, u, fmt::format("platen displacement {}", analysis::format_si(u, "m", 4)),
                fmt::format("the platen travelled {} to {} between the first and last frame",
                            analysis::format_si(*lo, "m", 4), analysis::format_si(*hi, "m", 4)));
    picked.push_back({k, fmt::format("{} {}", request, text)});
  };
  for (const std::string& text : o.at) {
    if (is_bare_number(text))
      throw AnalyzeError(fmt::format(
          "--at '{}': give a unit, a time (e.g. 20us) or a platen displacement (e.g. 0.8mm)",
          text));
    try {
      const double t = parse_quantity(text, QuantityKind::time);
      const std::size_t k = nearest(times, t, fmt::format("t = {}", analysis::format_si(t, "s", 4)),
                                    "the run has " + frame_range(run));
      picked.push_back({k, "--at " + text});
      continue;
    } catch (const UnitError&) {
    }
    double u = 0.0;
    try {
      u = parse_quantity(text, QuantityKind::length);
    } catch (const UnitError& e) {
      throw AnalyzeError(fmt::format(
          "--at '{}': expected a time (e.g. 20us) or a platen displacement (e.g. 0.8mm): {}", text,
          e.what()));
    }
    by_displacement(u, text, "--at");
  }
  for (const std::string& text : o.at_displacement) {
    double u = 0.0;
    try {
      u = parse_quantity(text, QuantityKind::length);
    } catch (const UnitError& e) {
      throw AnalyzeError(fmt::format("--at-displacement '{}': {}", text, e.what()));
    }
    by_displacement(u, text, "--at-displacement");
  }
  for (const std::string& text : o.frames) {
    int index = 0;
    if (text == "last")
      index = run.frames.back().index;
    else if (text == "first")
      index = run.frames.front().index;
    else {
      std::size_t used = 0;
      try {
        index = std::stoi(text, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used == 0 || used != text.size())
        throw AnalyzeError(
            fmt::format("--frame '{}': expected a frame index, 'first' or 'last'", text));
    }
    const auto it = std::find_if(run.frames.begin(), run.frames.end(),
                                 [&](const FrameInfo& f) { return f.index == index; });
    if (it == run.frames.end())
      throw AnalyzeError(fmt::format("{}: no frame {} ({} does not exist; the run has {})",
                                     run.path, index, frame_group(index), frame_range(run)));
    picked.push_back({static_cast<std::size_t>(it - run.frames.begin()), "--frame " + text});
  }
  if (o.at.empty() && o.at_displacement.empty() && o.frames.empty()) {
    // Default: the frames nearest to 1/4, 1/2, 3/4 and all of the run's last frame time.
    const double t0 = times.front(), t1 = times.back();
    for (const double f : {0.25, 0.5, 0.75, 1.0}) {
      const double t = t0 + f * (t1 - t0);
      std::size_t best = 0;
      for (std::size_t k = 1; k < times.size(); ++k)
        if (std::abs(times[k] - t) < std::abs(times[best] - t)) best = k;
      picked.push_back({best, fmt::format("default ({:.0f} % of the run)", 100 * f)});
    }
  }
  // Frame order, each frame once (the first request that chose it names it).
  std::stable_sort(picked.begin(), picked.end(),
                   [](const Selected& a, const Selected& b) { return a.position < b.position; });
  picked.erase(
      std::unique(picked.begin(), picked.end(),
                  [](const Selected& a, const Selected& b) { return a.position == b.position; }),
      picked.end());
  return picked;
}

}  // namespace fragmpm::pipeline::analyze_detail
