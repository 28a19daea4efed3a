#pragma once
// What the phase-field stage keeps between steps: the per-material coefficients of the nodal
// equation, the unknowns of the active grid (one per node and body), the assembled system and the
// conjugate-gradient solver. Exists only when a material has the phase-field law.
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>
#include <array>
#include <cstdint>
#include <vector>

#include "fragmpm/mpm/problem.hpp"

namespace fragmpm::mpm {

/// Tag of StepState::material_damages for a material with the phase-field law (0: no damage,
/// 1: a damage law of damage_law.hpp).
inline constexpr char material_phase_field = 2;

/// Relative residual |K d − f| / |f| at which the conjugate gradients stop ([KT19] §4.3: tol_c =
/// 10⁻⁶).
inline constexpr double phase_field_tolerance = 1e-6;

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
  int iterations = 0;     ///< of the last solve
  double residual = 0.0;  ///< relative residual of the last solve
};

}  // namespace fragmpm::mpm
