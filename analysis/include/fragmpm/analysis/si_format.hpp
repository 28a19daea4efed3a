#pragma once
// SI prefixes for figure text: scale bars, time stamps, axis units.
#include <string>

namespace fragmpm::analysis {

/// A prefix and the factor that converts a value in the base unit to it (value · factor).
struct SiPrefix {
  std::string prefix;  ///< "p", "n", "µ", "m", "", "k", "M", "G"
  double factor = 1.0;
};

/// The prefix that brings `magnitude` (> 0) into [1, 1000); 1 (no prefix) for zero or non-finite.
SiPrefix si_prefix(double magnitude);

/// "1 mm", "200 µm", "12.5 µs": value with the prefix that brings the number into [1, 1000), with
/// at most `significant` significant digits (trailing zeros dropped).
std::string format_si(double value, const std::string& unit, int significant = 3);

}  // namespace fragmpm::analysis
