// Phase-field panels at a paper's time points (phase_field_snapshots.hpp).
#include "phase_field_snapshots.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <opencv2/core.hpp>
#include <utility>

#include "fragmpm/analysis/frame_figure.hpp"
#include "fragmpm/analysis/particle_figure.hpp"
#include "fragmpm/analysis/png_file.hpp"
#include "fragmpm/mpm/current_domain.hpp"

namespace fragmpm::pipeline {

PhaseFieldSnapshots phase_field_snapshots(const std::vector<double>& wanted_us) {
  PhaseFieldSnapshots s;
  for (double t : wanted_us) s.wanted.push_back(t * 1e-6);
  return s;
}

namespace {

bool snapshot_due(const PhaseFieldSnapshots& snapshots, double time) {
  const std::size_t next = snapshots.frames.size();
  return next < snapshots.wanted.size() && time >= snapshots.wanted[next] - 1e-9;
}

}  // namespace

void take_snapshot(PhaseFieldSnapshots& snapshots, const mpm::Solver<2>& solver) {
  if (!snapshot_due(snapshots, solver.time())) return;
  snapshots.frames.push_back(
      mpm::with_current_domains<2>(solver.particles(), solver.problem().grid.shape_function));
  snapshots.times.push_back(solver.time());
}

void take_snapshot(PhaseFieldSnapshots& snapshots, mpm::Particles<2> frame, double time) {
  if (!snapshot_due(snapshots, time)) return;
  snapshots.frames.push_back(std::move(frame));
  snapshots.times.push_back(time);
}

void write_phase_field_panels(const PhaseFieldSnapshots& snapshots, const std::string& png_path,
                              const std::string& title) {
  if (snapshots.frames.empty()) return;
  // Two panels to a row for four time points (the paper's 2 × 2 figures), three for more.
  const std::size_t columns = snapshots.frames.size() <= 4 ? 2 : 3;
  std::vector<cv::Mat> panels;
  for (std::size_t k = 0; k < snapshots.frames.size(); ++k) {
    analysis::ParticleFigure figure = analysis::frame_figure(
        snapshots.frames[k], analysis::FrameField::damage, snapshots.times[k], title);
    figure.field_name = "phase field d";
    figure.width = 900;
    figure.height = 700;
    panels.push_back(analysis::render_particle_figure(figure));
  }
  // A short last row is filled with white panels of the same size.
  while (panels.size() % columns != 0)
    panels.emplace_back(panels.front().size(), panels.front().type(), cv::Scalar(255, 255, 255));
  std::vector<cv::Mat> rows;
  for (std::size_t k = 0; k < panels.size(); k += columns) {
    cv::Mat row;
    cv::hconcat(std::vector<cv::Mat>(panels.begin() + static_cast<std::ptrdiff_t>(k),
                                     panels.begin() + static_cast<std::ptrdiff_t>(k + columns)),
                row);
    rows.push_back(row);
  }
  cv::Mat all;
  cv::vconcat(rows, all);
  const std::filesystem::path path(png_path);
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  analysis::write_png(all, png_path);
  std::fprintf(stderr, "written %s\n", png_path.c_str());
}

}  // namespace fragmpm::pipeline
