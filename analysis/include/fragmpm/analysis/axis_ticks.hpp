#pragma once
// Tick values and tick labels of figure axes: "nice" values 1, 2 or 5 × 10^k on linear axes,
// decades (with 2 and 5 when at most two decades are shown) on logarithmic axes.
#include <string>
#include <vector>

namespace fragmpm::analysis {

/// A piece of a tick label; superscripts carry exponents ("10" then superscript "-3").
struct TextRun {
  std::string text;
  bool superscript = false;
};
using RichText = std::vector<TextRun>;

struct AxisTicks {
  double lo = 0.0, hi = 1.0;     ///< the axis range (data units, not logarithms)
  std::vector<double> major;     ///< labelled ticks inside [lo, hi]
  std::vector<double> minor;     ///< unlabelled ticks inside [lo, hi] (log axes)
  std::vector<RichText> labels;  ///< one per major tick
  RichText multiplier;           ///< e.g. "×10^-6" shown at the axis end; empty when unused
};

/// The step 1, 2 or 5 × 10^k nearest to span/target on the 1–2–5 ladder (span > 0): the span then
/// holds between 2/3 and 3/2 of `target` steps.
double nice_step(double span, int target);

/// Linear axis over the data range [lo, hi] (lo <= hi, both finite), widened by `margin` × span on
/// each side (a zero span is widened to ±10 % of |lo|, or ±1 at zero). Ticks are the multiples of
/// nice_step(span, 6) inside the range. When the largest |tick| is ≥ 1e5 or < 1e-2, labels are
/// divided by 10^(3m) and the multiplier holds "x10^(3m)".
AxisTicks linear_ticks(double lo, double hi, double margin = 0.04);

/// Logarithmic axis over the data range [lo, hi] (0 < lo <= hi), widened by `margin` × the span in
/// decades on each side. Major ticks are decades (every n-th decade when more than 8 are shown);
/// with fewer than three decades inside, 1, 2 and 5 × 10^k; with fewer than two of those, every
/// integer multiple. Labels are plain numbers when all lie in [1e-3, 1e4], else "m×10^k".
AxisTicks log_ticks(double lo, double hi, double margin = 0.04);

/// Plain text of a label (superscripts written as ^k), for messages and tests.
std::string plain_text(const RichText& text);

}  // namespace fragmpm::analysis
