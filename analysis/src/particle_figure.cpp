// Particle figures (see particle_figure.hpp): OpenGL (OSMesa) fills the particle domains, the
// colour bar or id swatches and the scale bar; OpenCV adds the text and writes the PNG.
#include "fragmpm/analysis/particle_figure.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "figure_text.hpp"
#include "fragmpm/analysis/axis_ticks.hpp"
#include "fragmpm/analysis/colour_map.hpp"
#include "fragmpm/analysis/figure_error.hpp"
#include "fragmpm/analysis/offscreen.hpp"
#include "fragmpm/analysis/png_file.hpp"
#include "fragmpm/analysis/si_format.hpp"
#include "gl_draw.hpp"

namespace fragmpm::analysis {

using namespace detail;

namespace {

constexpr std::size_t max_legend_rows = 15;

std::string figure_name(const ParticleFigure& f) {
  return f.title.empty() ? std::string("particle figure")
                         : fmt::format("particle figure '{}'", f.title);
}

bool dimensionless(const std::string& units) {
  return units.empty() || units == "1" || units == "-";
}

std::string bar_label(const ParticleFigure& f) {
  return dimensionless(f.units) ? f.field_name : fmt::format("{} [{}]", f.field_name, f.units);
}

/// Sorted distinct ids for the legend; negative ids collapse into one "none" entry (-1).
std::vector<std::int64_t> legend_ids(const std::vector<std::int64_t>& ids) {
  std::set<std::int64_t> distinct;
  for (std::int64_t id : ids) distinct.insert(id < 0 ? -1 : id);
  std::vector<std::int64_t> out(distinct.begin(), distinct.end());
  if (!out.empty() && out.front() < 0)
    std::rotate(out.begin(), out.begin() + 1, out.end());  // "none" last
  return out;
}

std::string id_text(const ParticleFigure& f, std::int64_t id) {
  return id < 0 ? f.none_name : fmt::format("{} {}", f.id_name, id);
}

struct Layout {
  ParticleFrame frame;
  AxisTicks bar_ticks;               ///< continuous fields
  std::vector<std::int64_t> legend;  ///< ids shown (categorical)
  std::string overflow_text;         ///< "... 18 fragments in all" when not every id fits
  double legend_left = 0, legend_top = 0, legend_row = 0, legend_swatch = 0;
  double bottom_text_y = 0;  ///< top of the scale-bar / time row
  double drawn_right = 0;    ///< right edge of the particles [px]
  double title_centre = 0;
};

Layout layout(const ParticleFigure& fig) {
  const std::string name = figure_name(fig);
  if (fig.width < 200 || fig.height < 200 || fig.width > 16384 || fig.height > 16384)
    throw FigureError(fmt::format("{}: size {} x {} pixels; expected each side in [200, 16384]",
                                  name, fig.width, fig.height));
  const std::size_t n = fig.x.size();
  if (n == 0) throw FigureError(name + ": no particles");
  if (fig.r1.size() != n || fig.r2.size() != n)
    throw FigureError(fmt::format("{}: {} centres but {} r1 and {} r2 vectors", name, n,
                                  fig.r1.size(), fig.r2.size()));
  const bool categorical = !fig.ids.empty();
  if (categorical == !fig.values.empty())
    throw FigureError(
        name + ": give either a value per particle or an id per particle (exactly one of the two)");
  const std::size_t colours = categorical ? fig.ids.size() : fig.values.size();
  if (colours != n)
    throw FigureError(fmt::format("{}: {} particles but {} {}", name, n, colours,
                                  categorical ? "ids" : "values"));

  double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo, y_lo = x_lo, y_hi = -x_lo;
  bool any_area = false;
  for (std::size_t i = 0; i < n; ++i) {
    if (!fig.x[i].allFinite() || !fig.r1[i].allFinite() || !fig.r2[i].allFinite())
      throw FigureError(
          fmt::format("{}: particle {}: position or domain vectors not finite", name, i));
    const double area = std::abs(fig.r1[i].x() * fig.r2[i].y() - fig.r1[i].y() * fig.r2[i].x());
    any_area = any_area || area > 0.0;
    for (int a = -1; a <= 1; a += 2)
      for (int b = -1; b <= 1; b += 2) {
        const Eigen::Vector2d c = fig.x[i] + 0.5 * a * fig.r1[i] + 0.5 * b * fig.r2[i];
        x_lo = std::min(x_lo, c.x()), x_hi = std::max(x_hi, c.x());
        y_lo = std::min(y_lo, c.y()), y_hi = std::max(y_hi, c.y());
      }
  }
  if (!any_area)
    throw FigureError(
        name + ": every particle domain has zero area (are the r1, r2 domain vectors missing?)");

  const FigureStyle st = figure_style(fig.width, fig.height);
  Layout l;
  ParticleFrame& pf = l.frame;
  const double title_h =
      fig.title.empty() ? 0 : text_extent(plain(fig.title), st.title_font).height;
  const double row_h = text_extent(plain("0 mm"), st.label_font).height;
  const double bar_thickness = std::max(3.0, 7.0 * st.scale);
  const double top = st.pad + (title_h > 0 ? title_h + st.pad : 0);
  const double bottom_strip = st.pad + bar_thickness + 0.5 * st.pad + row_h + st.pad;

  // Right strip: colour bar with ticks, labels and the rotated field label, or the id legend.
  double strip = 0;
  if (!categorical) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (double v : fig.values)
      if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
    if (!std::isfinite(lo)) lo = 0.0, hi = 1.0;  // no finite value: everything is drawn grey
    if (fig.vmin) lo = *fig.vmin;
    if (fig.vmax) hi = *fig.vmax;
    if (!std::isfinite(lo) || !std::isfinite(hi) || hi < lo)
      throw FigureError(
          fmt::format("{}: colour range [{}, {}] is empty or not finite", name, lo, hi));
    l.bar_ticks = linear_ticks(lo, hi, 0.0);
    pf.vmin = l.bar_ticks.lo;
    pf.vmax = l.bar_ticks.hi;
    double tick_w = 0;
    for (const RichText& t : l.bar_ticks.labels)
      tick_w = std::max<double>(tick_w, text_extent(t, st.tick_font).width);
    const double label_h = text_extent(plain(bar_label(fig)), st.label_font).height;
    const double bar_w = std::max(12.0, 30.0 * st.scale);
    strip = 2 * st.pad + bar_w + st.tick_length + 0.5 * st.pad + tick_w + st.pad + label_h + st.pad;
    pf.bar_right = static_cast<int>(std::lround(fig.width - strip + 2 * st.pad + bar_w));
    pf.bar_left = static_cast<int>(std::lround(fig.width - strip + 2 * st.pad));
  } else {
    // Ids in order, "none" last; when they do not fit, the first ids, "none", and a count of all.
    const std::vector<std::int64_t> ids = legend_ids(fig.ids);
    const bool has_none = !ids.empty() && ids.back() < 0;
    const std::size_t named = ids.size() - (has_none ? 1 : 0);
    l.legend = ids;
    if (ids.size() > max_legend_rows) {
      l.legend.assign(ids.begin(),
                      ids.begin() + static_cast<long>(max_legend_rows - 1 - (has_none ? 1 : 0)));
      if (has_none) l.legend.push_back(-1);
      l.overflow_text = fmt::format("... {} {}s in all", named, fig.id_name);
    }
    double text_w = 0;
    for (std::int64_t id : l.legend)
      text_w = std::max<double>(text_w, text_extent(plain(id_text(fig, id)), st.tick_font).width);
    if (!l.overflow_text.empty())
      text_w = std::max<double>(text_w, text_extent(plain(l.overflow_text), st.tick_font).width);
    l.legend_swatch = std::max(8.0, 22.0 * st.scale);
    l.legend_row = std::max<double>(l.legend_swatch, row_h) + 0.6 * st.pad;
    strip = 2 * st.pad + l.legend_swatch + 0.7 * st.pad + text_w + st.pad;
    l.legend_left = fig.width - strip + 2 * st.pad;
  }

  const double area_left = st.pad, area_right = fig.width - strip;
  const double area_top = top, area_bottom = fig.height - bottom_strip;
  if (area_right - area_left < 50 || area_bottom - area_top < 50)
    throw FigureError(fmt::format("{}: {} x {} pixels leave no room for the particles", name,
                                  fig.width, fig.height));
  pf.scale =
      std::min((area_right - area_left) / (x_hi - x_lo), (area_bottom - area_top) / (y_hi - y_lo));
  pf.x_min = x_lo;
  pf.y_min = y_lo;
  // Centre the particles in the free area; the scale-bar row follows right under them.
  const double drawn_w = pf.scale * (x_hi - x_lo), drawn_h = pf.scale * (y_hi - y_lo);
  pf.left = area_left + 0.5 * (area_right - area_left - drawn_w);
  pf.bottom = area_top + drawn_h + 0.5 * (area_bottom - area_top - drawn_h);
  l.drawn_right = pf.left + drawn_w;
  l.bottom_text_y = pf.bottom + st.pad;
  const double mid = pf.bottom - 0.5 * drawn_h;

  if (!categorical) {
    const double bar_h =
        std::min(area_bottom - area_top, std::max(drawn_h, 0.6 * (area_bottom - area_top)));
    pf.bar_top = static_cast<int>(std::lround(std::max(area_top, mid - 0.5 * bar_h)));
    pf.bar_bottom = static_cast<int>(std::lround(pf.bar_top + bar_h));
  } else {
    const double rows = static_cast<double>(l.legend.size() + (l.overflow_text.empty() ? 0 : 1));
    l.legend_top = std::max(area_top, mid - 0.5 * rows * l.legend_row);
  }
  pf.scale_bar_length = scale_bar_length(0.3 * (x_hi - x_lo));
  l.title_centre = 0.5 * (area_left + area_right);
  return l;
}

}  // namespace

Eigen::Vector2d ParticleFrame::to_pixel(const Eigen::Vector2d& p) const {
  return {left + scale * (p.x() - x_min), bottom - scale * (p.y() - y_min)};
}

ParticleFrame particle_frame(const ParticleFigure& figure) {
  return layout(figure).frame;
}

cv::Mat render_particle_figure(const ParticleFigure& fig) {
  const Layout l = layout(fig);
  const ParticleFrame& pf = l.frame;
  const FigureStyle st = figure_style(fig.width, fig.height);
  const bool categorical = !fig.ids.empty();
  const Rgb black{0, 0, 0};

  OffscreenContext gl(fig.width, fig.height);
  // Particle domains: two flat triangles per parallelogram (corners x ± r1/2 ± r2/2).
  const std::size_t n = fig.x.size();
  std::vector<float> xy;
  std::vector<std::uint8_t> rgb;
  xy.reserve(12 * n);
  rgb.reserve(6 * n);
  const double range = pf.vmax - pf.vmin;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d h1 = 0.5 * fig.r1[i], h2 = 0.5 * fig.r2[i];
    const Eigen::Vector2d c[4] = {pf.to_pixel(fig.x[i] - h1 - h2), pf.to_pixel(fig.x[i] + h1 - h2),
                                  pf.to_pixel(fig.x[i] + h1 + h2), pf.to_pixel(fig.x[i] - h1 + h2)};
    const Rgb colour =
        categorical ? categorical_colour(fig.ids[i])
                    : viridis(std::isfinite(fig.values[i]) ? (fig.values[i] - pf.vmin) / range
                                                           : std::nan(""));
    for (int t : {0, 2}) {  // triangles (c0, c1, c2) and (c2, c3, c0)
      for (int k : {t, t + 1, (t + 2) % 4}) {
        xy.push_back(static_cast<float>(c[k].x()));
        xy.push_back(static_cast<float>(c[k].y()));
      }
      rgb.insert(rgb.end(), {colour.r, colour.g, colour.b});
    }
  }
  fill_triangles(xy, rgb);

  const int aw = st.axis_width;
  if (!categorical) {
    // Colour bar: one flat band per pixel row, value increasing upwards.
    for (int y = pf.bar_top; y < pf.bar_bottom; ++y) {
      const double t = (pf.bar_bottom - 0.5 - y) / static_cast<double>(pf.bar_bottom - pf.bar_top);
      fill_rect(pf.bar_left, y, pf.bar_right, y + 1, viridis(t));
    }
    stroke_rect(pf.bar_left - 1, pf.bar_top - 1, pf.bar_right + 1, pf.bar_bottom + 1, 1, black);
    for (double v : l.bar_ticks.major) {
      const double y =
          std::floor(pf.bar_bottom - (v - pf.vmin) / range * (pf.bar_bottom - pf.bar_top));
      fill_rect(pf.bar_right + 1, std::min<double>(y, pf.bar_bottom - aw),
                pf.bar_right + 1 + st.tick_length, std::min<double>(y, pf.bar_bottom - aw) + aw,
                black);
    }
  } else {
    for (std::size_t r = 0; r < l.legend.size(); ++r) {
      const double y = l.legend_top + r * l.legend_row + 0.5 * (l.legend_row - l.legend_swatch);
      fill_rect(l.legend_left, y, l.legend_left + l.legend_swatch, y + l.legend_swatch,
                categorical_colour(l.legend[r]));
      stroke_rect(l.legend_left, y, l.legend_left + l.legend_swatch, y + l.legend_swatch, 1,
                  Rgb{90, 90, 90});
    }
  }
  // Scale bar under the lower-left corner of the particles.
  const double bar_thickness = std::max(3.0, 7.0 * st.scale);
  const double sb_x0 = std::floor(pf.left), sb_len = pf.scale_bar_length * pf.scale;
  fill_rect(sb_x0, l.bottom_text_y, sb_x0 + sb_len, l.bottom_text_y + bar_thickness, black);
  cv::Mat image = gl.read_bgr();

  // Text.
  if (!fig.title.empty())
    draw_text(image, plain(fig.title), {l.title_centre, st.pad}, HAlign::centre, VAlign::top,
              st.title_font);
  const double text_y = l.bottom_text_y + bar_thickness + 0.5 * st.pad;
  draw_text(image, plain(format_si(pf.scale_bar_length, "m")), {sb_x0 + 0.5 * sb_len, text_y},
            HAlign::centre, VAlign::top, st.label_font);
  if (fig.time)
    draw_text(image, plain("t = " + format_si(*fig.time, "s", 4)), {l.drawn_right, text_y},
              HAlign::right, VAlign::top, st.label_font);
  if (!categorical) {
    double tick_w = 0;
    for (std::size_t k = 0; k < l.bar_ticks.major.size(); ++k) {
      const double y =
          pf.bar_bottom - (l.bar_ticks.major[k] - pf.vmin) / range * (pf.bar_bottom - pf.bar_top);
      draw_text(image, l.bar_ticks.labels[k], {pf.bar_right + 1 + st.tick_length + 0.5 * st.pad, y},
                HAlign::left, VAlign::centre, st.tick_font);
      tick_w = std::max<double>(tick_w, text_extent(l.bar_ticks.labels[k], st.tick_font).width);
    }
    if (!l.bar_ticks.multiplier.empty())
      draw_text(image, l.bar_ticks.multiplier,
                {static_cast<double>(pf.bar_left), pf.bar_top - 0.5 * st.pad}, HAlign::left,
                VAlign::bottom, st.tick_font);
    const double label_x = pf.bar_right + 1 + st.tick_length + 0.5 * st.pad + tick_w + st.pad;
    draw_text(image, plain(bar_label(fig)), {label_x, 0.5 * (pf.bar_top + pf.bar_bottom)},
              HAlign::left, VAlign::centre, st.label_font, true);
  } else {
    for (std::size_t r = 0; r < l.legend.size(); ++r) {
      const double cy = l.legend_top + (r + 0.5) * l.legend_row;
      draw_text(image, plain(id_text(fig, l.legend[r])),
                {l.legend_left + l.legend_swatch + 0.7 * st.pad, cy}, HAlign::left, VAlign::centre,
                st.tick_font);
    }
    if (!l.overflow_text.empty())
      draw_text(image, plain(l.overflow_text),
                {l.legend_left, l.legend_top + (l.legend.size() + 0.5) * l.legend_row},
                HAlign::left, VAlign::centre, st.tick_font);
  }
  return image;
}

void write_particle_figure(const ParticleFigure& figure, const std::string& png_path) {
  write_png(render_particle_figure(figure), png_path);
}

double scale_bar_length(double max_length) {
  if (!(max_length > 0.0) || !std::isfinite(max_length))
    throw FigureError(
        fmt::format("scale bar: the longest allowed length {} m is not positive", max_length));
  const double magnitude = std::pow(10.0, std::floor(std::log10(max_length)));
  for (double m : {5.0, 2.0, 1.0})
    if (m * magnitude <= max_length * (1 + 1e-12)) return m * magnitude;
  return magnitude;
}

}  // namespace fragmpm::analysis
