// The APIC transfer: a rigid spin passes the grid without creating stress, momentum and angular
// momentum of a free spinning body are kept, the stencil offsets satisfy the identities the
// transfer relies on, and the result does not depend on the thread count.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <random>
#include <string>

#include "fragmpm/mpm/current_domain.hpp"
#include "fragmpm/mpm/shape_functions.hpp"
#include "fragmpm/mpm/solver.hpp"
#include "fragmpm/pipeline/scene.hpp"

using namespace fragmpm;
using mpm::Mat;
using mpm::Vec;

namespace {

/// A free glass disk (R = 3 mm) spinning at 2000 rad/s; `transfer` and `shape` are substituted.
mpm::Problem<2> spinning_disk(const std::string& transfer, const std::string& shape = "cpdi") {
  const std::string text = R"(
[grid]
cell_size = "0.5 mm"
min = ["-6 mm", "-6 mm"]
max = ["6 mm", "6 mm"]
shape_function = ")" + shape +
                           R"("
[time]
cfl = 0.4
transfer = ")" + transfer + R"("
[[materials]]
name = "glass"
model = "neo-hookean"
E = "70 GPa"
nu = 0.22
density = "2.5 g/cm3"
[[bodies]]
name = "disk"
material = "glass"
shape = "disk"
center = ["0 mm", "0 mm"]
radius = "3 mm"
angular_velocity = "2000 rad/s"
[stop]
max_steps = 1000
)";
  return pipeline::parse_scene(text, "spinning-disk.toml");
}

/// h = 0.1, nodes −5 … 14 per direction.
mpm::GridIndex<2> test_grid() {
  mpm::GridIndex<2> grid;
  grid.cell_size = 0.1;
  grid.inverse_cell_size = 10.0;
  grid.lower = mpm::IVec<2>(-5, -5);
  grid.extent = mpm::IVec<2>(20, 20);
  return grid;
}

double largest_stress(const mpm::Particles<2>& P) {
  double largest = 0.0;
  for (const auto& s : P.stress) largest = std::max(largest, s.cwiseAbs().maxCoeff());
  return largest;
}

}  // namespace

// The first step starts stress-free, so the grid update adds nothing to the lumped velocities. With
// APIC they are ω × x_i at every node (partly filled or not), the velocity gradient is the pure
// spin, and the midpoint increment keeps F orthogonal: no stress beyond round-off of E. FLIP
// lumps ω × x̄_i (x̄_i the centroid of the node's particles), and the boundary nodes stretch.
TEST(Apic, RigidSpinCreatesNoStressInTheFirstStep) {
  mpm::Solver<2> apic(spinning_disk("apic"));
  ASSERT_FALSE(apic.step());
  mpm::Solver<2> flip(spinning_disk("flip"));
  ASSERT_FALSE(flip.step());
  const double E = 70e9;
  EXPECT_LT(largest_stress(apic.particles()), 1e-12 * E);
  // The FLIP stress is of order E ω Δt (h/2)/R at the rim: far above round-off.
  const double flip_scale = E * 2000.0 * flip.last_row().dt;
  EXPECT_GT(largest_stress(flip.particles()), 1e-3 * flip_scale);
}

TEST(Apic, LinearHatStencilGivesGradientFromOffsets) {
  // For the linear hat, D_p = Σ S̄ (x_i − x_p)(x_i − x_p)ᵀ is diag(f(1 − f)) h² and
  // S̄ D_p⁻¹ (x_i − x_p) = ∇S̄ for every node: C_p = L_p is the APIC matrix B_p D_p⁻¹.
  const mpm::GridIndex<2> grid = test_grid();
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.05, 0.95);
  for (int trial = 0; trial < 50; ++trial) {
    const Vec<2> x(u(rng), u(rng));
    mpm::Stencil<2> s;
    mpm::linear_stencil<2, true>(x, grid, s);
    Mat<2> moment = Mat<2>::Zero();
    Vec<2> first = Vec<2>::Zero();
    for (int e = 0; e < s.count; ++e) {
      first += s.weight[e] * s.offset[e];
      moment += s.weight[e] * s.offset[e] * s.offset[e].transpose();
    }
    EXPECT_LT(first.norm(), 1e-15);
    EXPECT_NEAR(moment(0, 1), 0.0, 1e-16);
    for (int e = 0; e < s.count; ++e)
      EXPECT_LT((s.weight[e] * moment.inverse() * s.offset[e] - s.gradient[e]).norm(), 1e-9);
  }
}

TEST(Apic, StencilOffsetsAreNodeMinusParticleForEveryKernel) {
  const mpm::GridIndex<2> grid = test_grid();
  const Vec<2> x(0.437, 0.262);
  Mat<2> domain;
  domain << 0.05, 0.01, -0.02, 0.04;
  mpm::Stencil<2> kinds[4];
  mpm::linear_stencil<2, true>(x, grid, kinds[0]);
  mpm::ugimp_stencil<2, true>(x, Vec<2>(0.025, 0.025), grid, kinds[1]);
  mpm::cpdi_stencil<2, true>(x, domain, grid, kinds[2]);
  mpm::bspline2_stencil<2, true>(x, grid, kinds[3]);
  for (const auto& s : kinds) {
    Vec<2> first = Vec<2>::Zero();
    for (int e = 0; e < s.count; ++e) {
      const mpm::IVec<2> node = grid.global(s.node[e]);
      EXPECT_LT((grid.position(node) - x - s.offset[e]).norm(), 1e-15);
      first += s.weight[e] * s.offset[e];
    }
    EXPECT_LT(first.norm(), 1e-15);  // linear completeness: Σ S̄ x_i = x_p
  }
}

// A free body: the grid forces of a symmetric stress have no resultant and no moment, and the
// affine term Σ S̄ (x_i − x_p) = 0 adds no momentum, so momentum stays zero to round-off. The
// angular momentum Σ m (x × v + ε:(C Q)) is not kept to round-off: P2G hands the grid
// ε:(C_p D_p) with D_p = Σ S̄ (x_i − x_p)(x_i − x_p)ᵀ at the particle's new position, G2P took
// ε:(C_p D_p) at the old one, and D_p changes as the particle moves across the cell. Over a quarter
// turn of the larger disk of `fragmpm verify --stability` the drift is 7e-7 of Σ m r² ω.
TEST(Apic, FreeSpinKeepsMomentumAngularMomentumAndEnergy) {
  for (const char* shape : {"cpdi", "linear", "ugimp", "bspline2"}) {
    mpm::Solver<2> solver(spinning_disk("apic", shape));
    const auto& P = solver.particles();
    double inertia = 0.0, momentum_scale = 0.0;
    for (std::size_t p = 0; p < P.size(); ++p) {
      inertia += P.mass[p] * P.x[p].squaredNorm();
      momentum_scale += P.mass[p] * P.v[p].norm();
    }
    const double angular0 = solver.last_row().angular_momentum[0];
    const double energy0 = solver.last_row().kinetic + solver.last_row().strain;
    EXPECT_NEAR(angular0, inertia * 2000.0, 0.01 * inertia * 2000.0) << shape;
    double drift = 0.0, momentum = 0.0, energy_change = 0.0;
    for (int step = 0; step < 400; ++step) {
      ASSERT_FALSE(solver.step()) << shape;
      const auto& row = solver.last_row();
      drift = std::max(drift, std::abs(row.angular_momentum[0] - angular0));
      momentum = std::max(momentum, row.momentum.norm());
      energy_change = std::max(energy_change, std::abs(row.kinetic + row.strain - energy0));
    }
    EXPECT_LT(momentum / momentum_scale, 1e-12) << shape;
    // Measured over these 400 steps: 1.4e-7 (linear), 2.5e-7 (CPDI), 2.8e-6 (uGIMP); FLIP loses
    // 5.1e-3 to 6.1e-3 of it and 0.5 % of the energy.
    EXPECT_LT(drift / (inertia * 2000.0), 1e-5) << shape;
    EXPECT_LT(energy_change / energy0, 1e-3) << shape;
  }
}

TEST(Apic, ResultsIndependentOfThreadCount) {
  auto run = [](int threads) {
    omp_set_num_threads(threads);
    mpm::Solver<2> solver(spinning_disk("apic"));
    for (int s = 0; s < 200; ++s) EXPECT_FALSE(solver.step());
    return solver.particles();
  };
  const int saved = omp_get_max_threads();
  const auto one = run(1);
  const auto two = run(2);
  omp_set_num_threads(saved);
  for (std::size_t p = 0; p < one.size(); ++p) {
    ASSERT_EQ(one.x[p], two.x[p]);
    ASSERT_EQ(one.v[p], two.v[p]);
    ASSERT_EQ(one.affine[p], two.affine[p]);
    ASSERT_EQ(one.stress[p], two.stress[p]);
  }
}

// A disk spun rigidly to ω t = 0.02 rad: every particle's current domain (what frames and figures
// draw) has turned with it, whichever kernel ran. CPDI turns its stored domain; the B-spline and
// uGIMP kernels keep the initial square, which F maps. Drawn unturned, the squares of a turned
// piece overlap and leave gaps.
TEST(Apic, CurrentDomainsTurnWithASpinningDisk) {
  const double omega = 2000.0, angle = 0.02;
  for (const std::string shape : {"cpdi", "bspline2", "ugimp"}) {
    mpm::Solver<2> solver(spinning_disk("apic", shape));
    while (solver.time() < angle / omega) {
      const auto failure = solver.step();
      ASSERT_FALSE(failure) << shape << ": " << failure->what;
    }
    const double turned = omega * solver.time();
    const mpm::ShapeFunctionKind kind = solver.problem().grid.shape_function;
    const mpm::Particles<2> drawn = mpm::with_current_domains<2>(solver.particles(), kind);
    double largest_error = 0.0, area = 0.0;
    for (std::size_t p = 0; p < drawn.size(); ++p) {
      const Vec<2> edge = drawn.domain[p].col(0);
      largest_error = std::max(largest_error, std::abs(std::atan2(edge.y(), edge.x()) - turned));
      area += std::abs(drawn.domain[p].determinant());
    }
    EXPECT_LT(largest_error, 1e-3 * turned) << shape;
    double initial_area = 0.0;
    for (const double v : solver.particles().volume0) initial_area += v;
    EXPECT_NEAR(area, initial_area, 1e-3 * initial_area) << shape;
    if (kind != mpm::ShapeFunctionKind::cpdi) {
      const Vec<2> stored = solver.particles().domain[0].col(0);
      EXPECT_NEAR(std::atan2(stored.y(), stored.x()), 0.0, 1e-12) << shape;
    }
  }
}
