#pragma once
// The one exception type of the figure code: bad figure input (empty series, a non-positive value
// on a log axis, mismatched array lengths, an unwritable PNG path) or an OSMesa context that cannot
// be created. The message names what was wrong and where; the CLI maps it to exit code 2.
#include <stdexcept>

namespace fragmpm::analysis {

struct FigureError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace fragmpm::analysis
