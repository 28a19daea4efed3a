#pragma once
// Colour maps of the figures. Continuous fields use viridis (perceptually uniform, readable in grey
// and by colour-blind readers), taken from OpenCV's table (cv::COLORMAP_VIRIDIS); body and fragment
// ids use a categorical palette whose neighbouring ids differ strongly in hue.
#include <cstdint>

namespace fragmpm::analysis {

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
  friend bool operator==(const Rgb&, const Rgb&) = default;
};

/// Viridis at t in [0, 1] (clamped; NaN gives `no_data_colour()`), quantised to OpenCV's 256
/// entries.
Rgb viridis(double t);

/// Colour of a body or fragment id. Ids 0–9 take ten well-separated hues of a qualitative palette;
/// larger ids step round the hue circle by the golden angle (so consecutive ids never look alike)
/// at alternating saturation and brightness. Negative ids (no fragment, fines) are mid grey.
Rgb categorical_colour(std::int64_t id);

/// Grey used for particles whose value is missing (NaN) or whose id is negative.
Rgb no_data_colour();

/// The colour of the i-th line of a plot (the qualitative palette, cycled).
Rgb series_colour(std::size_t index);

}  // namespace fragmpm::analysis
