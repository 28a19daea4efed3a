#pragma once
// Text of the figures, drawn after the OpenGL geometry is read back (private to analysis/): UTF-8
// (µ, °, σ, ², −) with DejaVu Sans through OpenCV's FreeType module (Debian's fonts-dejavu-core;
// FRAGMPM_FONT names another TrueType file). Without a TrueType font the Hershey fonts draw it,
// which hold printable ASCII only, so the text is then transliterated (µ → u, ° → deg, ² → ^2 …).
#include <opencv2/core.hpp>
#include <string>

#include "fragmpm/analysis/axis_ticks.hpp"
#include "fragmpm/analysis/colour_map.hpp"

namespace fragmpm::analysis::detail {

struct TextStyle {
  double scale = 0.7;  ///< Hershey font scale (1.0 ≈ 22 px capital height)
  int thickness = 1;
  Rgb colour{0, 0, 0};
};

enum class HAlign { left, centre, right };
enum class VAlign { top, centre, bottom };

/// Printable-ASCII transliteration of UTF-8 text.
std::string ascii_text(const std::string& utf8);

RichText plain(const std::string& text);

/// Size in pixels of the text's ink box (ascent + descent, superscripts included).
cv::Size text_extent(const RichText& text, const TextStyle& style);

/// Draws `text` so that its box sits at `anchor` with the given alignment; `vertical` turns it 90°
/// counter-clockwise (reading upwards, as a y-axis label). The box is that of text_extent
/// (rotated).
void draw_text(cv::Mat& image, const RichText& text, cv::Point2d anchor, HAlign h, VAlign v,
               const TextStyle& style, bool vertical = false);

/// Figure scale: 1 at 1200 × 900 pixels, so that fonts and line widths follow the figure size.
double figure_scale(int width, int height);

/// Sizes shared by every figure, grown with figure_scale.
struct FigureStyle {
  double scale = 1.0;
  double pad = 12.0;         ///< general spacing [px]
  double tick_length = 8.0;  ///< major ticks [px]; minor ticks are half as long
  int axis_width = 2;        ///< axis frame and tick width [px]
  TextStyle tick_font, label_font, title_font;
};
FigureStyle figure_style(int width, int height);

}  // namespace fragmpm::analysis::detail
