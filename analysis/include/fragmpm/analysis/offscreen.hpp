#pragma once
// An off-screen OpenGL context (OSMesa, software rendering): figures are drawn without a display,
// X server or GPU (docs/design.md "Figures"). The context owns an RGBA framebuffer of the given
// size, sets a pixel projection (x right, y down, origin at the top-left corner of the image, as in
// OpenCV), and hands the result back as a cv::Mat.
#include <opencv2/core/mat.hpp>
#include <vector>

struct osmesa_context;  // OSMesaContext is `struct osmesa_context*` (GL/osmesa.h)

namespace fragmpm::analysis {

class OffscreenContext {
 public:
  /// Creates the context and makes it current on this thread. Throws FigureError when the size is
  /// not in [1, 16384] or OSMesa cannot create a context (e.g. the library lacks a software
  /// driver).
  OffscreenContext(int width, int height);
  ~OffscreenContext();
  OffscreenContext(const OffscreenContext&) = delete;
  OffscreenContext& operator=(const OffscreenContext&) = delete;

  int width() const { return width_; }
  int height() const { return height_; }

  /// Makes this context current on the calling thread (the constructor already did so once).
  void make_current();
  /// Finishes pending GL work and returns the framebuffer as an 8-bit BGR image (OpenCV's channel
  /// order), height × width, row 0 at the top.
  cv::Mat read_bgr();

 private:
  int width_ = 0;
  int height_ = 0;
  osmesa_context* context_ = nullptr;
  std::vector<unsigned char> buffer_;  ///< RGBA, row 0 at the bottom (OpenGL's convention)
};

}  // namespace fragmpm::analysis
