// V2 (docs/verification.md; [NBS18] §3, appendix eq. (46)-(54)): the rigid-block oracle against
// direct numerical integration of the block's equation of motion, the loading of the paper
// recomputed, and the coarsest MPM level for Coulomb friction within 2 % of the oracle.
#include <gtest/gtest.h>

#include <cmath>

#include "fragmpm/pipeline/sliding_block_oracle.hpp"
#include "fragmpm/pipeline/verify.hpp"

using namespace fragmpm;
using namespace fragmpm::pipeline;

namespace {

// [NBS18] §3: ρ = 1 g/cm³, h = 15 mm, l = 40 mm, μ = 0.2, R = 1, v_max = 2 % of √(E/ρ), E = 2500
// MPa, 85 mm of sliding, t1 = t2 = t_f/4.
const double v_max = 0.02 * std::sqrt(2.5e9 / 1000.0);
SlidingBlockLoading paper_loading() {
  return sliding_block_loading(1000.0, 0.015, 0.040, 0.2, 1.0, v_max, 0.085, 0.25);
}

}  // namespace

TEST(SlidingBlockOracle, LoadingOfThePaper) {
  const SlidingBlockLoading b = paper_loading();
  EXPECT_NEAR(v_max, 31.62, 0.01);
  EXPECT_NEAR(b.normal_stress, 0.147e6, 0.001e6);  // "N ≈ 0.147 MPa" (V2 in docs/verification.md)
  EXPECT_NEAR(b.end_time, 13.44e-3, 0.01e-3);      // "t_f ≈ 13.45 ms"
  EXPECT_NEAR(b.tangential_start, 0.25 * b.end_time, 1e-15);
  // The Coulomb block reaches v_max having slid 85 mm at t_f.
  const auto coulomb = rigid_block_friction(mpm::CoulombFriction{0.2});
  ASSERT_TRUE(coulomb);
  EXPECT_NEAR(rigid_block_velocity(b, *coulomb, b.end_time), v_max, 1e-9 * v_max);
  const RigidBlockState s = integrate_rigid_block(b, mpm::CoulombFriction{0.2}, b.end_time, 20000);
  EXPECT_NEAR(s.distance, 0.085, 1e-9);
  // Onset at S = μN (eq. (47)): t_i = t2 + 0.2 t_s.
  EXPECT_NEAR(rigid_block_onset(b, *coulomb),
              b.tangential_start + 0.2 * (b.end_time - b.tangential_start), 1e-15);
}

TEST(SlidingBlockOracle, ClosedFormsMatchNumericalIntegration) {
  const SlidingBlockLoading b = paper_loading();
  const mpm::FrictionLaw laws[] = {mpm::CoulombFriction{0.2},
                                   mpm::VelocityDependentFriction{0.2, 0.5 / v_max},
                                   mpm::AdhesiveFriction{0.2, 0.3 * b.normal_stress, 0.0},
                                   mpm::SmoothStaticDynamicFriction{0.4, 0.2, 0.0}};
  for (const auto& law : laws) {
    const auto closed = rigid_block_friction(law);
    ASSERT_TRUE(closed);
    for (double fraction : {0.7, 0.85, 1.0}) {
      const double t = fraction * b.end_time;
      const RigidBlockState s = integrate_rigid_block(b, law, t, 20000);
      EXPECT_NEAR(s.onset, rigid_block_onset(b, *closed), 1e-15);
      const double v = rigid_block_velocity(b, *closed, t),
                   q = rigid_block_friction_work(b, *closed, t);
      EXPECT_GT(v, 0.0);
      EXPECT_NEAR(s.velocity, v, 1e-9 * v) << law.index() << " at " << fraction << " t_f";
      EXPECT_NEAR(s.friction_work, q, 1e-8 * q) << law.index() << " at " << fraction << " t_f";
    }
  }
  // The thermal and smooth (v½ > 0) laws have no closed form.
  EXPECT_FALSE(rigid_block_friction(mpm::SmoothStaticDynamicFriction{0.4, 0.2, 0.05}));
  EXPECT_FALSE(rigid_block_friction(mpm::ThermalSofteningFriction{0.2, 300.0, 900.0}));
}

TEST(SlidingBlockOracle, SmoothLawSpansStaticAndDynamic) {
  // [NBS18] Fig. 4: large v½ slides like μ = μ_s, small v½ like the sharp static/dynamic law.
  const SlidingBlockLoading b = paper_loading();
  const double t = b.end_time;
  const double slow =
      integrate_rigid_block(b, mpm::SmoothStaticDynamicFriction{0.4, 0.2, 1e6}, t, 20000).velocity;
  const double coulomb_static =
      rigid_block_velocity(b, *rigid_block_friction(mpm::CoulombFriction{0.4}), t);
  EXPECT_NEAR(slow, coulomb_static, 2e-3 * coulomb_static);
  const double sharp = rigid_block_velocity(
      b, *rigid_block_friction(mpm::SmoothStaticDynamicFriction{0.4, 0.2, 0.0}), t);
  const double smooth =
      integrate_rigid_block(b, mpm::SmoothStaticDynamicFriction{0.4, 0.2, 1e-4}, t, 200000)
          .velocity;
  EXPECT_NEAR(smooth, sharp, 2e-3 * sharp);
}

TEST(VerifySlidingBlock, CoarsestCoulombLevelWithinTwoPercent) {
  // The paper's 5 mm grid, 656 particles, ~18 000 steps (about 10 s of one core).
  const auto rows = verify_sliding_block_level("coulomb", 0, 5e-3);
  ASSERT_EQ(rows.size(), 2u);
  for (const VerifyRow& r : rows) {
    EXPECT_GT(r.reference, 0.0);
    EXPECT_LT(r.error, 0.02) << r.metric << ": " << r.value << " vs " << r.reference;
  }
}

TEST(VerifySlidingBlock, StiffBlockMeetsTheRigidOracleOfTheSmoothStaticDynamicLaw) {
  // The rigid-block oracle of the smooth static-dynamic law holds for a block that does not slip
  // at its pushed edge first: ten times the scene's stiffness under the same loads (about 58 000
  // steps, 16 s of one core) meets it to 0.10 % in friction work and 0.02 % in velocity, where the
  // scene's block books 2.7 % more friction work.
  const auto rows = verify_sliding_block_level("static-dynamic-stiff", 0, 5e-3);
  ASSERT_EQ(rows.size(), 2u);
  for (const VerifyRow& r : rows) {
    EXPECT_GT(r.reference, 0.0);
    EXPECT_LT(r.error, 5e-3) << r.metric << ": " << r.value << " vs " << r.reference;
  }
}

TEST(VerifySlidingBlock, CoarsestAdhesionLevelWithinTwoPercent) {
  // The adhesion force S_a A scales with the contact area summed over the interface nodes. From the
  // fields' volume gradients that sum is the block length; [NBS18] eq. (11) over-estimates it at
  // the block's end nodes (0.61 h instead of h/2), which made this case 4.9 % slow at 5 mm.
  const auto rows = verify_sliding_block_level("adhesion", 0, 5e-3);
  ASSERT_EQ(rows.size(), 2u);
  for (const VerifyRow& r : rows) {
    EXPECT_GT(r.reference, 0.0);
    EXPECT_LT(r.error, 0.02) << r.metric << ": " << r.value << " vs " << r.reference;
    EXPECT_TRUE(r.has_target() && r.passed());
  }
}
