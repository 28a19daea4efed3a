// Fracture energy of a bar pulled apart (docs/verification.md, `bar-tension`). Closed-form oracle:
// a crack that crosses the ligament dissipates G_f × ligament per unit thickness, whatever the
// resolution. A crack band regularised by l_ch dissipates G_f / l_ch per unit volume of fully
// damaged material ([XLS21] eq. (19)-(21)), so the oracle holds only if the band that forms is
// l_ch wide. The case reports the band's width beside the dissipation, which tells why a level
// misses: a band n particle rows wide dissipates about n s / l_ch times G_f × ligament.
//
// The same bar with the time-to-failure law ([HH17] §2.7) checks the crack speed: a particle whose
// stress exceeds σ_f loses its stiffness over τ = l_ch / c_f. Were a particle to start failing only
// when the one behind it had finished, the crack would run at c_f with l_ch the particle size s;
// it starts earlier, on the stress the failing neighbour sheds, and with l_ch = s the crack runs
// at about 1.4 c_f. [HH17] §2.7 takes l_ch = the cell diagonal (2√2 s with two particles per
// cell), the default, which this case checks against c_f. The bottom particle of the weaker
// column is 20 % weaker still and the grips pull slowly (0.1 m/s each), so a single crack starts
// at the bottom face and runs up the column driven by its own stress concentration, long before
// the uniform stress reaches the column's strength (the ends next to the grips are made stronger,
// so the grips' corner stresses do not break the bar first). Its speed is the least-squares slope
// of the failed particles' heights against their failure times, first and last particle left out.
#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "fragmpm/pipeline/embedded_scenes.hpp"
#include "fragmpm/pipeline/scene.hpp"
#include "verify_run.hpp"

namespace fragmpm::pipeline {

namespace {

constexpr double ligament = 4e-3;     // [m]: the bar's height, scenes/verify/bar-tension.toml
constexpr double mid_length = 10e-3;  // [m]
constexpr double weaker = 0.98;
constexpr double fully_damaged = 0.99;

/// Width of the fully damaged band: its area over the ligament (per unit thickness).
double band_width(const mpm::Particles<2>& P) {
  double area = 0.0;
  for (std::size_t p = 0; p < P.size(); ++p)
    if (P.damage[p] >= fully_damaged) area += P.volume0[p];
  return area / ligament;
}

/// length_over_cell: l_ch / h, or 0 for the scene's default l_ch. column_strength: the weaker
/// column's strength over σ_f.
std::vector<VerifyRow> run_level(int level, double cell_size, double length_over_cell,
                                 const std::string& averaging, double column_strength,
                                 const std::string& variant) {
  std::map<std::string, std::string> overrides{{"grid.cell_size", toml_number(cell_size)},
                                               {"materials[0].averaging", "\"" + averaging + "\""},
                                               {"output.interval", "0.0"}};
  if (length_over_cell > 0.0)
    overrides["materials[0].characteristic_length"] = toml_number(cell_size * length_over_cell);
  const std::string text = with_overrides(embedded_scene("verify/bar-tension.toml"), overrides);
  mpm::Problem<2> problem = parse_scene(text, "scenes/verify/bar-tension.toml");
  // The imperfection that picks where the crack forms: the particle column just right of
  // mid-length is weaker (2 % in the calibrated case), so one row of particles reaches σ_f first.
  auto& P = problem.particles;
  const double spacing = std::sqrt(P.volume0[0]);
  for (std::size_t p = 0; p < P.size(); ++p)
    if (P.x[p][0] > mid_length && P.x[p][0] < mid_length + spacing)
      P.strength[p] *= column_strength;
  const auto& law = std::get<mpm::RankineSoftening>(problem.materials[0].damage);
  const double fracture_energy = law.fracture_energy;
  const double set_length = problem.materials[0].characteristic_length;
  const double characteristic_length =
      set_length > 0.0 ? set_length
                       : mpm::characteristic_length<2>(problem.materials[0],
                                                       problem.particles.volume0[0], cell_size);
  mpm::Solver<2> solver(std::move(problem));
  const double end_time = solver.problem().stop.end_time;
  const TimedRun timing =
      run_until(solver, end_time, "bar-tension " + variant + " " + cell_label(cell_size), 0.0,
                [](const mpm::Solver<2>&) {});
  std::vector<VerifyRow> rows;
  VerifyRow dissipation = level_row("bar-tension", variant, level, cell_size, solver, timing);
  dissipation.metric = "damage_dissipation_J/m (reference: G_f x ligament)";
  dissipation.value = solver.last_row().totals.dissipated;
  dissipation.reference = fracture_energy * ligament;
  dissipation.error = relative_error(dissipation.value, dissipation.reference);
  // docs/verification.md: the default (local) law within 5 % at every level; the nonlocal law and
  // the 20 % flaw are labelled variants whose results are listed under the known shortfalls.
  if (length_over_cell == 0.0 && averaging == "local" && column_strength == weaker) {
    dissipation.target_low = 0.95 * dissipation.reference;
    dissipation.target_high = 1.05 * dissipation.reference;
  }
  rows.push_back(dissipation);
  VerifyRow band = dissipation;
  band.metric = "band_width_m (reference: l_ch)";
  band.value = band_width(solver.particles());
  band.reference = characteristic_length;
  band.error = relative_error(band.value, band.reference);
  band.target_low = -std::numeric_limits<double>::infinity();
  band.target_high = std::numeric_limits<double>::infinity();
  rows.push_back(band);
  return rows;
}

constexpr double crack_speed = 2000.0;  // c_f [m/s]

/// length_over_particle: l_ch / s for τ = l_ch / c_f, or 0 for the default (the cell diagonal).
std::vector<VerifyRow> run_crack_speed(int level, double cell_size, double length_over_particle,
                                       const std::string& variant) {
  std::string text = embedded_scene("verify/bar-tension.toml");
  const auto replace = [&text](const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    if (at == std::string::npos)
      throw std::runtime_error("bar-tension: the scene no longer holds '" + from + "'");
    text.replace(at, from.size(), to);
  };
  replace("damage = \"rankine\"", "damage = \"time-to-failure\"\ncrack_speed = \"2 km/s\"");
  replace("fracture_energy = \"0.1 N/mm\"", "");
  std::map<std::string, std::string> overrides{
      {"grid.cell_size", toml_number(cell_size)},
      {"output.interval", "0.0"},
      {"stop.end_time", "\"70 us\""},
      {"walls[0].velocity.to", "[\"-0.1 m/s\", \"0 m/s\"]"},
      {"walls[1].velocity.to", "[\"0.1 m/s\", \"0 m/s\"]"}};
  mpm::Problem<2> probe = parse_scene(with_overrides(text, overrides), "bar-tension.toml");
  const double spacing = std::sqrt(probe.particles.volume0[0]);
  if (length_over_particle > 0.0)
    overrides["materials[0].characteristic_length"] = toml_number(spacing * length_over_particle);
  mpm::Problem<2> problem =
      parse_scene(with_overrides(text, overrides), "scenes/verify/bar-tension.toml");
  auto& P = problem.particles;
  std::vector<std::size_t> column;
  for (std::size_t p = 0; p < P.size(); ++p)
    if (P.x[p][0] > mid_length && P.x[p][0] < mid_length + spacing) {
      P.strength[p] *= weaker;
      column.push_back(p);
    }
  // The grips hold whole node columns, which concentrates stress at the bar's corners; at h =
  // 0.25 mm that alone breaks the bar at a grip first. The 2 mm next to each grip are made 50 %
  // stronger so the crack forms at the seed.
  for (std::size_t p = 0; p < P.size(); ++p)
    if (P.x[p][0] < 2e-3 || P.x[p][0] > 2.0 * mid_length - 2e-3) P.strength[p] *= 1.5;
  std::sort(column.begin(), column.end(),
            [&P](std::size_t a, std::size_t b) { return P.x[a][1] < P.x[b][1]; });
  P.strength[column.front()] *= 0.8;
  const double tau_length =
      mpm::characteristic_length<2>(problem.materials[0], P.volume0[0], cell_size);
  // The crack may step into a neighbouring column: a height counts as cracked when any particle
  // within two spacings of the weaker column at that height is fully damaged.
  std::vector<std::vector<std::size_t>> rows_at(column.size());
  for (std::size_t p = 0; p < P.size(); ++p)
    for (std::size_t k = 0; k < column.size(); ++k)
      if (std::abs(P.x[p][1] - P.x[column[k]][1]) < 0.5 * spacing &&
          std::abs(P.x[p][0] - P.x[column[k]][0]) < 2.5 * spacing)
        rows_at[k].push_back(p);
  std::vector<double> heights(column.size());
  for (std::size_t k = 0; k < column.size(); ++k) heights[k] = P.x[column[k]][1];
  std::vector<double> failed_at(column.size(), -1.0);
  mpm::Solver<2> solver(std::move(problem));
  const TimedRun timing =
      run_until(solver, solver.problem().stop.end_time,
                "bar-tension crack speed " + variant + " " + cell_label(cell_size), 0.0,
                [&](const mpm::Solver<2>& s) {
                  for (std::size_t k = 0; k < column.size(); ++k)
                    if (failed_at[k] < 0.0)
                      for (std::size_t p : rows_at[k])
                        if (s.particles().damage[p] >= fully_damaged) {
                          failed_at[k] = s.time();
                          break;
                        }
                });
  // Least squares of height against failure time over the particles between the first and last.
  double n = 0.0, st = 0.0, sy = 0.0, stt = 0.0, sty = 0.0, first = -1.0, last = -1.0;
  for (std::size_t k = 1; k + 1 < column.size(); ++k) {
    if (failed_at[k] < 0.0) continue;
    const double t = failed_at[k], y = heights[k];
    n += 1.0;
    st += t;
    sy += y;
    stt += t * t;
    sty += t * y;
    first = first < 0.0 ? t : std::min(first, t);
    last = std::max(last, t);
  }
  const double denominator = n * stt - st * st;
  VerifyRow speed = level_row("bar-tension", variant, level, cell_size, solver, timing);
  speed.metric = "crack_speed_m/s (reference: c_f)";
  speed.value = n >= 3.0 && denominator > 0.0 ? (n * sty - st * sy) / denominator : 0.0;
  speed.reference = crack_speed;
  speed.error = relative_error(speed.value, speed.reference);
  if (length_over_particle == 0.0) {  // docs/verification.md: within 10 % of c_f
    speed.target_low = 0.9 * crack_speed;
    speed.target_high = 1.1 * crack_speed;
  }
  std::vector<VerifyRow> rows{speed};
  VerifyRow tau = speed;
  tau.metric = "failed_column_fraction (reference: 1)";
  tau.value = n / double(column.size() >= 2 ? column.size() - 2 : 1);
  tau.reference = 1.0;
  tau.error = relative_error(tau.value, 1.0);
  tau.target_low = -std::numeric_limits<double>::infinity();
  tau.target_high = std::numeric_limits<double>::infinity();
  rows.push_back(tau);
  std::fprintf(
      stderr,
      "    tau = l_ch / c_f = %.4g us (l_ch = %.4g mm); column failed from %.4g to %.4g us\n",
      tau_length / crack_speed * 1e6, tau_length * 1e3, first * 1e6, last * 1e6);
  return rows;
}

}  // namespace

std::vector<VerifyRow> verify_bar_tension(const VerifyOptions& options) {
  std::vector<double> cells{0.5e-3, 0.25e-3};
  if (!options.quick) cells.push_back(0.125e-3);
  std::vector<VerifyRow> rows;
  struct Variant {
    double length_over_cell;
    const char* averaging;
    double column_strength;
    const char* name;
  };
  // The flaw variant shows what the default l_ch was calibrated on: with a column 20 % weaker
  // instead of 2 %, the neighbouring rows never come near σ_f and do not soften, and the same
  // law dissipates about 0.7 G_f (docs/verification.md, "Known shortfalls").
  const Variant variants[] = {{0.0, "local", weaker, "l_ch-default"},
                              {1.0, "local", weaker, "l_ch-cell-size"},
                              {std::sqrt(2.0), "local", weaker, "l_ch-cell-diagonal"},
                              {0.0, "nonlocal", weaker, "nonlocal-default"},
                              {0.0, "local", 0.8, "l_ch-default-flaw-20%"}};
  for (const Variant& v : variants)
    for (std::size_t level = 0; level < cells.size(); ++level)
      for (auto& r : run_level(static_cast<int>(level), cells[level], v.length_over_cell,
                               v.averaging, v.column_strength, v.name))
        rows.push_back(std::move(r));
  // Time to failure: τ from the cell diagonal (the default, [HH17] §2.7) and from the particle
  // size.
  const std::vector<std::pair<double, std::string>> speed_variants{{0.0, "ttf-default"},
                                                                   {1.0, "ttf-tau-particle"}};
  for (const auto& [length_over_particle, variant] : speed_variants)
    for (std::size_t level = 0; level < cells.size(); ++level)
      for (auto& r :
           run_crack_speed(static_cast<int>(level), cells[level], length_over_particle, variant))
        rows.push_back(std::move(r));
  return rows;
}

}  // namespace fragmpm::pipeline
