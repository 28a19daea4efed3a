#pragma once
// Particle figures of a run frame (`fragmpm render --field`, and the figures of analyze and the
// pipeline): the frame's particle arrays turned into a ParticleFigure for one field.
#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "fragmpm/analysis/fragments.hpp"
#include "fragmpm/analysis/particle_figure.hpp"
#include "fragmpm/mpm/particles.hpp"

namespace fragmpm::analysis {

enum class FrameField { damage, temperature, speed, stress, body };

/// The names `fragmpm render --field` accepts, in FrameField order.
const std::vector<std::string>& frame_field_names();
/// Throws FigureError naming the accepted fields when `name` is not one of them.
FrameField parse_frame_field(const std::string& name);

/// Maximum principal value of the in-plane Cauchy stress, σ1 = (σxx + σyy)/2 +
/// √(((σxx − σyy)/2)² + σxy²), taken of the symmetric part [Pa].
double max_principal_stress(const Eigen::Matrix2d& sigma);

/// Figure of `field` over the frame: damage d in [0, 1] (fixed range), temperature θ [K], speed |v|
/// [m/s], maximum principal stress [MPa], or body id. Domains from the CPDI edge vectors (columns
/// of Particles::domain). Throws FigureError when the frame lacks the field (temperature without
/// the thermal module).
ParticleFigure frame_figure(const mpm::Particles<2>& particles, FrameField field,
                            std::optional<double> time, const std::string& title);

/// Ids for a fragment figure: resolved fragments keep their id, fines and masked particles get −1
/// (drawn grey as "masked or fines").
std::vector<std::int64_t> resolved_fragment_ids(const FragmentLabels& labels);

/// Figure of fragment ids (one per particle, negative = no fragment / fines) over the frame.
ParticleFigure fragment_figure(const mpm::Particles<2>& particles,
                               const std::vector<std::int64_t>& fragment_ids,
                               std::optional<double> time, const std::string& title);

}  // namespace fragmpm::analysis
