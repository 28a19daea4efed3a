// Figures of the three-grain case (three_grain_figures.hpp). File names carry the variant without
// spaces and the platen travel, e.g. three-grain/16ms-fragments-0.8mm.png.
#include "three_grain_figures.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <opencv2/core.hpp>
#include <unordered_map>

#include "fragmpm/analysis/figure_error.hpp"
#include "fragmpm/analysis/fragment_figures.hpp"
#include "fragmpm/analysis/fragments.hpp"
#include "fragmpm/analysis/frame_figure.hpp"
#include "fragmpm/analysis/particle_figure.hpp"
#include "fragmpm/analysis/plot.hpp"
#include "fragmpm/analysis/png_file.hpp"

namespace fragmpm::pipeline {

namespace {

/// "16 m/s isothermal" → "16ms-isothermal".
std::string file_stem(const std::string& variant) {
  std::string out;
  for (char c : variant) {
    if (c == '/') continue;
    out += c == ' ' ? '-' : c;
  }
  return out;
}

std::string travel_text(double displacement) {
  char text[32];
  std::snprintf(text, sizeof text, "%gmm", std::round(displacement * 1e5) / 1e2);
  return text;
}

std::string path_in(const std::string& directory, const std::string& name) {
  return (std::filesystem::path(directory) / name).string();
}

void announce(const std::string& path) {
  std::fprintf(stderr, "written %s\n", path.c_str());
}

/// The reference states of `current`'s particles in its order (matched by id, as in the run).
mpm::Particles<2> matched_reference(const ThreeGrainRun& run, const mpm::Particles<2>& current) {
  std::unordered_map<std::int32_t, std::size_t> row_of;
  for (std::size_t p = 0; p < run.reference.size(); ++p)
    row_of[run.reference.id.empty() ? static_cast<std::int32_t>(p) : run.reference.id[p]] = p;
  std::vector<std::size_t> rows;
  for (std::size_t p = 0; p < current.size(); ++p)
    rows.push_back(current.id.empty() ? p : row_of.at(current.id[p]));
  return run.reference.select(rows);
}

void write_cdfs(const ThreeGrainRun& run, const std::string& directory) {
  const std::string stem = file_stem(run.spec.variant);
  std::vector<analysis::CdfCurve> diameters, roundness;
  for (const ThreeGrainFrame& f : run.frames) {
    char label[48];
    std::snprintf(label, sizeof label, "u = %g mm", std::round(f.sample.displacement * 1e5) / 1e2);
    diameters.push_back({label, f.top_fragments.equivalent_diameter});
    roundness.push_back({label, f.top_fragments.roundness});
  }
  const struct {
    analysis::CdfQuantity quantity;
    analysis::CdfWeighting weighting;
    const char* name;
  } plots[] = {
      {analysis::CdfQuantity::equivalent_diameter, analysis::CdfWeighting::number, "deq-number"},
      {analysis::CdfQuantity::equivalent_diameter, analysis::CdfWeighting::mass, "deq-mass"},
      {analysis::CdfQuantity::roundness, analysis::CdfWeighting::number, "roundness-number"},
      {analysis::CdfQuantity::roundness, analysis::CdfWeighting::mass, "roundness-mass"}};
  for (const auto& p : plots) {
    const bool diameter = p.quantity == analysis::CdfQuantity::equivalent_diameter;
    try {
      analysis::PlotSpec spec =
          analysis::cdf_plot_spec(diameter ? diameters : roundness, p.quantity, p.weighting);
      spec.title = "Top grain at " + run.spec.variant + ": " + spec.title;
      const std::string path = path_in(directory, stem + "-cdf-" + p.name + ".png");
      analysis::write_line_plot(spec, path);
      announce(path);
    } catch (const analysis::FigureError& e) {
      std::fprintf(stderr, "no %s CDF for %s: %s\n", p.name, run.spec.variant.c_str(), e.what());
    }
  }
}

void write_frame_figures(const ThreeGrainRun& run, const std::string& directory) {
  const std::string stem = file_stem(run.spec.variant);
  for (const ThreeGrainFrame& f : run.frames) {
    const std::string travel = travel_text(f.sample.displacement);
    char title[96];
    std::snprintf(title, sizeof title, "%s, platen travel %g mm", run.spec.variant.c_str(),
                  std::round(f.sample.displacement * 1e5) / 1e2);
    // Fragments of all three grains (the CDFs are of the top grain alone).
    const analysis::FragmentLabels labels =
        analysis::label_fragments(matched_reference(run, f.particles), f.particles);
    analysis::ParticleFigure fragments =
        analysis::fragment_figure(f.particles, analysis::resolved_fragment_ids(labels),
                                  f.sample.time, std::string("Fragments: ") + title);
    std::string path = path_in(directory, stem + "-fragments-" + travel + ".png");
    analysis::write_particle_figure(fragments, path);
    announce(path);
    if (!run.thermal) continue;
    analysis::ParticleFigure temperature =
        analysis::frame_figure(f.particles, analysis::FrameField::temperature, f.sample.time,
                               std::string("Temperature: ") + title);
    path = path_in(directory, stem + "-temperature-" + travel + ".png");
    analysis::write_particle_figure(temperature, path);
    announce(path);
  }
}

void write_force_displacement(const std::vector<ThreeGrainRun>& runs,
                              const std::string& directory) {
  analysis::PlotSpec spec;
  spec.title = "Three grains: top platen force against its travel";
  spec.x_label = "platen travel [mm]";
  spec.y_label = "platen force |F_y| [kN/m]";
  for (const ThreeGrainRun& run : runs) {
    analysis::LineSeries line;
    line.label = run.spec.variant;
    for (std::size_t k = 0; k < run.curve_force.size(); ++k) {
      line.x.push_back(run.curve_displacement[k] * 1e3);
      line.y.push_back(run.curve_force[k] * 1e-3);
    }
    if (!line.x.empty()) spec.series.push_back(std::move(line));
  }
  if (spec.series.empty()) return;
  const std::string path = path_in(directory, "force-displacement.png");
  analysis::write_line_plot(spec, path);
  announce(path);
}

void write_isothermal_vs_coupled(const ThreeGrainRun& isothermal, const ThreeGrainRun& coupled,
                                 const std::string& directory) {
  std::vector<cv::Mat> panels;
  for (const ThreeGrainRun* run : {&isothermal, &coupled}) {
    const ThreeGrainFrame& last = run->frames.back();
    char title[96];
    std::snprintf(title, sizeof title, "Damage, %s, platen travel %g mm", run->spec.variant.c_str(),
                  std::round(last.sample.displacement * 1e5) / 1e2);
    analysis::ParticleFigure figure = analysis::frame_figure(
        last.particles, analysis::FrameField::damage, last.sample.time, title);
    figure.width = 900;
    figure.height = 1200;
    panels.push_back(analysis::render_particle_figure(figure));
  }
  cv::Mat both;
  cv::hconcat(panels, both);
  const std::string path = path_in(directory, "isothermal-vs-coupled.png");
  analysis::write_png(both, path);
  announce(path);
}

}  // namespace

void write_three_grain_figures(const std::vector<ThreeGrainRun>& runs, int isothermal, int coupled,
                               const std::string& directory) {
  for (const ThreeGrainRun& run : runs) {
    write_cdfs(run, directory);
    write_frame_figures(run, directory);
  }
  write_force_displacement(runs, directory);
  if (isothermal >= 0 && coupled >= 0)
    write_isothermal_vs_coupled(runs[static_cast<std::size_t>(isothermal)],
                                runs[static_cast<std::size_t>(coupled)], directory);
}

}  // namespace fragmpm::pipeline
