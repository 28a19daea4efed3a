// Line plots (see plot.hpp): OpenGL (OSMesa) draws grid, lines, markers, frame and ticks; OpenCV
// draws the text after read-back and writes the PNG.
#include "fragmpm/analysis/plot.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "figure_text.hpp"
#include "fragmpm/analysis/colour_map.hpp"
#include "fragmpm/analysis/figure_error.hpp"
#include "fragmpm/analysis/offscreen.hpp"
#include "fragmpm/analysis/png_file.hpp"
#include "gl_draw.hpp"

namespace fragmpm::analysis {

using namespace detail;

namespace {

const Rgb axis_colour{0, 0, 0};
const Rgb grid_colour{228, 228, 228};
const Rgb legend_border{150, 150, 150};

std::string plot_name(const PlotSpec& spec) {
  return spec.title.empty() ? std::string("line plot") : fmt::format("line plot '{}'", spec.title);
}

std::string series_name(const LineSeries& s, std::size_t i) {
  return s.label.empty() ? fmt::format("series {}", i + 1)
                         : fmt::format("series {} '{}'", i + 1, s.label);
}

void validate(const PlotSpec& spec) {
  if (spec.width < 200 || spec.height < 200 || spec.width > 16384 || spec.height > 16384)
    throw FigureError(fmt::format("{}: size {} x {} pixels; expected each side in [200, 16384]",
                                  plot_name(spec), spec.width, spec.height));
  if (spec.series.empty()) throw FigureError(plot_name(spec) + ": no series to draw");
  for (std::size_t i = 0; i < spec.series.size(); ++i) {
    const LineSeries& s = spec.series[i];
    if (s.x.size() != s.y.size())
      throw FigureError(fmt::format("{}, {}: {} x values but {} y values", plot_name(spec),
                                    series_name(s, i), s.x.size(), s.y.size()));
    if (s.x.empty())
      throw FigureError(fmt::format("{}, {}: no points", plot_name(spec), series_name(s, i)));
    for (std::size_t k = 0; k < s.x.size(); ++k) {
      for (int axis = 0; axis < 2; ++axis) {
        const double v = axis == 0 ? s.x[k] : s.y[k];
        const char* name = axis == 0 ? "x" : "y";
        if (!std::isfinite(v))
          throw FigureError(fmt::format("{}, {}, point {}: {} = {} is not finite", plot_name(spec),
                                        series_name(s, i), k + 1, name, v));
        if ((axis == 0 ? spec.log_x : spec.log_y) && v <= 0.0)
          throw FigureError(
              fmt::format("{}, {}, point {}: {} = {} is not positive; the log {} axis "
                          "needs positive values",
                          plot_name(spec), series_name(s, i), k + 1, name, v, name));
      }
    }
  }
}

double axis_fraction(double v, double lo, double hi, bool log) {
  return log ? (std::log10(v) - std::log10(lo)) / (std::log10(hi) - std::log10(lo))
             : (v - lo) / (hi - lo);
}

struct LegendBox {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  double row_height = 0, swatch = 0;
};

struct Legend {
  std::vector<std::size_t> entries;  ///< indices of labelled series
  double width = 0, height = 0, row_height = 0, swatch = 0;
};

Legend legend_size(const PlotSpec& spec, const FigureStyle& st) {
  Legend l;
  double text_w = 0, text_h = 0;
  for (std::size_t i = 0; i < spec.series.size(); ++i) {
    if (spec.series[i].label.empty()) continue;
    l.entries.push_back(i);
    const cv::Size sz = text_extent(plain(spec.series[i].label), st.tick_font);
    text_w = std::max<double>(text_w, sz.width);
    text_h = std::max<double>(text_h, sz.height);
  }
  l.swatch = 40.0 * st.scale;
  l.row_height = text_h + 6.0 * st.scale;
  l.width = 2 * st.pad + l.swatch + 0.7 * st.pad + text_w;
  l.height = 2 * (0.6 * st.pad) + l.row_height * static_cast<double>(l.entries.size());
  return l;
}

/// The corner of the plot area where the legend covers the fewest sampled points of the lines.
LegendBox place_legend(const PlotSpec& spec, const PlotFrame& f, const Legend& l,
                       const FigureStyle& st) {
  const double inset = st.pad;
  std::vector<LegendBox> candidates;
  for (int corner = 0; corner < 4; ++corner) {
    LegendBox b;
    b.x0 = (corner % 2 == 0) ? f.right - inset - l.width : f.left + inset;
    b.y0 = (corner < 2) ? f.top + inset : f.bottom - inset - l.height;
    b.x1 = b.x0 + l.width;
    b.y1 = b.y0 + l.height;
    candidates.push_back(b);
  }
  std::vector<long> covered(candidates.size(), 0);
  for (const LineSeries& s : spec.series) {
    for (std::size_t k = 0; k < s.x.size(); ++k) {
      const int samples = k + 1 < s.x.size() ? 8 : 1;
      for (int j = 0; j < samples; ++j) {
        const double t = static_cast<double>(j) / samples;
        const double px0 = f.to_px(s.x[k]), py0 = f.to_py(s.y[k]);
        const double px = samples > 1 ? px0 + t * (f.to_px(s.x[k + 1]) - px0) : px0;
        const double py = samples > 1 ? py0 + t * (f.to_py(s.y[k + 1]) - py0) : py0;
        for (std::size_t c = 0; c < candidates.size(); ++c)
          if (px >= candidates[c].x0 && px <= candidates[c].x1 && py >= candidates[c].y0 &&
              py <= candidates[c].y1)
            ++covered[c];
      }
    }
  }
  const auto best = std::min_element(covered.begin(), covered.end()) - covered.begin();
  LegendBox b = candidates[static_cast<std::size_t>(best)];
  b.row_height = l.row_height;
  b.swatch = l.swatch;
  return b;
}

}  // namespace

double PlotFrame::to_px(double v) const {
  return left + axis_fraction(v, x.lo, x.hi, log_x) * (right - left);
}

double PlotFrame::to_py(double v) const {
  return bottom - axis_fraction(v, y.lo, y.hi, log_y) * (bottom - top);
}

PlotFrame plot_frame(const PlotSpec& spec) {
  validate(spec);
  const FigureStyle st = figure_style(spec.width, spec.height);
  double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo, y_lo = x_lo, y_hi = -x_lo;
  for (const LineSeries& s : spec.series) {
    for (double v : s.x) x_lo = std::min(x_lo, v), x_hi = std::max(x_hi, v);
    for (double v : s.y) y_lo = std::min(y_lo, v), y_hi = std::max(y_hi, v);
  }
  PlotFrame f;
  f.log_x = spec.log_x;
  f.log_y = spec.log_y;
  f.axis_width = st.axis_width;
  f.x = spec.log_x ? log_ticks(x_lo, x_hi) : linear_ticks(x_lo, x_hi);
  f.y = spec.log_y ? log_ticks(y_lo, y_hi) : linear_ticks(y_lo, y_hi);

  double y_tick_w = 0, x_tick_h = 0, last_x_tick_w = 0;
  for (const RichText& t : f.y.labels)
    y_tick_w = std::max<double>(y_tick_w, text_extent(t, st.tick_font).width);
  for (const RichText& t : f.x.labels)
    x_tick_h = std::max<double>(x_tick_h, text_extent(t, st.tick_font).height);
  if (!f.x.labels.empty()) last_x_tick_w = text_extent(f.x.labels.back(), st.tick_font).width;
  const double y_label_h =
      spec.y_label.empty() ? 0 : text_extent(plain(spec.y_label), st.label_font).height;
  const double x_label_h =
      spec.x_label.empty() ? 0 : text_extent(plain(spec.x_label), st.label_font).height;
  const double title_h =
      spec.title.empty() ? 0 : text_extent(plain(spec.title), st.title_font).height;
  const double y_mult_h =
      f.y.multiplier.empty() ? 0 : text_extent(f.y.multiplier, st.tick_font).height;
  const double gap = 0.5 * st.pad;

  f.left = static_cast<int>(
      std::lround(st.pad + y_label_h + st.pad + y_tick_w + gap + st.tick_length + st.axis_width));
  f.right = spec.width -
            static_cast<int>(std::lround(2 * st.pad + std::max(0.0, 0.5 * last_x_tick_w - st.pad)));
  f.top =
      static_cast<int>(std::lround(st.pad + title_h + st.pad + std::max(st.pad, y_mult_h + gap)));
  f.bottom = spec.height - static_cast<int>(std::lround(st.axis_width + st.tick_length + gap +
                                                        x_tick_h + st.pad + x_label_h + st.pad));
  if (f.right - f.left < 50 || f.bottom - f.top < 50)
    throw FigureError(
        fmt::format("{}: {} x {} pixels leave no room for the plot area after the labels",
                    plot_name(spec), spec.width, spec.height));
  return f;
}

cv::Mat render_line_plot(const PlotSpec& spec) {
  const PlotFrame f = plot_frame(spec);
  const FigureStyle st = figure_style(spec.width, spec.height);
  const double s = st.scale;
  const int aw = f.axis_width;
  const Legend legend = legend_size(spec, st);
  const LegendBox box = legend.entries.empty() ? LegendBox{} : place_legend(spec, f, legend, st);

  OffscreenContext gl(spec.width, spec.height);
  // Grid at the major ticks, under the data.
  for (double v : f.x.major) {
    const double px = std::floor(f.to_px(v));
    fill_rect(px, f.top, px + 1, f.bottom, grid_colour);
  }
  for (double v : f.y.major) {
    const double py = std::floor(f.to_py(v));
    fill_rect(f.left, py, f.right, py + 1, grid_colour);
  }
  // Data, clipped to the plot area.
  clip_to(f.left, f.top, f.right, f.bottom, spec.height);
  const double line_width = std::max(1.5, 2.6 * s);
  for (std::size_t i = 0; i < spec.series.size(); ++i) {
    const LineSeries& ser = spec.series[i];
    std::vector<PixelPoint> pts;
    pts.reserve(ser.x.size());
    for (std::size_t k = 0; k < ser.x.size(); ++k)
      pts.push_back({f.to_px(ser.x[k]), f.to_py(ser.y[k])});
    const std::size_t ci = ser.colour >= 0 ? static_cast<std::size_t>(ser.colour) : i;
    const Rgb c = series_colour(ci);
    const bool dashed = ser.dashed || ci >= 10;  // colours repeat after ten: dashes tell them apart
    if (ser.line) draw_polyline(pts, line_width, c, dashed);
    if (ser.markers || !ser.line || pts.size() == 1) draw_markers(pts, std::max(4.0, 9.0 * s), c);
  }
  clip_off();
  // Axis frame just outside the plot area, and outward ticks on the left and bottom axes.
  stroke_rect(f.left - aw, f.top - aw, f.right + aw, f.bottom + aw, aw, axis_colour);
  const double tl = st.tick_length;
  for (double v : f.x.major) {
    const double px = std::floor(f.to_px(v));
    fill_rect(px, f.bottom + aw, px + aw, f.bottom + aw + tl, axis_colour);
  }
  for (double v : f.x.minor) {
    const double px = std::floor(f.to_px(v));
    fill_rect(px, f.bottom + aw, px + 1, f.bottom + aw + 0.5 * tl, axis_colour);
  }
  for (double v : f.y.major) {
    const double py = std::floor(f.to_py(v));
    fill_rect(f.left - aw - tl, py, f.left - aw, py + aw, axis_colour);
  }
  for (double v : f.y.minor) {
    const double py = std::floor(f.to_py(v));
    fill_rect(f.left - aw - 0.5 * tl, py, f.left - aw, py + 1, axis_colour);
  }
  // Legend box with a line (and marker) swatch per labelled series.
  if (!legend.entries.empty()) {
    fill_rect(box.x0, box.y0, box.x1, box.y1, Rgb{255, 255, 255});
    stroke_rect(box.x0, box.y0, box.x1, box.y1, 1, legend_border);
    for (std::size_t r = 0; r < legend.entries.size(); ++r) {
      const std::size_t i = legend.entries[r];
      const double cy = box.y0 + 0.6 * st.pad + (r + 0.5) * box.row_height;
      const double x0 = box.x0 + st.pad;
      std::vector<PixelPoint> pts{{x0, cy}, {x0 + box.swatch, cy}};
      const LineSeries& ser = spec.series[i];
      const std::size_t ci = ser.colour >= 0 ? static_cast<std::size_t>(ser.colour) : i;
      if (ser.line) draw_polyline(pts, line_width, series_colour(ci), ser.dashed || ci >= 10);
      if (ser.markers || !ser.line)
        draw_markers({{x0 + 0.5 * box.swatch, cy}}, std::max(4.0, 9.0 * s), series_colour(ci));
    }
  }
  cv::Mat image = gl.read_bgr();

  // Text.
  const double gap = 0.5 * st.pad;
  for (std::size_t k = 0; k < f.x.major.size(); ++k)
    draw_text(image, f.x.labels[k], {f.to_px(f.x.major[k]), f.bottom + aw + tl + gap},
              HAlign::centre, VAlign::top, st.tick_font);
  for (std::size_t k = 0; k < f.y.major.size(); ++k)
    draw_text(image, f.y.labels[k], {f.left - aw - tl - gap, f.to_py(f.y.major[k])}, HAlign::right,
              VAlign::centre, st.tick_font);
  const double x_tick_h =
      f.x.labels.empty() ? 0 : text_extent(f.x.labels.front(), st.tick_font).height;
  const double x_label_y = f.bottom + aw + tl + gap + x_tick_h + st.pad;
  if (!spec.x_label.empty())
    draw_text(image, plain(spec.x_label), {0.5 * (f.left + f.right), x_label_y}, HAlign::centre,
              VAlign::top, st.label_font);
  if (!f.x.multiplier.empty())
    draw_text(image, f.x.multiplier, {static_cast<double>(f.right), x_label_y}, HAlign::right,
              VAlign::top, st.tick_font);
  if (!spec.y_label.empty())
    draw_text(image, plain(spec.y_label), {st.pad, 0.5 * (f.top + f.bottom)}, HAlign::left,
              VAlign::centre, st.label_font, true);
  if (!f.y.multiplier.empty())
    draw_text(image, f.y.multiplier, {static_cast<double>(f.left - aw), f.top - aw - gap},
              HAlign::left, VAlign::bottom, st.tick_font);
  if (!spec.title.empty())
    draw_text(image, plain(spec.title), {0.5 * (f.left + f.right), st.pad}, HAlign::centre,
              VAlign::top, st.title_font);
  for (std::size_t r = 0; r < legend.entries.size(); ++r) {
    const double cy = box.y0 + 0.6 * st.pad + (r + 0.5) * box.row_height;
    draw_text(image, plain(spec.series[legend.entries[r]].label),
              {box.x0 + st.pad + box.swatch + 0.7 * st.pad, cy}, HAlign::left, VAlign::centre,
              st.tick_font);
  }
  return image;
}

void write_line_plot(const PlotSpec& spec, const std::string& png_path) {
  write_png(render_line_plot(spec), png_path);
}

}  // namespace fragmpm::analysis
