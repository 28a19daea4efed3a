#pragma once
// What the phase-field stage keeps between steps: the per-material coefficients of the nodal
// equation, the unknowns of the active grid (one per node and body), the assembled system and the
// conjugate-gradient solver. Exists only when a material has the phase-field law.
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>
#include <array>
#include <cstdint>
#include <vector>

#include "fragmpm/mpm/phase_field_warm_start.hpp"
#include "fragmpm/mpm/problem.hpp"

namespace fragmpm::mpm {

/// Tag of StepState::material_damages for a material with the phase-field law (0: no damage,
/// 1: a damage law of damage_law.hpp).
inline constexpr char material_phase_field = 2;

/// Relative residual |K d − f| / |f| at which the conjugate gradients stop ([KT19] §4.3: tol_c =
/// 10⁻⁶).
inline constexpr double phase_field_tolerance = 1e-6;

/// Preconditioner switch. Jacobi costs nothing to set up and suffices while the history field is
/// mild (`fragmpm bench`, 10⁵ particles: 12 iterations a step). Once cracks are open, the history
/// H of their particles reaches 10⁵ G_c/(4 l₀), and the H-weighted particle mass matrix of a
/// cracked band, nearly rank-deficient with few particles per cell, sets the condition number. On
/// the system of the colliding rings at 300 µs (10 386 unknowns, H/(G_c/(4 l₀)) up to 1.3 × 10⁵)
/// Jacobi took 668 iterations (0.11 s) and the incomplete Cholesky factor of the same system in
/// node order 105 (0.067 s); warm-started, 314 against 35. Its factorisation (0.016 s) costs about
/// 95 Jacobi iterations and each of its iterations about 3, so with 8 to 10 times fewer
/// iterations the factor pays once Jacobi needs more than about 150. A solve past
/// `jacobi_iteration_limit` hands the next solves to the factor; a factored solve below
/// `factored_iteration_floor` (Jacobi would then need about 150 or fewer) hands them back.
inline constexpr int jacobi_iteration_limit = 150;
inline constexpr int factored_iteration_floor = 15;

template <int D>
struct PhaseFieldState {
  /// Bodies a node keeps apart: each body has its own phase field ([KT19] §3.1.1, eq. (28): one
  /// per discrete field), so a crack in one grain does not diffuse into the grain it touches. A
  /// node reached by more bodies than this lets the last ones share its last unknown.
  static constexpr int slots = 4;

  using Matrix = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;

  /// Per material (index = material id); zero for materials without the law.
  std::vector<double> local_coefficient;     ///< G_c / (4 l₀) [J/m⁴]
  std::vector<double> gradient_coefficient;  ///< G_c l₀ [J/m²]
  std::vector<double> drive_factor;          ///< 1 − k_f
  std::vector<double> residual_stiffness;    ///< k_f
  std::vector<double> fracture_energy;       ///< G_c [J/m²]
  std::vector<double> length_scale;          ///< l₀ [m]
  /// The fourth-order anisotropic term ([KT19] §2.2; D = 2 with the B-spline only): per material
  /// whether it is on and G_c l₀³ Γ_g (phase_field_anisotropy_global) [J/m⁰·m²·m = J·m].
  std::vector<char> anisotropic;
  std::vector<Eigen::Matrix3d> fourth_order;

  /// Per node and slot of the active grid: the body the slot holds (−1 = free) and its unknown.
  std::vector<std::int32_t> node_body, node_unknown;
  /// Per unknown: its node (linear index of this step's grid) and body.
  std::vector<std::int64_t> unknown_node;
  std::vector<std::int32_t> unknown_body;
  /// Node offsets o ∈ [−reach, reach]^D that two nodes of one particle's stencil can have; the
  /// rows of the system are first summed per offset (`band`, unknowns × band_width), which the
  /// strip-ordered scatter fills without races, then compressed.
  int reach = 1;
  int band_width = 1;
  std::vector<double> band;
  std::vector<double> guess_weight;  ///< Σ V₀ S̄ per unknown (the guess is Σ V₀ S̄ (1 − d_p) / this)
  /// The system K c = f for c = 1 − d in compressed rows ([KT19] eq. (56)-(57)).
  std::vector<int> outer, inner;
  std::vector<double> values;
  Eigen::VectorXd rhs, guess, solution;
  Eigen::ConjugateGradient<Matrix, Eigen::Lower | Eigen::Upper> solver;
  /// The same, preconditioned by an incomplete Cholesky factor in node order (the unknowns are
  /// numbered along grid rows, so the factor keeps the band's coupling; a fill-reducing order
  /// took three times as many iterations on the rings' system).
  Eigen::ConjugateGradient<
      Matrix, Eigen::Lower | Eigen::Upper,
      Eigen::IncompleteCholesky<double, Eigen::Lower, Eigen::NaturalOrdering<int>>>
      factored_solver;
  /// The last solution, which starts the next solve, and the preconditioner the next solve uses.
  PhaseFieldWarmStart<D> last;
  bool factored = false;  ///< the last solve used the incomplete Cholesky factor
  int iterations = 0;     ///< of the last solve
  double residual = 0.0;  ///< relative residual of the last solve
};

}  // namespace fragmpm::mpm
