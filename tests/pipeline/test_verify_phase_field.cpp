// `fragmpm verify phase-field-bar` (docs/verification.md): the fast parts of the case. A crack
// imposed by a huge history on one particle column has the closed-form profile d = exp(−|x|/(2 l₀))
// (the strip's cosh form) and the energy G_c per unit crack length, to first order in h / l₀; the
// pulled bar with a partial crack ends with one crack of energy G_c × height.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <variant>

#include "fragmpm/analysis/fragments.hpp"
#include "fragmpm/mpm/solver.hpp"
#include "fragmpm/pipeline/analyze.hpp"
#include "fragmpm/pipeline/embedded_scenes.hpp"
#include "fragmpm/pipeline/scene.hpp"
#include "fragmpm/pipeline/verify_phase_field.hpp"

using namespace fragmpm::pipeline;

TEST(VerifyPhaseField, StripSceneHasAColumnOnTheCrackLineAndEndsAtA) {
  // h = 0.5 mm, n = 20 columns each side, 2 mm high: s = 0.25 mm, a = 20.5 s = 5.125 mm; the
  // lattice's columns at x = k s, k = −20 … 20, and 8 rows of 0.25 mm in the height.
  for (const char* shape : {"bspline2", "linear"}) {
    const auto problem =
        parse_scene(phase_field_strip_scene(0.5e-3, shape, 20, 2e-3), "strip.toml");
    const auto& P = problem.particles;
    ASSERT_EQ(P.size(), 41u * 8u) << shape;
    double left = 1e300, right = -1e300, on_line = 0.0, mass = 0.0;
    for (std::size_t p = 0; p < P.size(); ++p) {
      const double column = P.x[p][0] / 0.25e-3;
      EXPECT_NEAR(column, std::round(column), 1e-9) << p;
      on_line += std::abs(P.x[p][0]) < 1e-12;
      left = std::min(left, P.x[p][0]);
      right = std::max(right, P.x[p][0]);
      mass += P.mass[p];
    }
    EXPECT_EQ(on_line, 8.0);
    EXPECT_NEAR(left, -5e-3, 1e-15);
    EXPECT_NEAR(right, 5e-3, 1e-15);
    EXPECT_NEAR(mass, 2000.0 * 10.25e-3 * 2e-3, 1e-12);  // ρ × (2a × height), unit thickness
    const auto& law = std::get<fragmpm::mpm::PhaseField>(problem.materials[0].damage);
    EXPECT_EQ(law.length_scale, 1e-3);
    EXPECT_EQ(law.fracture_energy, 100.0);
  }
}

TEST(VerifyPhaseField, ImposedCrackHasTheClosedFormProfileAndEnergy) {
  // Measured (B-spline, 2 particles per cell, l₀ = 1 mm):
  //   h = 0.5 mm:   max 0.0815, rms 0.0146,  Ψ_f / (G_c A) = 1.0425
  //   h = 0.25 mm:  max 0.0412, rms 0.00676, Ψ_f / (G_c A) = 1.0203
  //   h = 0.125 mm: max 0.0207, rms 0.00324, Ψ_f / (G_c A) = 1.0099
  // first order in h / l₀ for the profile and for the energy's excess.
  const double cells[] = {0.5e-3, 0.25e-3, 0.125e-3};
  CrackProfile e[3];
  for (int k = 0; k < 3; ++k) e[k] = phase_field_crack_profile(cells[k], "bspline2");
  for (int k = 1; k < 3; ++k) {
    EXPECT_GT(std::log2(e[k - 1].max_error / e[k].max_error), 0.9) << k;
    EXPECT_GT(std::log2(e[k - 1].rms_error / e[k].rms_error), 0.9) << k;
    EXPECT_GT(std::log2((e[k - 1].energy_ratio - 1.0) / (e[k].energy_ratio - 1.0)), 0.9) << k;
  }
  EXPECT_LT(e[0].max_error, 0.09);
  EXPECT_LT(e[2].rms_error, 0.004);
  for (int k = 0; k < 3; ++k) {
    EXPECT_GT(e[k].energy_ratio, 1.0) << k;
    EXPECT_LT(e[k].energy_ratio, 1.05) << k;
  }
  // Linear hats and CPDI give the same profile to first order (the same solve on other kernels).
  for (const char* shape : {"linear", "cpdi"}) {
    const CrackProfile c = phase_field_crack_profile(0.25e-3, shape);
    EXPECT_LT(c.max_error, 0.1) << shape;
    EXPECT_NEAR(c.energy_ratio, 1.0, 0.06) << shape;
  }
}

TEST(VerifyPhaseField, SeededBarEndsWithOneCrackOfEnergyGcTimesHeight) {
  // h = 0.5 mm (the coarsest level; 0.99 measured, 1.02 and 1.01 at 0.25 and 0.125 mm).
  const auto rows = phase_field_bar_level("seeded", 0, 0.5e-3);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_TRUE(rows[0].passed()) << rows[0].value;
  EXPECT_NEAR(rows[0].value, 0.9935, 0.01);
  EXPECT_LT(rows[1].value, 0.03);  // the bulk's share: 2.4 % measured
  // The seed's history (G_c/4 per crack area, stored by no strain) is spent on the crack, and the
  // balance books it as the history excess (docs/design.md §2.5): without that booking the error
  // was a surplus of 0.107 of the input; what is left is the finite steps' own error (−0.0088
  // measured).
  EXPECT_LT(std::abs(rows[2].value), 0.02);
}

TEST(VerifyPhaseField, AnisotropicCrackHasTheClosedFormProfileAndEnergy) {
  // The paper's cubic γ = (1, 1, 0, 74) ([KT19] §5.1 (ii)); the crack normal is x. Along ξ₁
  // (φ = 0): γ_n = 1, profile (1 + u) e^(−u) with u = |x|/(√2 l₀), energy √2 Ḡ_c. Measured:
  //   h = 0.5 mm:   max 0.00505, Ψ_f / closed form 1.0046
  //   h = 0.25 mm:  max 0.00135, 1.0013
  //   h = 0.125 mm: max 0.00035, 1.0003   (second order: the profile is C¹ at the crack)
  // (The finest level is left to `fragmpm verify phase-field-bar`: two strips 20 l₀ high.)
  const fragmpm::mpm::PhaseFieldAnisotropy along{1.0, 1.0, 0.0, 74.0, 0.0};
  const CrackProfile e[2] = {phase_field_crack_profile(0.5e-3, "bspline2", along),
                             phase_field_crack_profile(0.25e-3, "bspline2", along)};
  EXPECT_GT(std::log2(e[0].max_error / e[1].max_error), 1.8);
  EXPECT_GT(std::log2((e[0].energy_ratio - 1.0) / (e[1].energy_ratio - 1.0)), 1.8);
  EXPECT_LT(e[0].max_error, 0.006);
  EXPECT_NEAR(e[0].energy_ratio, 1.0, 0.005);
  // Material axes at 45° to the crack normal: γ_n = (1 + 1 + 74)/4 = 19, energy 2.315 Ḡ_c (the
  // paper's G_c,max 0.0049 N/mm for Ḡ_c = 0.002121 N/mm). Measured 1.0035 at h = 0.5 mm (1.0024,
  // 1.0022 finer); the profile in the middle of the strip within 0.019 at every h (what the
  // strip's free edges leave there).
  const fragmpm::mpm::PhaseFieldAnisotropy rotated{1.0, 1.0, 0.0, 74.0, std::acos(-1.0) / 4.0};
  const CrackProfile r = phase_field_crack_profile(0.5e-3, "bspline2", rotated);
  EXPECT_NEAR(r.energy_ratio, 1.0, 0.006);
  EXPECT_LT(r.max_error, 0.025);
}

TEST(VerifyPhaseField, PulledBarBreaksIntoTwoFragments) {
  // The seeded bar of phase_field_bar_level at h = 0.5 mm, partitioned: at 30 µs its crack
  // particles have d = 0.95-0.97 (measured largest 0.949), so the analysis of a phase-field run
  // masks at d ≥ 0.9 (phase_field_fragment_mask) and finds the two halves.
  std::string text = fragmpm::pipeline::with_overrides(
      fragmpm::pipeline::embedded_scene("verify/phase-field-bar.toml"),
      {{"grid.cell_size", "0.0005"},
       {"walls[0].velocity.to", "[-0.5, 0.0]"},
       {"walls[1].velocity.to", "[0.5, 0.0]"}});
  auto problem = fragmpm::pipeline::parse_scene(text, "phase-field-bar.toml");
  auto& P = problem.particles;
  const double spacing = std::sqrt(P.volume0[0]);
  for (std::size_t p = 0; p < P.size(); ++p)
    if (std::abs(P.x[p][0] - 10e-3) < 0.5 * spacing) P.damage_history[p] = 100.0 / spacing;
  const auto reference = P;
  fragmpm::mpm::Solver<2> solver(std::move(problem));
  while (solver.time() < 30e-6) ASSERT_FALSE(solver.step());
  fragmpm::analysis::FragmentOptions options;
  options.d_mask = phase_field_fragment_mask;
  const auto labels = fragmpm::analysis::label_fragments(reference, solver.particles(), options);
  EXPECT_EQ(labels.resolved(), 2u);
  EXPECT_GT(labels.masked, 0u);
  // Both halves hold about half the particles.
  const auto members = fragmpm::analysis::fragment_members(labels);
  for (std::size_t f = 0; f < 2; ++f)
    EXPECT_NEAR(double(members[f].size()) / double(reference.size()), 0.5, 0.05);
}
