// `fragmpm analyze` as a function (see analyze.hpp): read the run file, label and measure the
// fragments of the chosen frames, summarise every frame, and write tables, figures and run-file
// groups.
#include "fragmpm/pipeline/analyze.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <optional>
#include <set>

#include "analyze_frames.hpp"
#include "fragmpm/analysis/figure_error.hpp"
#include "fragmpm/analysis/fragment_figures.hpp"
#include "fragmpm/analysis/frame_reference.hpp"
#include "fragmpm/analysis/si_format.hpp"
#include "fragmpm/mpm/run_file_fragments.hpp"
#include "fragmpm/mpm/run_file_reader.hpp"

namespace fragmpm::pipeline {

namespace fs = std::filesystem;
using namespace analyze_detail;

namespace {

constexpr const char* kWrittenBy = "fragmpm analyze";

void say(std::FILE* log, const std::string& line) {
  if (log) std::fprintf(log, "%s\n", line.c_str());
}

std::string frame_label(const AnalyzedFrame& f) {
  std::string label = fmt::format("t = {}", analysis::format_si(f.time, "s", 3));
  if (std::isfinite(f.platen_displacement))
    label += fmt::format(", u = {}", analysis::format_si(f.platen_displacement, "m", 3));
  return label;
}

std::string describe(const analysis::FrameFragments& r) {
  const analysis::FragmentSummary& s = r.summary;
  std::string text = fmt::format("{} fragments + {} fines ({} particles), {} particles masked",
                                 s.fragments, s.fines, s.fine_particles, s.masked_particles);
  if (s.fragments > 0)
    text += fmt::format("; mean equivalent diameter {} (mass-weighted {}, largest {})",
                        analysis::format_si(s.mean_equivalent_diameter, "m", 3),
                        analysis::format_si(s.mass_mean_equivalent_diameter, "m", 3),
                        analysis::format_si(s.largest_equivalent_diameter, "m", 3));
  if (s.departed_particles > 0)
    text += fmt::format("; {} particles ({:.4g} kg/m) left the domain and were removed",
                        s.departed_particles, s.departed_mass);
  text += r.raster_checked ? "\n      " + r.raster.summary()
                           : "\n      raster check skipped: " + r.raster_note;
  return text;
}

/// The /fragments/ groups this analysis will write that exist already: fine (and listed) when an
/// earlier analyze wrote them, refused otherwise.
/// `names` are relative to /fragments ("000002", "series").
std::vector<std::string> groups_to_replace(const mpm::RunFileReader& file,
                                           const std::vector<std::string>& names) {
  std::vector<std::string> replace;
  for (const std::string& name : names) {
    const mpm::RunFileReader::GroupState state = file.fragment_group(name);
    if (!state.exists) continue;
    if (!state.is_group || state.written_by != kWrittenBy)
      throw AnalyzeError(fmt::format(
          "{}: /fragments/{} exists and was not written by fragmpm analyze; refusing to "
          "replace it (use --csv-only to leave the run file alone)",
          file.path(), name));
    replace.push_back("fragments/" + name);
  }
  return replace;
}

void set_options(mpm::TableGroup& g, const analysis::FragmentOptions& o) {
  g.attributes.push_back({"written_by", std::string(kWrittenBy)});
  g.attributes.push_back({"d_mask", o.d_mask});
  g.attributes.push_back({"min_particles", static_cast<std::int64_t>(o.min_particles)});
  g.attributes.push_back({"reference_reach", o.reference_reach});
  g.attributes.push_back({"current_reach", o.current_reach});
}

mpm::TableGroup frame_group_table(const AnalyzeOptions& o, const AnalyzeResult& r,
                                  const AnalyzedFrame& f) {
  mpm::TableGroup g;
  set_options(g, o.fragments);
  auto attribute = [&](const char* name, mpm::TableAttribute value) {
    g.attributes.push_back({name, std::move(value)});
  };
  attribute("frame", static_cast<std::int64_t>(f.frame));
  attribute("time", f.time);
  attribute("step", static_cast<std::int64_t>(f.step));
  attribute("request", f.request);
  if (!r.platen.empty()) {
    attribute("platen", r.platen);
    attribute("platen_displacement", f.platen_displacement);
  }
  const analysis::FragmentSummary& s = f.fragments.summary;
  attribute("fragments", static_cast<std::int64_t>(s.fragments));
  attribute("fines", static_cast<std::int64_t>(s.fines));
  attribute("fine_particles", static_cast<std::int64_t>(s.fine_particles));
  attribute("masked_particles", static_cast<std::int64_t>(s.masked_particles));
  attribute("fines_mass", s.fines_mass);
  attribute("fines_area", s.fines_area);
  attribute("departed_particles", static_cast<std::int64_t>(s.departed_particles));
  attribute("departed_mass", s.departed_mass);
  attribute("raster_check", f.fragments.raster_checked ? f.fragments.raster.summary()
                                                       : "skipped: " + f.fragments.raster_note);
  g.columns = analysis::fragment_frame_datasets(f.fragments);
  return g;
}

void write_run_groups(const AnalyzeOptions& o, const AnalyzeResult& r) {
  const mpm::FragmentGroupWriter file = [&] {
    try {
      return mpm::FragmentGroupWriter::open(o.run_path);
    } catch (const mpm::RunFileError& e) {
      throw AnalyzeError(
          fmt::format("cannot write the fragment tables into the run file ({}); the CSV files are "
                      "written; use --csv-only to skip the run file",
                      e.what()));
    }
  }();
  for (const AnalyzedFrame& f : r.frames)
    file.replace(fmt::format("{:06d}", f.frame), frame_group_table(o, r, f));
  mpm::TableGroup series;
  set_options(series, o.fragments);
  if (!r.platen.empty()) series.attributes.push_back({"platen", r.platen});
  series.columns = analysis::fragment_series_datasets(r.series, !r.platen.empty());
  file.replace("series", series);
  file.flush();
}

void write_figures(const AnalyzeResult& r, std::vector<std::string>& files, std::FILE* log) {
  std::vector<analysis::CdfCurve> curves;
  for (const AnalyzedFrame& f : r.frames) {
    curves.push_back({frame_label(f), f.fragments.equivalent_diameter});
  }
  std::vector<analysis::CdfCurve> roundness;
  for (const AnalyzedFrame& f : r.frames)
    roundness.push_back({frame_label(f), f.fragments.roundness});
  using analysis::CdfQuantity;
  using analysis::CdfWeighting;
  struct Figure {
    const char* file;
    std::function<analysis::PlotSpec()> spec;
  };
  const Figure figures[] = {
      {"cdf_equivalent_diameter.png",
       [&] {
         return analysis::cdf_plot_spec(curves, CdfQuantity::equivalent_diameter,
                                        CdfWeighting::number);
       }},
      {"cdf_equivalent_diameter_mass.png",
       [&] {
         return analysis::cdf_plot_spec(curves, CdfQuantity::equivalent_diameter,
                                        CdfWeighting::mass);
       }},
      {"cdf_roundness.png",
       [&] {
         return analysis::cdf_plot_spec(roundness, CdfQuantity::roundness, CdfWeighting::number);
       }},
      {"cdf_roundness_mass.png",
       [&] {
         return analysis::cdf_plot_spec(roundness, CdfQuantity::roundness, CdfWeighting::mass);
       }},
      {"fragment_count.png", [&] { return analysis::fragment_count_spec(r.series); }},
      {"fragment_size.png", [&] { return analysis::fragment_size_spec(r.series); }},
  };
  for (const Figure& f : figures) {
    const std::string path = (fs::path(r.output_dir) / f.file).string();
    try {
      analysis::write_line_plot(f.spec(), path);
      files.push_back(path);
    } catch (const analysis::FigureError& e) {
      say(log, fmt::format("  figure {} skipped: {}", f.file, e.what()));
    }
  }
}

mpm::RunFileReader open_run(const std::string& path) {
  try {
    return mpm::RunFileReader::open(path);
  } catch (const mpm::NotARunFile& e) {
    throw AnalyzeError(e.what());
  } catch (const mpm::RunFileError& e) {
    throw AnalyzeError(fmt::format("{}: not a FragMPM run file ({})", path, e.what()));
  }
}

/// The CSV tables of the analysed frames and the count / size series; their paths go to
/// result.files.
void write_tables(AnalyzeResult& result) {
  const fs::path dir(result.output_dir);
  for (const AnalyzedFrame& f : result.frames) {
    const std::string n = fmt::format("{:06d}", f.frame);
    const bool theta = f.fragments.has_temperature;
    const std::string files[] = {(dir / ("fragments_" + n + ".csv")).string(),
                                 (dir / ("fines_" + n + ".csv")).string(),
                                 (dir / ("cdf_equivalent_diameter_" + n + ".csv")).string(),
                                 (dir / ("cdf_roundness_" + n + ".csv")).string()};
    try {
      analysis::write_fragment_csv(files[0], f.fragments.fragments, theta);
      analysis::write_fragment_csv(files[1], f.fragments.fines, theta);
      analysis::write_cdf_csv(files[2], f.fragments.equivalent_diameter, "equivalent_diameter_m");
      analysis::write_cdf_csv(files[3], f.fragments.roundness, "roundness");
    } catch (const std::runtime_error& e) {
      throw AnalyzeError(e.what());
    }
    for (const std::string& file : files) result.files.push_back(file);
  }
  const std::string series_csv = (dir / "fragment_series.csv").string();
  try {
    analysis::write_fragment_series_csv(series_csv, result.series, !result.platen.empty());
  } catch (const std::runtime_error& e) {
    throw AnalyzeError(e.what());
  }
  result.files.push_back(series_csv);
}

}  // namespace

AnalyzeResult analyze_run(const AnalyzeOptions& given, std::FILE* log) {
  AnalyzeOptions o = given;
  try {
    analysis::validate(o.fragments);
  } catch (const std::invalid_argument& e) {
    throw AnalyzeError(e.what());
  }
  const std::string& path = o.run_path;
  std::error_code ec;
  if (!fs::exists(path, ec)) throw AnalyzeError(path + ": no such file");
  if (fs::is_directory(path, ec)) throw AnalyzeError(path + ": is a directory, not a run file");
  if (!o.d_mask_given) {
    const std::vector<mpm::ModuleDecision> modules = open_run(path).meta().modules;
    for (const mpm::ModuleDecision& m : modules)
      if (m.module == "phase field" && m.active)
        o.fragments.d_mask = std::min(o.fragments.d_mask, phase_field_fragment_mask);
  }

  AnalyzeResult result;
  result.output_dir = o.output_dir;
  if (result.output_dir.empty()) {
    const fs::path p(path);
    result.output_dir = (p.parent_path() / (p.stem().string() + "_fragments")).string();
  }
  {
    const mpm::RunFileReader file = open_run(path);
    const RunIndex run = read_run_index(file);
    const mpm::RunSeries series = file.read_series(platen_series(run));
    std::vector<std::string> moving;
    result.platen = choose_platen(series, run, o.platen, moving);
    const std::vector<double> travel =
        result.platen.empty() ? std::vector<double>{} : platen_travel(series, run, result.platen);
    const std::vector<Selected> selection = select_frames(o, run, travel, moving);

    if (o.write_run_file) {
      std::vector<std::string> names{"series"};
      for (const Selected& s : selection)
        names.push_back(fmt::format("{:06d}", run.frames[s.position].index));
      for (const std::string& name : groups_to_replace(file, names))
        result.replaced_groups.push_back("/" + name);
    }
    fs::create_directories(result.output_dir, ec);
    if (ec || !fs::is_directory(result.output_dir))
      throw AnalyzeError(fmt::format("{}: cannot create the output directory ({})",
                                     result.output_dir, ec.message()));

    const FrameInfo& first = run.frames.front();
    const mpm::Particles<2> reference = read_analysis_frame(file, run, first.index);
    say(log, fmt::format(
                 "fragmpm analyze: {} ({} particles, {} frames; reference configuration: frame {} "
                 "at t = {}{})",
                 path, reference.size(), run.frames.size(), first.index,
                 analysis::format_si(first.time, "s", 4),
                 result.platen.empty() ? "" : fmt::format("; platen: wall '{}'", result.platen)));
    say(log, fmt::format("  mask d >= {}, fines below {} particles", o.fragments.d_mask,
                         o.fragments.min_particles));

    // --body: the chosen body's particles in the first frame, whose count and mass give what of
    // it left the domain by a later frame.
    std::size_t body_particles = 0;
    double body_mass = 0.0;
    if (o.body >= 0) {
      if (reference.body.size() != reference.size())
        throw AnalyzeError(
            fmt::format("{}: frame {} has no 'body' dataset, so --body cannot pick "
                        "a body's particles",
                        path, first.index));
      const std::set<std::int32_t> present(reference.body.begin(), reference.body.end());
      for (std::size_t p = 0; p < reference.size(); ++p)
        if (reference.body[p] == o.body) ++body_particles, body_mass += reference.mass[p];
      if (body_particles == 0)
        throw AnalyzeError(
            fmt::format("{}: --body {}: no particle of that body in frame {}; the "
                        "run's bodies are {}",
                        path, o.body, first.index, fmt::join(present, ", ")));
      say(log, fmt::format("  fragments of body {} only ({} of {} particles)", o.body,
                           body_particles, reference.size()));
    }

    std::size_t next = 0;  // next entry of `selection`
    for (std::size_t k = 0; k < run.frames.size(); ++k) {
      const FrameInfo& info = run.frames[k];
      const mpm::Particles<2> whole_frame =
          k == 0 ? reference : read_analysis_frame(file, run, info.index);
      // Particles removed after leaving the domain are missing from later frames; the rest find
      // their reference configuration by id.
      analysis::FrameReference matched;
      try {
        matched = analysis::frame_reference(reference, whole_frame);
      } catch (const std::invalid_argument& e) {
        throw AnalyzeError(fmt::format("{}: {} does not match the reference frame {}: {}", path,
                                       frame_group(info.index), first.index, e.what()));
      }
      // With --body, the body's rows of this frame (`kept`) and of the reference.
      std::vector<std::size_t> kept;
      mpm::Particles<2> body_frame;
      if (o.body >= 0) {
        for (std::size_t p = 0; p < whole_frame.size(); ++p)
          if (whole_frame.body[p] == o.body) kept.push_back(p);
        body_frame = whole_frame.select(kept);
        matched.particles = matched.particles.select(kept);
        double mass_now = 0.0;
        for (std::size_t p : kept) mass_now += whole_frame.mass[p];
        matched.departed = body_particles - kept.size();
        matched.departed_mass = std::max(0.0, body_mass - mass_now);
      }
      const mpm::Particles<2>& current = o.body >= 0 ? body_frame : whole_frame;
      auto count_departed = [&matched](analysis::FragmentSummary& s) {
        s.departed_particles = matched.departed;
        s.departed_mass = matched.departed_mass;
      };
      analysis::FragmentSeriesPoint point;
      point.frame = info.index;
      point.step = info.step;
      point.time = info.time;
      point.platen_displacement =
          travel.empty() ? std::numeric_limits<double>::quiet_NaN() : travel[k];
      try {
        if (next < selection.size() && selection[next].position == k) {
          AnalyzedFrame f;
          f.frame = info.index;
          f.step = info.step;
          f.time = info.time;
          f.platen_displacement = point.platen_displacement;
          f.request = selection[next].request;
          f.fragments = analysis::analyze_fragments(matched.particles, current, o.fragments);
          count_departed(f.fragments.summary);
          if (o.body >= 0) {  // particle_fragment covers the whole frame, as without --body
            std::vector<std::int32_t> labels(whole_frame.size(), other_body_fragment);
            for (std::size_t r = 0; r < kept.size(); ++r)
              labels[kept[r]] = f.fragments.labels.fragment[r];
            f.fragments.labels.fragment = std::move(labels);
          }
          point.summary = f.fragments.summary;
          say(log, fmt::format("  {} -> frame {} (t = {}, step {}{}): {}", f.request, f.frame,
                               analysis::format_si(f.time, "s", 4), f.step,
                               std::isfinite(f.platen_displacement)
                                   ? fmt::format(", platen displacement {}",
                                                 analysis::format_si(f.platen_displacement, "m", 4))
                                   : "",
                               describe(f.fragments)));
          result.frames.push_back(std::move(f));
          ++next;
        } else {
          point.summary = analysis::summarize_fragments(
              current, analysis::label_fragments(matched.particles, current, o.fragments));
          count_departed(point.summary);
        }
      } catch (const std::invalid_argument& e) {
        throw AnalyzeError(fmt::format("{}: {}: {}", path, frame_group(info.index), e.what()));
      }
      result.series.push_back(point);
    }
  }

  write_tables(result);
  say(log, fmt::format("  tables ({} frames) and the count / size series over {} frames -> {}",
                       result.frames.size(), result.series.size(), result.output_dir));
  if (o.figures) {
    const std::size_t before = result.files.size();
    write_figures(result, result.files, log);
    if (result.files.size() > before)
      say(log, fmt::format("  {} figures -> {}", result.files.size() - before, result.output_dir));
  }
  if (o.write_run_file) {
    write_run_groups(o, result);
    for (const AnalyzedFrame& f : result.frames)
      say(log, fmt::format("  run file: /fragments/{:06d} written", f.frame));
    say(log, "  run file: /fragments/series written");
    for (const std::string& g : result.replaced_groups)
      say(log, fmt::format("  run file: {} replaced the group of an earlier analyze", g));
  }
  return result;
}

}  // namespace fragmpm::pipeline
