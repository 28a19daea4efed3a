#pragma once
// Prescribed rigid-wall velocity as a function of time, with its exact time integral
// (displacement).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "fragmpm/mpm/types.hpp"

namespace fragmpm::mpm {

enum class HistoryKind { constant, ramp, sinusoid };

/// constant: v(t) = from.
/// ramp: v = from for t <= t_start, linear to `to` over [t_start, t_end], then `to`.
/// sinusoid: v = from for t <= t_start, then from + amplitude * sin(2π frequency (t − t_start) +
/// phase)
/// ([NBS18] eq. (44) with t₁ = t_start).
template <int D>
struct VelocityHistory {
  HistoryKind kind = HistoryKind::constant;
  Vec<D> from = Vec<D>::Zero();       ///< [m/s]
  Vec<D> to = Vec<D>::Zero();         ///< [m/s] (ramp)
  Vec<D> amplitude = Vec<D>::Zero();  ///< [m/s] (sinusoid)
  double t_start = 0.0, t_end = 0.0;  ///< [s] (ramp; t_start also delays a sinusoid)
  double frequency = 0.0;             ///< [Hz] (sinusoid)
  double phase = 0.0;                 ///< [rad] (sinusoid)

  Vec<D> velocity(double t) const {
    switch (kind) {
      case HistoryKind::constant:
        return from;
      case HistoryKind::ramp: {
        if (t <= t_start) return from;
        if (t >= t_end) return to;
        const double s = (t - t_start) / (t_end - t_start);
        return from + s * (to - from);
      }
      case HistoryKind::sinusoid:
        if (t <= t_start) return from;
        return from +
               amplitude * std::sin(2.0 * std::numbers::pi * frequency * (t - t_start) + phase);
    }
    return from;
  }

  /// ∫_0^t v dt' in closed form, so wall positions do not drift with the time step.
  Vec<D> displacement(double t) const {
    switch (kind) {
      case HistoryKind::constant:
        return from * t;
      case HistoryKind::ramp: {
        if (t <= t_start) return from * t;
        const double ramp_len = t_end - t_start;
        const double tr = std::min(t, t_end) - t_start;
        Vec<D> d = from * t_start + from * tr + (to - from) * (tr * tr / (2.0 * ramp_len));
        if (t > t_end) d += to * (t - t_end);
        return d;
      }
      case HistoryKind::sinusoid: {
        const double w = 2.0 * std::numbers::pi * frequency;
        const double running = std::max(t - t_start, 0.0);
        if (w == 0.0) return from * t + amplitude * std::sin(phase) * running;
        return from * t + amplitude * ((std::cos(phase) - std::cos(w * running + phase)) / w);
      }
    }
    return from * t;
  }
};

}  // namespace fragmpm::mpm
