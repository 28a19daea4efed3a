#pragma once
// Line plots rendered off-screen (OSMesa geometry, OpenCV text) and written as PNG: CDFs of
// fragment size, energy balance over time, force–displacement of the platens, verification error
// versus run time (docs/design.md "Figures"). Axes carry ticks at nice 1–2–5 values, tick labels,
// axis labels, a title and a legend; either axis may be logarithmic.
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

#include "fragmpm/analysis/axis_ticks.hpp"

namespace fragmpm::analysis {

struct LineSeries {
  std::string label;         ///< legend entry; empty = not in the legend
  std::vector<double> x, y;  ///< same length, drawn in the order given
  bool markers = false;      ///< a round marker at each point
  bool line = true;          ///< false: markers only (a scatter plot)
  bool dashed = false;       ///< dashed line (e.g. the edges of a band around another series)
  int colour = -1;           ///< palette index; −1 = the series' own index in the plot
};

struct PlotSpec {
  std::string title, x_label, y_label;
  bool log_x = false, log_y = false;
  std::vector<LineSeries> series;
  int width = 1200, height = 900;  ///< pixels
};

/// Where the axes of a plot fall: the plot area [left, right) × [top, bottom) in pixels (the axis
/// frame is drawn just outside it), the ticks of each axis, and the data → pixel maps.
struct PlotFrame {
  int left = 0, top = 0, right = 0, bottom = 0;
  int axis_width = 1;  ///< frame line width in pixels
  AxisTicks x, y;
  bool log_x = false, log_y = false;
  double to_px(double x_value) const;  ///< pixel column (continuous) of a data x
  double to_py(double y_value) const;  ///< pixel row (continuous, y down) of a data y
};

/// Checks the spec and lays the plot out. Throws FigureError naming the plot, series and point on
/// bad input: no series, a series without points or with x and y of different lengths, a
/// non-finite value, a non-positive value on a log axis, or a size outside [200, 16384] pixels.
PlotFrame plot_frame(const PlotSpec& spec);

/// The plot as an 8-bit BGR image (height × width).
cv::Mat render_line_plot(const PlotSpec& spec);

/// Renders and writes the plot as PNG (replacing an existing file).
void write_line_plot(const PlotSpec& spec, const std::string& png_path);

}  // namespace fragmpm::analysis
