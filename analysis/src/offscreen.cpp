// OSMesa context + framebuffer (see offscreen.hpp).
#include "fragmpm/analysis/offscreen.hpp"

#include <GL/osmesa.h>
#include <fmt/format.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

#include "fragmpm/analysis/figure_error.hpp"

namespace fragmpm::analysis {

OffscreenContext::OffscreenContext(int width, int height) : width_(width), height_(height) {
  constexpr int max_side = 16384;
  if (width < 1 || height < 1 || width > max_side || height > max_side)
    throw FigureError(fmt::format("figure size {} x {} pixels: expected each side in [1, {}]",
                                  width, height, max_side));
  // No depth, stencil or accumulation buffers: figures are flat 2D geometry drawn in order.
  context_ = OSMesaCreateContextExt(OSMESA_RGBA, 0, 0, 0, nullptr);
  if (context_ == nullptr)
    throw FigureError(
        "OSMesa could not create an off-screen OpenGL context (is the Mesa software driver of "
        "libosmesa6 installed?)");
  buffer_.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4, 0);
  make_current();
  glViewport(0, 0, width, height);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  // Pixel coordinates with y down: pixel (i, j) of the returned image covers [i, i+1] x [j, j+1].
  glOrtho(0.0, width, height, 0.0, -1.0, 1.0);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glClearColor(1.0f, 1.0f, 1.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
}

OffscreenContext::~OffscreenContext() {
  if (context_ != nullptr) OSMesaDestroyContext(context_);
}

void OffscreenContext::make_current() {
  if (!OSMesaMakeCurrent(context_, buffer_.data(), GL_UNSIGNED_BYTE, width_, height_))
    throw FigureError(fmt::format("OSMesa could not bind a {} x {} framebuffer", width_, height_));
}

cv::Mat OffscreenContext::read_bgr() {
  make_current();
  glFinish();
  const cv::Mat rgba(height_, width_, CV_8UC4, buffer_.data());
  cv::Mat flipped, bgr;
  cv::flip(rgba, flipped, 0);  // OpenGL stores the bottom row first
  cv::cvtColor(flipped, bgr, cv::COLOR_RGBA2BGR);
  return bgr;
}

}  // namespace fragmpm::analysis
