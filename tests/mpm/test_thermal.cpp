// Thermal module ([XLS21] §2.1-2.3, §3.1, Alg. 2): thermo-elastic stress and heating, conduction,
// thermal wall conditions, and that a scene without thermal data runs exactly as before.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "fragmpm/mpm/solver.hpp"
#include "fragmpm/mpm/thermal.hpp"
#include "fragmpm/pipeline/embedded_scenes.hpp"
#include "fragmpm/pipeline/scene.hpp"
#include "fragmpm/pipeline/verify.hpp"

using namespace fragmpm;

namespace {

/// Replaces the first occurrence of `what` in `text` by `by` (the scene must contain it).
std::string replaced(std::string text, const std::string& what, const std::string& by) {
  const auto at = text.find(what);
  if (at == std::string::npos) throw std::logic_error("scene has no '" + what + "'");
  return text.replace(at, what.size(), by);
}

double mean_temperature(const mpm::Particles<2>& P) {
  return std::accumulate(P.temperature.begin(), P.temperature.end(), 0.0) / double(P.size());
}

// A 4 × 4 mm block between four roller walls; the right and top walls move in and back out once
// (sinusoidal velocity over one period T = 40 µs, peak displacement 0.08 mm = 2 %), about ten wave
// transits, so the block is squeezed nearly uniformly and released.
const char* squeeze_scene = R"toml(
[grid]
cell_size = "0.5 mm"
min = ["-1 mm", "-1 mm"]
max = ["6 mm", "6 mm"]
[[materials]]
name = "solid"
E = "1 GPa"
nu = 0.25
density = "1000 kg/m3"
heat_capacity = "1000 J/(kg K)"
expansion = "1e-4 1/K"
temperature = "300 K"
[[bodies]]
name = "block"
material = "solid"
shape = "box"
min = ["0 mm", "0 mm"]
max = ["4 mm", "4 mm"]
[[walls]]
name = "left"
point = ["0 mm", "0 mm"]
normal = [1, 0]
kind = "roller"
[[walls]]
name = "bottom"
point = ["0 mm", "0 mm"]
normal = [0, 1]
kind = "roller"
[[walls]]
name = "right"
point = ["4 mm", "0 mm"]
normal = [-1, 0]
kind = "roller"
velocity = { type = "sinusoid", amplitude = ["-6.2832 m/s", "0 m/s"], frequency = "25 kHz" }
[[walls]]
name = "top"
point = ["0 mm", "4 mm"]
normal = [0, -1]
kind = "roller"
velocity = { type = "sinusoid", amplitude = ["0 m/s", "-6.2832 m/s"], frequency = "25 kHz" }
[stop]
end_time = "40 us"
)toml";

}  // namespace

TEST(ThermalPhysics, ThermalStressVanishesAtTheReferenceTemperatureAndIsAPressure) {
  const double K = 50e9, alpha = 1e-5;
  EXPECT_EQ(mpm::thermal_kirchhoff_pressure(K, alpha, 300.0, 300.0, 0.97), 0.0);
  // J = 1: τ_θ = −3αK(θ − θ₀): heating a clamped body puts it in compression.
  EXPECT_DOUBLE_EQ(mpm::thermal_kirchhoff_pressure(K, alpha, 310.0, 300.0, 1.0),
                   -3.0 * alpha * K * 10.0);
  const mpm::Mat<2> s = mpm::thermal_cauchy_stress<2>(K, alpha, 310.0, 300.0, 1.02);
  EXPECT_DOUBLE_EQ(s(0, 0), s(1, 1));
  EXPECT_EQ(s(0, 1), 0.0);
  EXPECT_DOUBLE_EQ(s(0, 0), -3.0 * alpha * K * 10.0 * (1.0 - std::log(1.02)) / (1.02 * 1.02));
}

TEST(ThermalPhysics, AdiabaticRatioIsAFunctionOfStateAndHeatsInCompression) {
  const double K = 50e9, alpha = 1e-5, rho = 2300.0, c = 800.0;
  const double down = mpm::adiabatic_temperature_ratio(K, alpha, rho, c, 1.0, 1.0, 0.98);
  const double up = mpm::adiabatic_temperature_ratio(K, alpha, rho, c, 1.0, 0.98, 1.0);
  EXPECT_GT(down, 1.0);
  EXPECT_NEAR(down * up, 1.0, 1e-15);
  // Small change: θ̇/θ = −3α U″(J) J̇ /(ρ₀ c) with U″(1) = K ([XLS21] eq. (39)).
  const double small = mpm::adiabatic_temperature_ratio(K, alpha, rho, c, 1.0, 1.0, 1.0 - 1e-6);
  EXPECT_NEAR((small - 1.0) / 1e-6, 3.0 * alpha * K / (rho * c),
              1e-5 * 3.0 * alpha * K / (rho * c));
  // Fully damaged and isotropically degraded: no coupling left.
  EXPECT_EQ(mpm::adiabatic_temperature_ratio(K, alpha, rho, c, 0.0, 1.0, 0.9), 1.0);
  EXPECT_EQ(mpm::coupling_fraction(0.5, mpm::Degradation::isotropic, 0.9), 0.5);
  EXPECT_EQ(mpm::coupling_fraction(0.5, mpm::Degradation::tensile_spectral, 0.9), 1.0);
  EXPECT_EQ(mpm::coupling_fraction(0.5, mpm::Degradation::tensile_spectral, 1.1), 0.5);
}

TEST(ThermalPhysics, DamageHeatIsTheReleasedEnergyPlusTheCouplingTerm) {
  // (ψ̄ + 3αθ₀U′(J)) Δd, [XLS21] eq. (28) and 40.
  const double K = 10e9, alpha = 2e-5, theta0 = 290.0, J = 1.01, psi = 3e5;
  const double expected = (psi + 3.0 * alpha * theta0 * K * std::log(J) / J) * 0.25;
  EXPECT_DOUBLE_EQ(mpm::damage_heat_density(psi, K, alpha, theta0, J, 0.25), expected);
  EXPECT_DOUBLE_EQ(mpm::damage_heat_density(psi, K, 0.0, theta0, J, 0.25), psi * 0.25);
}

TEST(ThermalSolver, AdiabaticCompressReleaseCycleReturnsToTheStartingTemperature) {
  auto problem = pipeline::parse_scene(squeeze_scene, "squeeze.toml");
  ASSERT_TRUE(problem.thermal.active());
  ASSERT_EQ(problem.particles.temperature.size(), problem.particles.size());
  const double K = problem.materials[0].bulk_modulus, alpha = 1e-4, rho = 1000.0, c = 1000.0;
  mpm::Solver<2> solver(std::move(problem));
  double hottest = 300.0;
  while (solver.time() < 40e-6 * (1.0 - 1e-12)) {
    auto failure = solver.step(40e-6 - solver.time());
    ASSERT_FALSE(failure) << failure->what;
    hottest = std::max(hottest, mean_temperature(solver.particles()));
  }
  // The thermal stage books the volume change of the previous mechanical step; a vanishing step
  // books the last one and moves nothing.
  ASSERT_FALSE(solver.step(1e-15));
  const auto& P = solver.particles();
  // Every particle sits on its own adiabat θ = θ_start exp(−3α(U′(J) − U′(1))/(ρ₀c)): the heating
  // of the squeeze is given back exactly on release ([XLS21] eq. (39) integrated exactly, κ = 0).
  double worst = 0.0;
  for (std::size_t p = 0; p < P.size(); ++p) {
    const double adiabat =
        300.0 * mpm::adiabatic_temperature_ratio(K, alpha, rho, c, 1.0, 1.0, P.F[p].determinant());
    worst = std::max(worst, std::abs(P.temperature[p] - adiabat));
  }
  EXPECT_LT(worst, 1e-9 * 300.0);
  // The squeeze (ΔJ ≈ −4 %) heats by about 3αK|Δ ln J|θ/(ρc) ≈ 2.5 K; after the release the block
  // is back at 300 K up to what its residual vibration holds.
  EXPECT_GT(hottest - 300.0, 1.5);
  EXPECT_LT(std::abs(mean_temperature(P) - 300.0), 0.02 * (hottest - 300.0));
  EXPECT_GT(solver.last_row().thermal, -1.0);  // series value is finite and booked
}

TEST(ThermalSolver, SceneWithoutThermalDataHasNoThermalArrays) {
  std::string text = squeeze_scene;
  text = replaced(text, "heat_capacity = \"1000 J/(kg K)\"\n", "");
  text = replaced(text, "expansion = \"1e-4 1/K\"\n", "");
  text = replaced(text, "temperature = \"300 K\"\n", "");
  auto problem = pipeline::parse_scene(text, "squeeze.toml");
  EXPECT_FALSE(problem.thermal.active());
  EXPECT_TRUE(problem.particles.temperature.empty());
  const auto plan = mpm::plan_modules<2>(problem);
  bool listed = false;
  for (const auto& m : plan) {
    if (m.module != "thermal") continue;
    listed = true;
    EXPECT_FALSE(m.active);
  }
  EXPECT_TRUE(listed);
}

TEST(ThermalSolver, ZeroCouplingLeavesTheMechanicsBitIdentical) {
  // Two bodies with damage exercise the partitioned path. Thermal data with α = 0 (and heat from
  // damage and conduction flowing) must not change one bit of the mechanics.
  const std::string base = R"toml(
[grid]
cell_size = "1 mm"
min = ["-2 mm", "-2 mm"]
max = ["30 mm", "20 mm"]
[[materials]]
name = "rock"
E = "10 GPa"
nu = 0.2
density = "2500 kg/m3"
damage = "rankine"
strength = "5 MPa"
fracture_energy = "20 J/m2"
THERMAL
[[bodies]]
name = "a"
material = "rock"
shape = "disk"
center = ["8 mm", "8 mm"]
radius = "5 mm"
velocity = ["20 m/s", "0 m/s"]
[[bodies]]
name = "b"
material = "rock"
shape = "disk"
center = ["19 mm", "8.5 mm"]
radius = "5 mm"
velocity = ["-20 m/s", "0 m/s"]
[stop]
max_steps = 150
)toml";
  auto off = pipeline::parse_scene(replaced(base, "THERMAL", ""), "off.toml");
  auto on = pipeline::parse_scene(
      replaced(base, "THERMAL",
               "heat_capacity = \"800 J/(kg K)\"\nconductivity = \"0 W/(m K)\"\nexpansion = 0"),
      "on.toml");
  ASSERT_FALSE(off.thermal.active());
  ASSERT_TRUE(on.thermal.active());
  mpm::Solver<2> a(std::move(off)), b(std::move(on));
  for (int s = 0; s < 150; ++s) {
    ASSERT_FALSE(a.step());
    ASSERT_FALSE(b.step());
    ASSERT_EQ(a.last_row().dt, b.last_row().dt);
  }
  const auto &P = a.particles(), &Q = b.particles();
  double damaged = 0.0;
  for (std::size_t p = 0; p < P.size(); ++p) {
    ASSERT_EQ(P.x[p], Q.x[p]) << p;
    ASSERT_EQ(P.v[p], Q.v[p]) << p;
    ASSERT_EQ(P.stress[p], Q.stress[p]) << p;
    ASSERT_EQ(P.damage[p], Q.damage[p]) << p;
    damaged += P.damage[p];
  }
  EXPECT_GT(damaged, 0.0);  // the impact did crack the disks, so damage heating ran
  // Damage heat: with α = 0 and κ = 0 the heat content equals the recorded damage dissipation once
  // a vanishing step has booked the last mechanical step's damage.
  ASSERT_FALSE(b.step(1e-15));
  EXPECT_NEAR(b.last_row().thermal, b.accumulators().dissipated,
              1e-9 * b.accumulators().dissipated);
}

TEST(ThermalSolver, ConductionMatchesTheErfcSolution) {
  pipeline::VerifyOptions options;
  options.quick = true;
  const auto rows = pipeline::verify_conduction(options);
  ASSERT_EQ(rows.size(), 6u);
  for (std::size_t k = 0; k + 2 < rows.size(); ++k)
    EXPECT_LT(rows[k + 2].value, rows[k].value);  // refines
  EXPECT_LT(rows[4].value, 0.01);                 // finest quick level, 1 ms
  EXPECT_LT(rows[5].value, 0.01);                 // 4 ms
}

TEST(ThermalSolver, ContactFaceTemperaturesOfPressedBlocksMatchEq90) {
  // V3: steady conduction through two pressed blocks with h_c = γ̄|p| ([XLS21] eq. (13), (90)),
  // three pressures; the contact heat uses the step's normal contact impulse (eq. (82)).
  pipeline::VerifyOptions options;
  options.quick = true;
  const auto rows = pipeline::verify_contact_temperature(options);
  ASSERT_EQ(rows.size(), 6u);
  for (const auto& r : rows) EXPECT_LT(r.error, 0.3) << r.variant << " " << r.metric;
  // The jump across the interface shrinks as the pressure (κ̄) grows.
  EXPECT_GT(rows[0].value - rows[1].value, rows[2].value - rows[3].value);
  EXPECT_GT(rows[2].value - rows[3].value, rows[4].value - rows[5].value);
}

namespace {

// A still strip 4 × 1 mm, insulated except where a test adds heat at x = 0.
const char* strip_scene = R"toml(
[grid]
cell_size = "0.5 mm"
min = ["-1 mm", "-1 mm"]
max = ["6 mm", "3 mm"]
[[materials]]
name = "solid"
E = "10 kPa"
nu = 0.3
density = "1000 kg/m3"
heat_capacity = "100 J/(kg K)"
conductivity = "10 W/(m K)"
temperature = "300 K"
[[bodies]]
name = "strip"
material = "solid"
shape = "box"
min = ["0 mm", "0 mm"]
max = ["4 mm", "1 mm"]
HEAT
[stop]
end_time = "2 ms"
)toml";

double heat_after(const std::string& heat, double end_time) {
  auto problem = pipeline::parse_scene(replaced(strip_scene, "HEAT", heat), "strip.toml");
  EXPECT_TRUE(problem.thermal.active());
  mpm::Solver<2> solver(std::move(problem));
  while (solver.time() < end_time * (1.0 - 1e-12)) {
    auto failure = solver.step(end_time - solver.time());
    if (failure) ADD_FAILURE() << failure->what;
    if (failure) break;
  }
  EXPECT_FALSE(solver.step(1e-15));  // books nothing new; keeps the last row current
  return solver.last_row().thermal;
}

}  // namespace

TEST(ThermalBoundary, FluxThroughAThermalPlaneAddsExactlyQTimesFaceTimesTime) {
  // [XLS21] eq. (57): Q_i = ∫ S_i q̄ dΓ; the face length per node from ∮ S_i n dΓ = ∫ ∇S_i dV sums
  // to the face, 1 mm, so the heat content grows by q̄ · 1 mm · t.
  const double heat = heat_after(R"toml(
[[walls]]
name = "heater"
point = ["0 mm", "0 mm"]
normal = [1, 0]
kind = "thermal"
thermal = { flux = "2 MW/m2" }
)toml",
                                 1e-3);
  EXPECT_NEAR(heat, 2e6 * 1e-3 * 1e-3, 1e-9 * 2.0);
}

TEST(ThermalBoundary, HeatFluxLoadOnABodyEdgeAddsExactlyQTimesEdgeTimesTime) {
  const double heat = heat_after(R"toml(
[[loads]]
name = "heater"
body = "strip"
side = "-x"
heat_flux = "-1 MW/m2"
)toml",
                                 1e-3);
  EXPECT_NEAR(heat, -1e6 * 1e-3 * 1e-3, 1e-9);
}

TEST(ThermalBoundary, ConvectionRelaxesTowardsTheAmbientWithoutOvershoot) {
  const double heat = heat_after(R"toml(
[[walls]]
name = "air"
point = ["4 mm", "0 mm"]
normal = [-1, 0]
kind = "thermal"
thermal = { film_coefficient = "1 kW/(m2 K)", ambient = "400 K" }
)toml",
                                 2e-3);
  // Heat flows in at h (θ_∞ − θ) A: at most h ΔT A t = 1e3 · 100 · 1e-3 · 2e-3 = 0.2 J/m, and only
  // a little less because the face warms slowly (capacity m c = 1000 · 4e-6 · 100 = 0.4 J/(K m)).
  EXPECT_GT(heat, 0.95 * 0.2);
  EXPECT_LT(heat, 0.2);
}

TEST(ThermalScene, ThermalDataWithoutHeatCapacityIsRefusedWithFileLineAndKey) {
  std::string text = replaced(squeeze_scene, "heat_capacity = \"1000 J/(kg K)\"\n", "");
  try {
    pipeline::parse_scene(text, "squeeze.toml");
    FAIL() << "expected a scene error";
  } catch (const pipeline::SceneError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("squeeze.toml"), std::string::npos) << what;
    EXPECT_NE(what.find("heat_capacity"), std::string::npos) << what;
  }
  EXPECT_THROW(
      pipeline::parse_scene(replaced(squeeze_scene, "\"1e-4 1/K\"", "\"5 m\""), "squeeze.toml"),
      pipeline::SceneError);
}

TEST(ThermalContact, FrictionalHeatEqualsFrictionWorkAtAWall) {
  // A block sliding on a floor with Coulomb friction: all friction work of the wall ([NBS18] eq.
  // (27)) becomes heat of the block, so the heat content equals /series/friction_work.
  const char* scene = R"toml(
[grid]
cell_size = "1 mm"
min = ["-2 mm", "-2 mm"]
max = ["40 mm", "10 mm"]
[physics]
gravity = ["0 m/s2", "-9.81e5 m/s2"]
[[materials]]
name = "block"
E = "100 MPa"
nu = 0.3
density = "1000 kg/m3"
heat_capacity = "500 J/(kg K)"
conductivity = "5 W/(m K)"
[[bodies]]
name = "block"
material = "block"
shape = "box"
min = ["2 mm", "0 mm"]
max = ["10 mm", "4 mm"]
velocity = ["5 m/s", "0 m/s"]
[[walls]]
name = "floor"
point = ["0 mm", "0 mm"]
normal = [0, 1]
kind = "contact"
friction = 0.3
[stop]
max_steps = 400
)toml";
  mpm::Solver<2> solver(pipeline::parse_scene(scene, "slide.toml"));
  for (int s = 0; s < 400; ++s) ASSERT_FALSE(solver.step());
  const double work = solver.accumulators().friction_work;
  EXPECT_GT(work, 0.0);
  EXPECT_NEAR(solver.last_row().thermal, work, 1e-9 * work);
}

namespace {

/// Capacity-weighted projection of `body`'s particle temperatures onto the node row y (the nodal
/// temperature of the solver's heat equation, [XLS21] Alg. 2 line 19) for undeformed axis-aligned
/// particle domains of a problem uniform in x: the weight is the mean of the hat over the domain.
/// body = −1: all bodies (the node temperature of merged fields).
double node_row_temperature(const mpm::Particles<2>& P, int body, double y, double h) {
  auto integral = [&](double s) {
    const double t = std::clamp((s - y) / h, -1.0, 1.0);
    return h * (t <= 0.0 ? 0.5 * (1.0 + t) * (1.0 + t) : 1.0 - 0.5 * (1.0 - t) * (1.0 - t));
  };
  double weight = 0.0, heat = 0.0;
  for (std::size_t p = 0; p < P.size(); ++p) {
    if (body >= 0 && P.body[p] != body) continue;
    const double half = 0.5 * (std::abs(P.domain[p](1, 0)) + std::abs(P.domain[p](1, 1)));
    const double w =
        (integral(P.x[p][1] + half) - integral(P.x[p][1] - half)) / (2.0 * half) * P.mass[p];
    weight += w;
    heat += w * P.temperature[p];
  }
  return heat / weight;
}

}  // namespace

TEST(ThermalContact, PerfectlyConductingContactPassesTheBulkFlux) {
  // The pressed blocks of V3 with an enormous conductance: the contact nodes are merged into one
  // thermal field (merge_perfect_contacts), so the contact conducts like the bulk. Steady state:
  // one linear profile from 20 °C to 50 °C over 5 mm, the same flux κ ΔT / L in both blocks, no
  // jump at the interface.
  auto problem = pipeline::parse_scene(
      pipeline::with_overrides(
          pipeline::embedded_scene("verify/contact-temperature.toml"),
          {{"contact.conductance", "\"1e12 W/(m2 K)\""}, {"output.interval", "0.0"}}),
      "contact-temperature.toml");
  const double end = problem.stop.end_time, h = problem.grid.cell_size;
  mpm::Solver<2> solver(std::move(problem));
  while (solver.time() < end * (1.0 - 1e-12)) ASSERT_FALSE(solver.step(end - solver.time()));
  const auto& P = solver.particles();
  // The merged interface node holds the mean of the linear profile.
  EXPECT_NEAR(node_row_temperature(P, -1, 2.5e-3, h), 308.15, 0.01);
  const double bulk_gradient = 30.0 / 5e-3;  // [K/m]
  const double lower_gradient =
      (node_row_temperature(P, 0, 2.0e-3, h) - node_row_temperature(P, 0, 0.5e-3, h)) / 1.5e-3;
  const double upper_gradient =
      (node_row_temperature(P, 1, 4.5e-3, h) - node_row_temperature(P, 1, 3.0e-3, h)) / 1.5e-3;
  EXPECT_NEAR(lower_gradient, bulk_gradient, 1e-4 * bulk_gradient);
  EXPECT_NEAR(upper_gradient, bulk_gradient, 1e-4 * bulk_gradient);
}

TEST(ThermalContact, ThermalSofteningFrictionVanishesAtTheDamageTemperature) {
  // A slider pushed onto a base by gravity slides with μ(θ) = μ₀⟨θ_dam − θ⟩²/(θ_dam − θ_ref)²
  // ([XLS21] eq. (15)), θ from the nodal temperatures of the two fields: at θ_ref it does friction
  // work, at and above θ_dam none at all.
  const std::string scene = R"toml(
[grid]
cell_size = "1 mm"
min = ["-2 mm", "-2 mm"]
max = ["40 mm", "12 mm"]
[physics]
gravity = ["0 m/s2", "-1e5 m/s2"]
[[materials]]
name = "m"
E = "100 MPa"
nu = 0.3
density = "1000 kg/m3"
heat_capacity = "500 J/(kg K)"
temperature = "TEMP"
[[bodies]]
name = "base"
material = "m"
shape = "box"
min = ["0 mm", "0 mm"]
max = ["38 mm", "4 mm"]
[[bodies]]
name = "slider"
material = "m"
shape = "box"
min = ["4 mm", "4 mm"]
max = ["12 mm", "8 mm"]
velocity = ["3 m/s", "0 m/s"]
[[walls]]
name = "floor"
point = ["0 mm", "0 mm"]
normal = [0, 1]
kind = "fixed"
[contact]
partitioning = "bodies"
friction = { law = "thermal-softening", mu = 0.5, theta_ref = "300 K", theta_dam = "400 K" }
[stop]
max_steps = 300
)toml";
  auto friction_work = [&](const std::string& temperature) {
    mpm::Solver<2> solver(
        pipeline::parse_scene(replaced(scene, "TEMP", temperature), "slider.toml"));
    for (int s = 0; s < 300; ++s) {
      auto failure = solver.step();
      if (failure) ADD_FAILURE() << failure->what;
      if (failure) break;
    }
    return solver.accumulators().friction_work;
  };
  const double cold = friction_work("300 K");
  EXPECT_GT(cold, 0.0);
  // At θ_dam itself μ is zero up to the round-off of the nodal re-projection of θ = 400 K.
  EXPECT_LT(friction_work("400 K"), 1e-20 * cold);
  EXPECT_EQ(friction_work("450 K"), 0.0);
}

TEST(ThermalSolver, TemperaturePicFractionKeepsTheRangeAndConservesHeat) {
  // Two bonded blocks at 400 K and 300 K with conductivities 100 and 0.01 W/(m K), drifting at
  // 0.1 m/s so cells come to hold both (scenes/stability/conductivity-contrast.toml). No heat
  // source: the maximum principle bounds every temperature by [300, 400] K. The incremental update
  // of [XLS21] eq. (62) alone carries particles past 400 K; with ζ_θ = 0.05 (the scene's value)
  // they stay inside. Heat content is conserved either way.
  const std::string scene = pipeline::embedded_scene("stability/conductivity-contrast.toml");
  double hottest[2] = {0.0, 0.0};
  for (int run = 0; run < 2; ++run) {
    const std::string text =
        run == 0 ? replaced(scene, "thermal_pic_fraction = 0.05", "thermal_pic_fraction = 0")
                 : scene;
    mpm::Solver<2> solver(pipeline::parse_scene(text, "conductivity-contrast.toml"));
    const double heat0 = mpm::thermal_energy<2>(solver.problem(), solver.particles());
    for (int s = 0; s < 300; ++s) ASSERT_FALSE(solver.step());  // the scene's max_steps
    const auto& T = solver.particles().temperature;
    hottest[run] = *std::max_element(T.begin(), T.end());
    const double coldest = *std::min_element(T.begin(), T.end());
    const double heat = mpm::thermal_energy<2>(solver.problem(), solver.particles());
    const auto& mass = solver.particles().mass;
    const double scale =
        std::accumulate(mass.begin(), mass.end(), 0.0) * 1000.0 * 100.0;  // C ΔT [J/m]
    EXPECT_LT(std::abs(heat - heat0) / scale, 1e-12) << "run " << run;
    EXPECT_GE(coldest, 300.0 - 1e-9) << "run " << run;
  }
  EXPECT_GT(hottest[0], 401.0);  // eq. (62) alone overshoots (407.8 K)
  EXPECT_LE(hottest[1], 400.0 + 1e-9);
}
