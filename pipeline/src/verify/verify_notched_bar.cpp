// V6: fracture energy of a notched bar struck by a disk ([HH17] §3.3, Table III, Fig. 12-13).
// Oracle: the energy the damage law dissipates equals G_f × the crack length actually formed (per
// unit thickness in plane strain), counted row by row across the ligament so that two cracks count
// twice (formed_crack_length). A second metric is the total mechanical energy lost,
// E₀ − (kinetic + strain) at the end, which also contains contact and numerical losses; the paper
// plots that one (Fig. 13), and shows single-field MPM losing too much.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <map>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "fragmpm/analysis/crack_crossings.hpp"
#include "fragmpm/analysis/fragments.hpp"
#include "fragmpm/pipeline/embedded_scenes.hpp"
#include "fragmpm/pipeline/scene.hpp"
#include "verify_run.hpp"

namespace fragmpm::pipeline {

namespace {

constexpr double notch_centre = 27.5e-3;  // [m], scenes/verify/notched-bar.toml
constexpr double notch_depth = 2e-3;      // [m]
constexpr double bar_height = 10e-3;      // [m]

/// Crack length formed in the ligament, per unit thickness: the rows of bar particles above the
/// notch within 3 mm of its axis, each crossed once by every run of fully damaged particles and
/// every boundary between two fragments of `fragmpm analyze` (crack faces that separated while
/// their particles kept some strength count too). One crack through the ligament gives the
/// ligament; the two cracks a finer grid starts from the notch's two corners give twice it.
double formed_crack_length(const mpm::Particles<2>& reference, const mpm::Particles<2>& current,
                           double spacing) {
  const analysis::RowWindow ligament{notch_centre - 3e-3, notch_centre + 3e-3, notch_depth,
                                     bar_height, 0};
  return analysis::crack_length_across_rows(
      reference, analysis::label_fragments(reference, current), ligament, spacing);
}

/// What a variant changes in the scene's geometry.
enum class Layout {
  scene,           ///< as scenes/verify/notched-bar.toml: square notch, crack plane on a node line
  crack_mid_cell,  ///< grid from x = −4 mm: at h = 1 mm the crack plane lies in the middle of a
                   ///< cell
  rounded_notch,   ///< the notch's top a half circle of radius 1 mm (same 2 mm depth)
};

/// The bar's outline with the notch's flat top replaced by a half circle of the notch's half width,
/// its apex at the square notch's depth. With square corners a grid that resolves them (h ≤ 0.5 mm)
/// starts a crack at each corner; the rounded top concentrates the stress on the axis, where
/// [HH17] Fig. 12 draws its single crack.
std::string rounded_notch_vertices() {
  constexpr double half_width = 1e-3;  // [m]
  constexpr int segments = 24;
  std::vector<std::pair<double, double>> points{
      {0.0, 0.0},
      {notch_centre - half_width, 0.0},
      {notch_centre - half_width, notch_depth - half_width}};
  for (int k = 1; k < segments; ++k) {
    const double angle = std::numbers::pi * (1.0 - static_cast<double>(k) / segments);
    points.emplace_back(notch_centre + half_width * std::cos(angle),
                        notch_depth - half_width + half_width * std::sin(angle));
  }
  points.insert(points.end(), {{notch_centre + half_width, notch_depth - half_width},
                               {notch_centre + half_width, 0.0},
                               {55e-3, 0.0},
                               {55e-3, bar_height},
                               {0.0, bar_height}});
  std::string text = "[";
  for (std::size_t i = 0; i < points.size(); ++i)
    text += (i ? ", [" : "[") + toml_number(points[i].first) + ", " +
            toml_number(points[i].second) + "]";
  return text + "]";
}

/// partitioning "auto" or "off"; paper_length: l_ch = cell diagonal as in [HH17] Table III instead
/// of the default 1.13 h.
std::vector<VerifyRow> run_level(int level, double cell_size, const std::string& partitioning,
                                 bool paper_length, const std::string& averaging,
                                 Layout layout = Layout::scene) {
  const bool crack_mid_cell = layout == Layout::crack_mid_cell;
  std::map<std::string, std::string> overrides{{"grid.cell_size", toml_number(cell_size)},
                                               {"contact.partitioning", "\"" + partitioning + "\""},
                                               {"materials[0].averaging", "\"" + averaging + "\""},
                                               {"output.interval", "0.0"}};
  if (paper_length)
    overrides["materials[0].characteristic_length"] = toml_number(cell_size * std::sqrt(2.0));
  if (crack_mid_cell) {
    overrides["grid.min"] = "[\"-4 mm\", \"-10 mm\"]";
    overrides["grid.max"] = "[\"59 mm\", \"35 mm\"]";
  }
  if (layout == Layout::rounded_notch) overrides["bodies[0].vertices"] = rounded_notch_vertices();
  const std::string text = with_overrides(embedded_scene("verify/notched-bar.toml"), overrides);
  mpm::Problem<2> problem = parse_scene(text, "scenes/verify/notched-bar.toml");
  const auto& damage_law = std::get<mpm::RankineSoftening>(problem.materials[0].damage);
  const double fracture_energy = damage_law.fracture_energy;
  const double spacing = std::sqrt(problem.particles.volume0[0]);
  mpm::Solver<2> solver(std::move(problem));
  const mpm::Particles<2> reference = solver.particles();
  const double end_time = solver.problem().stop.end_time;
  const TimedRun timing = run_until(
      solver, end_time,
      "notched-bar " + partitioning + " " + averaging + (paper_length ? " paper-l_ch" : "") +
          (crack_mid_cell ? " crack-mid-cell" : "") +
          (layout == Layout::rounded_notch ? " rounded-notch" : "") + " " + cell_label(cell_size),
      0.0, [](const mpm::Solver<2>&) {});
  const auto& row = solver.last_row();
  const double crack = formed_crack_length(reference, solver.particles(), spacing);
  const std::string variant = std::string(partitioning == "auto" ? "partitioned" : "single-field") +
                              (averaging == "nonlocal" ? "-nonlocal" : "") +
                              (paper_length ? "-paper-l_ch" : "") +
                              (crack_mid_cell ? "-crack-mid-cell" : "") +
                              (layout == Layout::rounded_notch ? "-rounded-notch" : "");
  std::vector<VerifyRow> rows;
  VerifyRow length = level_row("notched-bar", variant, level, cell_size, solver, timing);
  length.metric = "crack_length_m (reference: one crack through the ligament)";
  length.value = crack;
  length.reference = bar_height - notch_depth;
  length.error = relative_error(crack, length.reference);
  rows.push_back(length);
  if (crack <= 0.0) return rows;  // no crack: the energy metrics have no reference
  VerifyRow damage = length;
  damage.metric = "damage_dissipation_J/m (reference: G_f x crack)";
  damage.value = row.totals.dissipated;
  damage.reference = fracture_energy * crack;
  damage.error = relative_error(damage.value, damage.reference);
  // V6 in docs/verification.md: the default (local, partitioned) within 15 % at h = 1 mm.
  if (partitioning == "auto" && !paper_length && layout == Layout::scene && averaging == "local") {
    damage.target_low = 0.85 * damage.reference;
    damage.target_high = 1.15 * damage.reference;
  }
  rows.push_back(damage);
  VerifyRow lost = length;
  lost.metric = "energy_lost_J/m (reference: G_f x crack)";
  lost.value = row.totals.initial_energy + row.totals.wall_work + row.totals.load_work +
               row.totals.gravity_work - row.kinetic - row.strain;
  lost.reference = fracture_energy * crack;
  lost.error = relative_error(lost.value, lost.reference);
  rows.push_back(lost);
  return rows;
}

}  // namespace

std::vector<VerifyRow> verify_notched_bar(const VerifyOptions& options) {
  const std::vector<double> cells =
      options.quick ? std::vector<double>{1e-3} : std::vector<double>{1e-3, 0.5e-3};
  std::vector<VerifyRow> rows;
  for (const std::string averaging : {"nonlocal", "local"})
    for (const std::string partitioning : {"auto", "off"})
      for (std::size_t level = 0; level < cells.size(); ++level)
        for (auto& r :
             run_level(static_cast<int>(level), cells[level], partitioning, false, averaging))
          rows.push_back(std::move(r));
  // [HH17] Table III's l_ch = 1.414 mm at the paper's 1 mm grid, for comparison with the paper.
  for (auto& r : run_level(0, cells[0], "auto", true, "local")) rows.push_back(std::move(r));
  // The same coarse level with the crack plane in the middle of a cell: how much the 1 mm result
  // depends on where the crack lies relative to the nodes (reported, no target).
  for (auto& r : run_level(0, cells[0], "auto", false, "local", Layout::crack_mid_cell))
    rows.push_back(std::move(r));
  // A single crack on the axis, as [HH17] Fig. 12 has it, at every level (reported, no target).
  for (std::size_t level = 0; level < cells.size(); ++level)
    for (auto& r : run_level(static_cast<int>(level), cells[level], "auto", false, "local",
                             Layout::rounded_notch))
      rows.push_back(std::move(r));
  // The third level of the default law, partitioned: whether its dissipation converges under
  // refinement (the run costs about eight times one at h = 0.5 mm).
  if (!options.quick)
    for (auto& r : run_level(2, 0.25e-3, "auto", false, "local")) rows.push_back(std::move(r));
  // The default's dissipation per crack length, G_f-normalised, must agree between h = 1 and
  // 0.5 mm within 10 %: a regularised law dissipates the same energy at every resolution.
  if (!options.quick) {
    const VerifyRow* level_row_of[2] = {nullptr, nullptr};
    for (const VerifyRow& r : rows)
      if (r.variant == "partitioned" && r.level < 2 && r.metric.rfind("damage_dissipation", 0) == 0)
        level_row_of[r.level] = &r;
    if (level_row_of[0] && level_row_of[1]) {
      VerifyRow agreement = *level_row_of[1];
      const double coarse = level_row_of[0]->value / level_row_of[0]->reference;
      const double fine = level_row_of[1]->value / level_row_of[1]->reference;
      agreement.metric = "dissipation_per_G_f_crack_1mm/0.5mm";
      agreement.value = coarse / fine;
      agreement.reference = 1.0;
      agreement.error = relative_error(agreement.value, 1.0);
      agreement.target_low = 0.9;
      agreement.target_high = 1.1;
      rows.push_back(agreement);
    }
  }
  return rows;
}

}  // namespace fragmpm::pipeline
