#pragma once
// OpenGL drawing in pixel coordinates (x right, y down) for the figures (private to analysis/).
// Needs a current OffscreenContext. Axis-aligned lines are drawn as filled rectangles so that they
// cover whole pixels exactly; data lines are antialiased.
#include <cstdint>
#include <vector>

#include "fragmpm/analysis/colour_map.hpp"

namespace fragmpm::analysis::detail {

struct PixelPoint {
  double x = 0.0, y = 0.0;
};

/// Fills the pixels [x0, x1) × [y0, y1).
void fill_rect(double x0, double y0, double x1, double y1, Rgb colour);
/// Outline `width` pixels wide lying inside [x0, x1) × [y0, y1).
void stroke_rect(double x0, double y0, double x1, double y1, double width, Rgb colour);
/// Antialiased polyline; `dashed` draws it in long dashes.
void draw_polyline(const std::vector<PixelPoint>& points, double width, Rgb colour,
                   bool dashed = false);
/// Antialiased round markers of diameter `size` pixels.
void draw_markers(const std::vector<PixelPoint>& points, double size, Rgb colour);
/// Flat-coloured triangles: xy holds 6 floats per triangle, rgb 3 bytes per triangle.
void fill_triangles(const std::vector<float>& xy, const std::vector<std::uint8_t>& rgb);
/// Restricts drawing to [x0, x1) × [y0, y1) (pixel coordinates, y down); `off` lifts it.
void clip_to(int x0, int y0, int x1, int y1, int image_height);
void clip_off();

}  // namespace fragmpm::analysis::detail
