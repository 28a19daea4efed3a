// `fragmpm pipeline IMAGE --scene SCENE.toml -o DIR [--overwrite] [--threads N]` (docs/design.md):
// the scene is used as it is, except that IMAGE becomes the micrograph of every [[bodies]]
// entry with an `image` key, so the scene keeps the segmentation options (pixel size, input kind,
// crop, threshold) that fit its image. DIR receives
//   segmentation.png            the segmentation preview of each image body (segmentation_N.png if
//   several) run.h5, run.xmf             the run file and its XDMF companion fragments/
//   analyze_run: fragment tables, CDF and count / size figures figures/                    damage,
//   speed, stress, body and fragment figures of the last frame,
//                               fragment figures of the analysed frames, energy and
//                               force–displacement
//   summary.txt                 grains, fragments, energy balance error, wall time
//   report.html                 one static page: the summary, the trust checks, every figure
#include <fmt/format.h>
#include <omp.h>
#include <toml++/toml.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include "fragmpm/analysis/figure_error.hpp"
#include "fragmpm/analysis/frame_figure.hpp"
#include "fragmpm/analysis/particle_figure.hpp"
#include "fragmpm/analysis/plot.hpp"
#include "fragmpm/analysis/series_figures.hpp"
#include "fragmpm/analysis/si_format.hpp"
#include "fragmpm/mpm/build_info.hpp"
#include "fragmpm/mpm/run_file.hpp"
#include "fragmpm/mpm/run_file_reader.hpp"
#include "fragmpm/mpm/state_extremes.hpp"
#include "fragmpm/pipeline/analyze.hpp"
#include "fragmpm/pipeline/commands.hpp"
#include "fragmpm/pipeline/pipeline_job.hpp"
#include "fragmpm/pipeline/report_html.hpp"
#include "fragmpm/pipeline/run_loop.hpp"
#include "fragmpm/pipeline/scene.hpp"
#include "fragmpm/pipeline/segment.hpp"
#include "fragmpm/pipeline/segment_preview.hpp"
#include "scene/scene_grains.hpp"

namespace fragmpm::pipeline {

namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

void say(std::FILE* log, const std::string& line) {
  if (log) std::fprintf(log, "%s\n", line.c_str());
}

/// Byte offset of (line, column), both 1-based, column counted in code points as toml++ does.
std::size_t offset_of(const std::string& text, std::size_t line, std::size_t column) {
  std::size_t at = 0;
  for (std::size_t l = 1; l < line; ++l) {
    at = text.find('\n', at);
    if (at == std::string::npos) return text.size();
    ++at;
  }
  for (std::size_t c = 1; c < column && at < text.size(); ++c) {
    ++at;  // past the first byte of a code point, then past its continuation bytes
    while (at < text.size() && (static_cast<unsigned char>(text[at]) & 0xC0) == 0x80) ++at;
  }
  return at;
}

/// A TOML basic string holding `s`.
std::string toml_string(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

toml::table parse_toml(const std::string& text, const std::string& path) {
  try {
    return toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    throw PipelineError(fmt::format("{}:{}: {}", path, e.source().begin.line, e.description()));
  }
}

/// Empty, or absent: may be written to. Anything else needs --overwrite.
void check_output_dir(const fs::path& dir, bool overwrite) {
  std::error_code ec;
  if (!fs::exists(dir, ec)) return;
  if (!fs::is_directory(dir, ec))
    throw PipelineError(fmt::format("-o {}: exists and is not a directory", dir.string()));
  if (!fs::is_empty(dir, ec) && !overwrite)
    throw PipelineError(
        fmt::format("-o {}: the directory exists and is not empty; pass --overwrite to write "
                    "into it (files of the same name are replaced)",
                    dir.string()));
}

struct Preview {
  std::size_t grains = 0;
  cv::Mat image;
};

/// Segments the image of every image body with that body's options, as the scene compiler will.
std::vector<Preview> segment_previews(const std::string& text, const std::string& scene_path,
                                      const std::string& image) {
  const toml::table root = parse_toml(text, scene_path);
  std::vector<Preview> previews;
  const toml::array* bodies = root["bodies"].as_array();
  for (std::size_t i = 0; bodies && i < bodies->size(); ++i) {
    const toml::table* t = bodies->get(i)->as_table();
    if (!t || !t->contains("image")) continue;
    const scene_detail::Section section(*t, "bodies[" + std::to_string(i) + "]", scene_path);
    try {
      const Segmentation s = segment(scene_detail::read_segment_options(section, image));
      previews.push_back({s.table.grains.size(), draw_preview(s)});
    } catch (const SegmentInputError& e) {
      throw PipelineError(fmt::format("{}: {}", image, e.what()));
    } catch (const SceneError& e) {
      throw PipelineError(e.what());
    }
  }
  return previews;
}

std::string field_title(const std::string& what, int frame, double time, double travel) {
  return fmt::format(
      "{} - frame {}, t = {}{}", what, frame, analysis::format_si(time, "s", 3),
      std::isfinite(travel) ? ", platen " + analysis::format_si(travel, "m", 3) : std::string());
}

struct RunFacts {
  std::size_t particles = 0, bodies = 0;
  long long steps = 0;
  int frames = 0;
  double end_time = 0.0, travel = 0.0, run_seconds = 0.0;
  mpm::SeriesRow<2> last;
  bool failed = false;
  std::string failure;
  /// Extremes of the last frame (the end state of a finished run), or why there are none.
  std::string end_state;
  bool has_extremes = false;
  mpm::StateExtremes extremes;
  std::vector<mpm::ModuleDecision> modules;
};

std::string summary_text(const PipelineOptions& o, const std::vector<Preview>& previews,
                         const RunFacts& r, const AnalyzeResult* a, int threads, double setup_s,
                         double analysis_s, double total_s) {
  std::ostringstream s;
  std::size_t grains = 0;
  for (const Preview& p : previews) grains += p.grains;
  s << "fragmpm pipeline summary\n";
  s << fmt::format("image:      {}\nscene:      {}\n", o.image, o.scene_path);
  s << fmt::format(
      "grains:     {} segmented, {} simulated (grains holding at least one particle), {} "
      "particles\n",
      grains, r.bodies, r.particles);
  s << fmt::format("run:        {} steps to t = {}, platen travel {}, {} frames{}\n", r.steps,
                   analysis::format_si(r.end_time, "s", 4), analysis::format_si(r.travel, "m", 4),
                   r.frames,
                   r.failed ? ", STOPPED BY A NUMERICAL FAILURE: " + r.failure : std::string());
  const auto& t = r.last.totals;
  const double input = mpm::energy_input(r.last);
  s << fmt::format(
      "energy:     input {:.4g} J/m (initial {:.4g} + wall work {:.4g}); kinetic {:.4g}, strain "
      "{:.4g}, "
      "damage dissipation {:.4g}, crushed flow {:.4g}, crack energy {:.4g}, friction {:.4g}, "
      "contact {:.4g}, transfer {:.4g} [J/m]{}\n",
      input, t.initial_energy, t.wall_work, r.last.kinetic, r.last.strain, t.dissipated,
      t.flow_dissipation, t.fracture_energy, t.friction_work, t.contact_dissipation,
      t.transfer_dissipation,
      t.history_excess != 0.0
          ? fmt::format("; the phase field's history excess {:.4g} J/m is counted as put in",
                        t.history_excess)
          : std::string());
  s << fmt::format("balance:    error {:.4g} J/m = {:.3g} % of input\n", r.last.balance_error,
                   input > 0 ? 100.0 * std::abs(r.last.balance_error) / input : 0.0);
  if (!r.end_state.empty()) s << fmt::format("end state:  {}\n", r.end_state);
  if (t.lost.count > 0)
    s << fmt::format(
        "departed:   {} particles left the domain and were removed (mass {:.4g} kg/m; kinetic "
        "{:.4g} and strain {:.4g} J/m at removal, counted in the balance)\n",
        t.lost.count, t.lost.mass, t.lost.kinetic, t.lost.strain);
  if (a) {
    s << "fragments (resolved; fines apart), analysed frames:\n";
    s << "  frame   time        platen      fragments  fines  mean d_eq   largest d_eq\n";
    for (const AnalyzedFrame& f : a->frames) {
      const auto& m = f.fragments.summary;
      s << fmt::format(
          "  {:<6}  {:<10}  {:<10}  {:<9}  {:<5}  {:<10} {}\n", f.frame,
          analysis::format_si(f.time, "s", 3),
          std::isfinite(f.platen_displacement) ? analysis::format_si(f.platen_displacement, "m", 3)
                                               : "-",
          m.fragments, m.fines, analysis::format_si(m.mean_equivalent_diameter, "m", 3),
          analysis::format_si(m.largest_equivalent_diameter, "m", 3));
    }
    if (!a->frames.empty()) {
      const analysis::FragmentSummary& last = a->frames.back().fragments.summary;
      s << fmt::format("fragments:  {} resolved and {} fines at the last analysed frame",
                       last.fragments, last.fines);
      if (last.departed_particles > 0)
        s << fmt::format("; {} particles ({:.4g} kg/m) had left the domain",
                         last.departed_particles, last.departed_mass);
      s << "\n";
    }
  }
  s << fmt::format(
      "wall time:  {:.1f} s total (segmentation and setup {:.1f} s, run {:.1f} s, analysis and "
      "figures "
      "{:.1f} s), {} thread(s)\n",
      total_s, setup_s, r.run_seconds, analysis_s, threads);
  return s.str();
}

/// The page a person opens first: what ran, whether to trust it, and every figure with a caption.
Report pipeline_report(const PipelineOptions& o, const std::vector<Preview>& previews,
                       const RunFacts& r, const AnalyzeResult* a, int threads, double total_s,
                       const std::string& summary, const fs::path& dir,
                       const std::vector<std::string>& files) {
  Report report;
  report.title = "FragMPM run: " + fs::path(o.scene_path).filename().string();
  report.subtitle = fmt::format("image {}, scene {}, fragmpm {} ({})", o.image, o.scene_path,
                                mpm::program_version(), mpm::program_git_hash());
  std::size_t grains = 0;
  for (const Preview& p : previews) grains += p.grains;
  report.summary.push_back({"grains", fmt::format("{} segmented, {} simulated", grains, r.bodies)});
  report.summary.push_back({"particles", fmt::format("{}", r.particles)});
  report.summary.push_back({"run", fmt::format("{} steps to t = {}, platen travel {}, {} frames",
                                               r.steps, analysis::format_si(r.end_time, "s", 4),
                                               analysis::format_si(r.travel, "m", 4), r.frames)});
  report.summary.push_back(
      {"wall time", fmt::format("{:.1f} s in all, of which the run {:.1f} s, on {} thread(s)",
                                total_s, r.run_seconds, threads)});
  for (const mpm::ModuleDecision& m : r.modules)
    report.summary.push_back(
        {"module " + m.module, std::string(m.active ? "on: " : "off: ") + m.reason});
  if (a && !a->frames.empty()) {
    const AnalyzedFrame& f = a->frames.back();
    const analysis::FragmentSummary& m = f.fragments.summary;
    report.summary.push_back(
        {"fragments", fmt::format("{} resolved and {} fines at t = {} (mean d_eq {}, largest {})",
                                  m.fragments, m.fines, analysis::format_si(f.time, "s", 3),
                                  analysis::format_si(m.mean_equivalent_diameter, "m", 3),
                                  analysis::format_si(m.largest_equivalent_diameter, "m", 3))});
  }

  // Trust: the limits are those of the stability scenes (docs/verification.md).
  if (r.failed) report.checks.push_back({"numerical failure", r.failure, true});
  const auto& t = r.last.totals;
  const double input = mpm::energy_input(r.last);
  const double share = input > 0 ? std::abs(r.last.balance_error) / input : 0.0;
  report.checks.push_back(
      {"energy balance",
       fmt::format("error {:.4g} J/m = {:.3g} % of the input {:.4g} J/m (limit 2 %); booked: "
                   "damage {:.4g}, crushed flow {:.4g}, friction {:.4g}, contact {:.4g}, transfer "
                   "{:.4g}, departed {:.4g} J/m",
                   r.last.balance_error, 100.0 * share, input, t.dissipated, t.flow_dissipation,
                   t.friction_work, t.contact_dissipation, t.transfer_dissipation,
                   t.lost.kinetic + t.lost.strain),
       share > 0.02});
  if (r.has_extremes) {
    report.checks.push_back(
        {"largest volume ratio J",
         fmt::format("{:.4g}; {} particle(s) above J = {:g}", r.extremes.largest_J,
                     r.extremes.swollen, mpm::swollen_volume_ratio),
         r.extremes.swollen > 0});
    // No limit: the damage laws bound tension only, so a compressed contact may carry any stress.
    report.checks.push_back({.label = "largest |principal stress|",
                             .value = analysis::format_si(r.extremes.largest_stress, "Pa", 4),
                             .limited = false});
  }
  // No limit: with [grid] outside = "remove" departures are part of the run and booked.
  report.checks.push_back(
      {.label = "particles removed",
       .value = fmt::format("{} left the domain (mass {:.4g} kg/m)", t.lost.count, t.lost.mass),
       .limited = false});

  ReportSection segmentation{"Segmentation", {}}, fields{"Fields at the last frame", {}},
      maps{"Fragment maps", {}}, statistics{"Fragment statistics", {}},
      series{"Energy and force", {}};
  for (const std::string& file : files) {
    const std::string relative = fs::path(file).lexically_relative(dir).generic_string();
    const std::string caption = figure_caption(relative);
    if (caption.empty()) continue;
    ReportSection& section = relative.rfind("segmentation", 0) == 0            ? segmentation
                             : relative.find("_last.png") != std::string::npos ? fields
                             : relative.rfind("figures/fragments_", 0) == 0    ? maps
                             : relative.rfind("fragments/", 0) == 0            ? statistics
                                                                               : series;
    std::string text = caption;
    if (&section == &maps && a)
      for (const AnalyzedFrame& f : a->frames)
        if (relative == fmt::format("figures/fragments_{:06d}.png", f.frame))
          text = fmt::format("{} fragments and {} fines at t = {}{}. {}",
                             f.fragments.summary.fragments, f.fragments.summary.fines,
                             analysis::format_si(f.time, "s", 3),
                             std::isfinite(f.platen_displacement)
                                 ? ", platen " + analysis::format_si(f.platen_displacement, "m", 3)
                                 : std::string(),
                             caption);
    section.figures.push_back({relative, text});
  }
  report.sections = {segmentation, fields, maps, statistics, series};
  report.details = summary;
  return report;
}

}  // namespace

std::string scene_with_image(const std::string& text, const std::string& scene_path,
                             const std::string& image_path) {
  const toml::table root = parse_toml(text, scene_path);
  std::vector<std::pair<std::size_t, std::size_t>> ranges;  // byte ranges of the image values
  if (const toml::array* bodies = root["bodies"].as_array())
    for (const toml::node& b : *bodies)
      if (const toml::table* t = b.as_table())
        if (const toml::node* image = t->get("image")) {
          const toml::source_region& r = image->source();
          if (!image->is_string() || r.begin.line != r.end.line)
            throw PipelineError(
                fmt::format("{}:{}: key 'image': expected a path (a string on one line)",
                            scene_path, r.begin.line));
          ranges.emplace_back(offset_of(text, r.begin.line, r.begin.column),
                              offset_of(text, r.end.line, r.end.column));
        }
  if (ranges.empty())
    throw PipelineError(fmt::format(
        "{}: expected a [[bodies]] entry with image = \"…\" (grains from a micrograph, "
        "see scenes/demo/sandstone-crush.toml), got none; the pipeline puts IMAGE there",
        scene_path));
  std::string out = text;
  for (auto it = ranges.rbegin(); it != ranges.rend(); ++it)
    out.replace(it->first, it->second - it->first, toml_string(image_path));
  return out;
}

PipelineResult run_pipeline(const PipelineOptions& o, std::FILE* log) {
  const Clock::time_point start = Clock::now();
  const fs::path dir(o.output_dir);
  check_output_dir(dir, o.overwrite);
  std::error_code ec;
  if (!fs::is_regular_file(o.image, ec))
    throw PipelineError(fmt::format(
        "{}: {}", o.image, fs::exists(o.image, ec) ? "not a regular file" : "no such file"));
  const std::string image = fs::absolute(o.image).lexically_normal().string();
  if (o.threads > 0) omp_set_num_threads(o.threads);

  // Everything is checked before anything is written or simulated.
  const std::string text = scene_with_image(o.scene_text, o.scene_path, image);
  const std::vector<Preview> previews = segment_previews(text, o.scene_path, image);
  mpm::Problem<2> problem;
  try {
    problem = parse_scene(text, o.scene_path);
  } catch (const SceneError& e) {
    throw PipelineError(e.what());
  }

  PipelineResult result;
  fs::create_directories(dir / "figures", ec);
  if (ec)
    throw PipelineError(
        fmt::format("-o {}: cannot create the directory ({})", dir.string(), ec.message()));
  for (std::size_t k = 0; k < previews.size(); ++k) {
    const fs::path path =
        dir / (previews.size() == 1 ? "segmentation.png" : fmt::format("segmentation_{}.png", k));
    try {
      write_preview(previews[k].image, path.string());
    } catch (const SegmentInputError& e) {
      throw PipelineError(e.what());
    }
    result.files.push_back(path.string());
  }
  say(log, fmt::format("fragmpm pipeline: {} -> {} grains; segmentation preview -> {}", image,
                       previews.empty() ? 0 : previews.front().grains, result.files.front()));

  // Simulate.
  RunFacts facts;
  facts.particles = problem.particles.size();
  facts.bodies = problem.body_names.size();
  result.run_path = (dir / "run.h5").string();
  mpm::RunMeta meta;
  meta.scene_path = problem.scene_path;
  meta.scene_text = problem.scene_text;
  meta.modules = mpm::plan_modules<2>(problem);
  facts.modules = meta.modules;
  for (const auto& w : problem.walls) meta.wall_names.push_back(w.name);
  const int threads = omp_get_max_threads();
  say(log, fmt::format(
               "fragmpm pipeline: {} particles in {} grains, {} walls, cell size {}, {} thread(s)",
               facts.particles, facts.bodies, problem.walls.size(),
               analysis::format_si(problem.grid.cell_size, "m", 3), threads));
  const double setup_s = seconds_since(start);
  {
    mpm::RunFile<2> file = mpm::RunFile<2>::create(result.run_path, meta, true);
    mpm::Solver<2> solver(std::move(problem));
    RunLoopOptions loop;
    loop.progress = o.progress;
    const RunLoopResult run = run_loop(solver, file, loop);
    facts.steps = run.steps;
    facts.frames = run.frames;
    facts.run_seconds = run.wall_seconds;
    facts.end_time = solver.time();
    facts.last = solver.last_row();
    for (const auto& u : facts.last.wall_displacement)
      facts.travel = std::max(facts.travel, u.norm());
    if (run.failed) {
      facts.failed = true;
      facts.failure = fmt::format("step {}, t = {:.6g} s: {}", run.failure.step, run.failure.time,
                                  run.failure.what);
      result.exit_code = 3;
    }
  }
  result.files.push_back(result.run_path);
  result.files.push_back((dir / "run.xmf").string());
  say(log, fmt::format("fragmpm pipeline: {} steps in {:.1f} s -> {}", facts.steps,
                       facts.run_seconds, result.run_path));
  const Clock::time_point analysis_start = Clock::now();

  // Fragments, tables, CDFs.
  AnalyzeOptions ao;
  ao.run_path = result.run_path;
  ao.output_dir = (dir / "fragments").string();
  std::unique_ptr<AnalyzeResult> analyzed;
  try {
    analyzed = std::make_unique<AnalyzeResult>(analyze_run(ao, log));
    result.files.insert(result.files.end(), analyzed->files.begin(), analyzed->files.end());
  } catch (const AnalyzeError& e) {
    say(log, fmt::format("fragmpm pipeline: analysis skipped: {}", e.what()));
  }

  // Figures of the last frame and of the series.
  auto figure = [&](const std::string& name, auto&& draw) {
    const std::string path = (dir / "figures" / name).string();
    try {
      draw(path);
      result.files.push_back(path);
    } catch (const analysis::FigureError& e) {
      say(log, fmt::format("  figure {} skipped: {}", name, e.what()));
    }
  };
  {
    const mpm::RunFileReader file = mpm::RunFileReader::open(result.run_path);
    const int last = static_cast<int>(file.frames().size()) - 1;
    double time = 0.0;
    const mpm::Particles<2> particles = file.read_frame<2>(last, &time);
    const mpm::FrameEntry& frame = file.frames().back();
    facts.has_extremes = frame.has("F") && frame.has("stress");
    if (facts.has_extremes) facts.extremes = mpm::state_extremes<2>(particles);
    facts.end_state =
        facts.has_extremes
            ? fmt::format("{} (frame {}, t = {})", mpm::describe(facts.extremes), frame.index,
                          analysis::format_si(time, "s", 4))
            : fmt::format("frame {} has no F or stress (the scene's [output] fields)", frame.index);
    const struct {
      analysis::FrameField field;
      const char* name;
    } fields[] = {{analysis::FrameField::damage, "damage"},
                  {analysis::FrameField::speed, "speed"},
                  {analysis::FrameField::stress, "stress"},
                  {analysis::FrameField::body, "body"}};
    for (const auto& f : fields)
      figure(fmt::format("{}_last.png", f.name), [&](const std::string& path) {
        analysis::write_particle_figure(
            analysis::frame_figure(particles, f.field, time,
                                   field_title(f.name, last, time, facts.travel)),
            path);
      });
    if (analyzed)
      for (const AnalyzedFrame& f : analyzed->frames) {
        const mpm::Particles<2> current = f.frame == last ? particles : file.read_frame<2>(f.frame);
        figure(fmt::format("fragments_{:06d}.png", f.frame), [&](const std::string& path) {
          analysis::write_particle_figure(
              analysis::fragment_figure(
                  current, analysis::resolved_fragment_ids(f.fragments.labels), f.time,
                  field_title(fmt::format("{} fragments", f.fragments.summary.fragments), f.frame,
                              f.time, f.platen_displacement)),
              path);
        });
      }
    const mpm::RunSeries series = file.read_series();
    figure("energy.png", [&](const std::string& path) {
      analysis::write_line_plot(analysis::energy_plot_spec(series), path);
    });
    figure("force_displacement.png", [&](const std::string& path) {
      analysis::write_line_plot(analysis::force_displacement_spec(series, file.meta().wall_names),
                                path);
    });
  }
  const double analysis_s = seconds_since(analysis_start);

  result.summary = summary_text(o, previews, facts, analyzed.get(), threads, setup_s, analysis_s,
                                seconds_since(start));
  result.summary_path = (dir / "summary.txt").string();
  std::ofstream out(result.summary_path);
  out << result.summary;
  if (!out) throw PipelineError(fmt::format("{}: cannot write", result.summary_path));
  result.files.push_back(result.summary_path);

  const std::string report_path = (dir / "report.html").string();
  write_report(pipeline_report(o, previews, facts, analyzed.get(), threads, seconds_since(start),
                               result.summary, dir, result.files),
               report_path);
  result.files.push_back(report_path);
  say(log, fmt::format("fragmpm pipeline: report -> {}", report_path));
  return result;
}

namespace {

struct PipelineArguments {
  std::string image;
  std::string scene;
  std::string output;
  bool overwrite = false;
  int threads = 0;
  bool quiet = false;
};

int execute(const PipelineArguments& a) {
  try {
    std::ifstream in(a.scene, std::ios::binary);
    if (!in) throw PipelineError(fmt::format("--scene {}: cannot read the scene file", a.scene));
    std::ostringstream text;
    text << in.rdbuf();
    PipelineOptions o;
    o.image = a.image;
    o.scene_text = text.str();
    o.scene_path = a.scene;
    o.output_dir = a.output;
    o.overwrite = a.overwrite;
    o.threads = a.threads;
    o.progress = !a.quiet;
    const PipelineResult r = run_pipeline(o, stderr);
    std::printf("%s", r.summary.c_str());
    std::printf("written to %s: %zu files (summary: %s)\n", a.output.c_str(), r.files.size(),
                r.summary_path.c_str());
    return r.exit_code;
  } catch (const PipelineError& e) {
    std::fprintf(stderr, "fragmpm pipeline: %s\n", e.what());
    return 2;
  } catch (const mpm::RunFileError& e) {
    std::fprintf(stderr, "fragmpm pipeline: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fragmpm pipeline: %s\n", e.what());
    return 1;
  }
}

}  // namespace

void add_pipeline_command(CLI::App& app, CommandResult& result) {
  auto args = std::make_shared<PipelineArguments>();
  CLI::App* cmd = app.add_subcommand(
      "pipeline",
      "Micrograph → grains → crushing run → fragments, figures and summary.txt in one directory; "
      "IMAGE replaces the image of the scene's image bodies (their segmentation options stay)");
  cmd->add_option("image", args->image, "Micrograph (any format OpenCV reads)")->required();
  cmd->add_option("--scene", args->scene, "Scene file with a [[bodies]] entry image = \"…\"")
      ->required();
  cmd->add_option("-o,--output", args->output, "Output directory")->required();
  cmd->add_flag("--overwrite", args->overwrite, "Write into an existing non-empty directory");
  cmd->add_option("--threads", args->threads, "OpenMP threads (default: all cores)");
  cmd->add_flag("-q,--quiet", args->quiet, "No progress line");
  cmd->callback([args, &result] { result.exit_code = execute(*args); });
}

}  // namespace fragmpm::pipeline
