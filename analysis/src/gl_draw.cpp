// OpenGL drawing helpers (see gl_draw.hpp). Fixed-function OpenGL 1.x with client vertex arrays:
// everything OSMesa's software rasteriser provides, and enough for flat 2D figures.
#include "gl_draw.hpp"

#include <GL/gl.h>

#include <algorithm>

namespace fragmpm::analysis::detail {

namespace {

void set_colour(Rgb c) {
  glColor4ub(c.r, c.g, c.b, 255);
}

}  // namespace

void fill_rect(double x0, double y0, double x1, double y1, Rgb colour) {
  glDisable(GL_POLYGON_SMOOTH);
  set_colour(colour);
  glRectd(x0, y0, x1, y1);
}

void stroke_rect(double x0, double y0, double x1, double y1, double width, Rgb colour) {
  fill_rect(x0, y0, x1, y0 + width, colour);
  fill_rect(x0, y1 - width, x1, y1, colour);
  fill_rect(x0, y0, x0 + width, y1, colour);
  fill_rect(x1 - width, y0, x1, y1, colour);
}

void draw_polyline(const std::vector<PixelPoint>& points, double width, Rgb colour, bool dashed) {
  if (points.size() < 2) return;
  std::vector<double> xy;
  xy.reserve(2 * points.size());
  for (const PixelPoint& p : points) {
    xy.push_back(p.x);
    xy.push_back(p.y);
  }
  glEnable(GL_LINE_SMOOTH);
  glHint(GL_LINE_SMOOTH_HINT, GL_NICEST);
  glLineWidth(static_cast<GLfloat>(width));
  if (dashed) {
    glEnable(GL_LINE_STIPPLE);
    glLineStipple(std::max(1, static_cast<int>(width * 1.5)), 0x0FFF);
  }
  set_colour(colour);
  glEnableClientState(GL_VERTEX_ARRAY);
  glVertexPointer(2, GL_DOUBLE, 0, xy.data());
  glDrawArrays(GL_LINE_STRIP, 0, static_cast<GLsizei>(points.size()));
  // Round joins: smooth wide lines leave notches at sharp corners; a dot per vertex fills them.
  if (!dashed && width >= 2.0) {
    glEnable(GL_POINT_SMOOTH);
    glPointSize(static_cast<GLfloat>(width));
    glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(points.size()));
    glDisable(GL_POINT_SMOOTH);
  }
  glDisableClientState(GL_VERTEX_ARRAY);
  glDisable(GL_LINE_STIPPLE);
  glDisable(GL_LINE_SMOOTH);
  glLineWidth(1.0f);
}

void draw_markers(const std::vector<PixelPoint>& points, double size, Rgb colour) {
  if (points.empty()) return;
  std::vector<double> xy;
  xy.reserve(2 * points.size());
  for (const PixelPoint& p : points) {
    xy.push_back(p.x);
    xy.push_back(p.y);
  }
  glEnable(GL_POINT_SMOOTH);
  glHint(GL_POINT_SMOOTH_HINT, GL_NICEST);
  glPointSize(static_cast<GLfloat>(size));
  set_colour(colour);
  glEnableClientState(GL_VERTEX_ARRAY);
  glVertexPointer(2, GL_DOUBLE, 0, xy.data());
  glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(points.size()));
  glDisableClientState(GL_VERTEX_ARRAY);
  glDisable(GL_POINT_SMOOTH);
  glPointSize(1.0f);
}

void fill_triangles(const std::vector<float>& xy, const std::vector<std::uint8_t>& rgb) {
  const std::size_t triangles = xy.size() / 6;
  if (triangles == 0) return;
  // Flat shading takes each triangle's colour from its last vertex; expand to one colour per vertex
  // so the arrays line up.
  std::vector<std::uint8_t> colours;
  colours.reserve(triangles * 12);
  for (std::size_t t = 0; t < triangles; ++t)
    for (int v = 0; v < 3; ++v) {
      colours.push_back(rgb[3 * t]);
      colours.push_back(rgb[3 * t + 1]);
      colours.push_back(rgb[3 * t + 2]);
      colours.push_back(255);
    }
  glShadeModel(GL_FLAT);
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_COLOR_ARRAY);
  glVertexPointer(2, GL_FLOAT, 0, xy.data());
  glColorPointer(4, GL_UNSIGNED_BYTE, 0, colours.data());
  glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(3 * triangles));
  glDisableClientState(GL_COLOR_ARRAY);
  glDisableClientState(GL_VERTEX_ARRAY);
  glShadeModel(GL_SMOOTH);
}

void clip_to(int x0, int y0, int x1, int y1, int image_height) {
  glEnable(GL_SCISSOR_TEST);
  // Scissor boxes are in window coordinates, origin at the bottom-left.
  glScissor(x0, image_height - y1, std::max(0, x1 - x0), std::max(0, y1 - y0));
}

void clip_off() {
  glDisable(GL_SCISSOR_TEST);
}

}  // namespace fragmpm::analysis::detail
