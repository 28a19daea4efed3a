// Figure text with DejaVu Sans through OpenCV's FreeType module, or the Hershey fonts when no
// TrueType font is installed (see figure_text.hpp).
#include "figure_text.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <opencv2/freetype.hpp>
#include <opencv2/imgproc.hpp>
#include <utility>
#include <vector>

#include "fragmpm/analysis/label_text.hpp"

namespace fragmpm::analysis::detail {

namespace {

constexpr int font = cv::FONT_HERSHEY_SIMPLEX;
constexpr double superscript_scale = 0.68;
/// Pixel height of the TrueType em per unit of TextStyle::scale: DejaVu Sans capitals are 0.73 em,
/// so a scale of 1 gives the 22 px capitals of the Hershey font it replaces.
constexpr double em_per_scale = 30.0;

/// The TrueType font of this thread (FreeType2 objects are not shared between threads), or null
/// when none is installed. FRAGMPM_FONT names another font file.
cv::freetype::FreeType2* truetype() {
  thread_local std::unique_ptr<cv::Ptr<cv::freetype::FreeType2>> loaded;
  if (!loaded) {
    loaded = std::make_unique<cv::Ptr<cv::freetype::FreeType2>>();
    std::vector<std::string> candidates;
    if (const char* env = std::getenv("FRAGMPM_FONT")) candidates.emplace_back(env);
    candidates.emplace_back("/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf");
    for (const std::string& path : candidates) {
      std::error_code ec;
      if (!std::filesystem::is_regular_file(path, ec)) continue;
      try {
        cv::Ptr<cv::freetype::FreeType2> f = cv::freetype::createFreeType2();
        f->loadFontData(path, 0);
        *loaded = f;
        break;
      } catch (const cv::Exception&) {
        // not a font FreeType can read: try the next one, then fall back to Hershey
      }
    }
  }
  return loaded->get();
}

/// FreeType2::putText places a run by the top of the font's line, not by its baseline: the
/// distance from that point down to the baseline, found once per font height by drawing "H" (which
/// sits on the baseline and has no descender) and taking the row below its lowest ink.
int baseline_below_origin(cv::freetype::FreeType2& f, int height) {
  thread_local std::vector<std::pair<int, int>> known;
  for (const auto& [h, offset] : known)
    if (h == height) return offset;
  cv::Mat probe = cv::Mat::zeros(4 * height + 8, 2 * height + 8, CV_8UC3);
  f.putText(probe, "H", cv::Point(2, 0), height, cv::Scalar(255, 255, 255), -1, cv::LINE_8, false);
  int lowest = -1;
  for (int r = 0; r < probe.rows; ++r)
    for (int c = 0; c < probe.cols; ++c)
      if (probe.at<cv::Vec3b>(r, c)[0] > 127) lowest = r;
  const int offset = lowest + 1;
  known.emplace_back(height, offset);
  return offset;
}

/// The text as drawn: UTF-8 with a TrueType font, transliterated ASCII with Hershey.
std::string drawable(const std::string& utf8) {
  return truetype() ? utf8 : ascii_text(utf8);
}

cv::Size measure(const std::string& s, double scale, int thickness, int* descent) {
  if (auto* f = truetype()) {
    int baseline = 0;
    const int height = static_cast<int>(std::lround(em_per_scale * scale));
    const cv::Size size = f->getTextSize(s, height, -1, &baseline);
    if (descent) *descent = baseline;
    return size;
  }
  return cv::getTextSize(s, font, scale, thickness, descent);
}

struct Placed {
  std::string text;
  double scale;
  int x;         ///< left of the run in the text box
  int baseline;  ///< baseline y in the text box
};

struct Layout {
  std::vector<Placed> runs;
  cv::Size size;  ///< nominal box: capital height + descent (+ superscripts) + padding
  int extra = 0;  ///< rows above the nominal box for glyphs taller than capitals ([, (, |)
};

/// Lays runs out left to right; superscripts are smaller and raised by half the capital height.
Layout layout(const RichText& text, const TextStyle& style) {
  int x = 0, top = 0, bottom = 0;  // relative to the main baseline (y down, top negative)
  std::vector<std::pair<Placed, int>> runs;
  int base_height = measure("0", style.scale, style.thickness, nullptr).height;
  for (const TextRun& r : text) {
    const std::string s = drawable(r.text);
    if (s.empty()) continue;
    const double scale = r.superscript ? style.scale * superscript_scale : style.scale;
    int descent = 0;
    const cv::Size sz = measure(s, scale, style.thickness, &descent);
    const int raise = r.superscript ? static_cast<int>(std::lround(0.55 * base_height)) : 0;
    runs.push_back({Placed{s, scale, x, 0}, raise});
    top = std::min(top, -raise - sz.height);
    bottom = std::max(bottom, -raise + descent);
    x += sz.width + (r.superscript ? 2 : 0);
  }
  Layout out;
  const int pad = style.thickness + 1;  // antialiased strokes spill over the nominal box
  out.extra = static_cast<int>(std::ceil(0.35 * base_height));
  for (auto& [p, raise] : runs) {
    p.baseline = -top - raise + pad + out.extra;
    p.x += pad;
    out.runs.push_back(p);
  }
  out.size = cv::Size(x + 2 * pad, bottom - top + 2 * pad);
  return out;
}

}  // namespace

std::string ascii_text(const std::string& utf8) {
  static const std::vector<std::pair<std::string, std::string>> table{
      {"\u00b5", "u"},     {"\u03bc", "u"},     {"\u00b0", " deg"}, {"\u03c3", "sigma"},
      {"\u03b8", "theta"}, {"\u0394", "Delta"}, {"\u2212", "-"},    {"\u2013", "-"},
      {"\u2014", "-"},     {"\u00b2", "^2"},    {"\u00b3", "^3"},   {"\u00d7", "x"},
      {"\u2264", "<="},    {"\u2265", ">="},    {"\u00b1", "+/-"},  {"\u2026", "..."},
      {"\u2192", "->"},    {"\u00b7", "."}};
  std::string out;
  for (std::size_t i = 0; i < utf8.size();) {
    const unsigned char c = static_cast<unsigned char>(utf8[i]);
    if (c < 0x80) {
      out += (c >= 0x20 && c < 0x7f) ? static_cast<char>(c) : ' ';
      ++i;
      continue;
    }
    bool matched = false;
    for (const auto& [from, to] : table) {
      if (utf8.compare(i, from.size(), from) == 0) {
        out += to;
        i += from.size();
        matched = true;
        break;
      }
    }
    if (matched) continue;
    // An unknown multi-byte character becomes '?', skipping its continuation bytes.
    out += '?';
    ++i;
    while (i < utf8.size() && (static_cast<unsigned char>(utf8[i]) & 0xC0) == 0x80) ++i;
  }
  return out;
}

RichText plain(const std::string& text) {
  return {{text, false}};
}

cv::Size text_extent(const RichText& text, const TextStyle& style) {
  return layout(text, style).size;
}

void draw_text(cv::Mat& image, const RichText& text, cv::Point2d anchor, HAlign h, VAlign v,
               const TextStyle& style, bool vertical) {
  const Layout l = layout(text, style);
  if (l.size.width <= 0 || l.size.height <= 0) return;
  // Coverage mask of the text, then blended in: lets rotated text share the horizontal code path.
  cv::Mat mask = cv::Mat::zeros(l.size.height + l.extra, l.size.width, CV_8UC1);
  if (auto* f = truetype()) {
    // FreeType2 draws into three channels; the coverage is any one of them.
    cv::Mat colour_mask = cv::Mat::zeros(mask.size(), CV_8UC3);
    for (const Placed& p : l.runs) {
      const int height = static_cast<int>(std::lround(em_per_scale * p.scale));
      f->putText(colour_mask, p.text,
                 cv::Point(p.x, p.baseline - baseline_below_origin(*f, height)), height,
                 cv::Scalar(255, 255, 255), -1, cv::LINE_AA, false);
    }
    cv::extractChannel(colour_mask, mask, 0);
  } else {
    for (const Placed& p : l.runs)
      cv::putText(mask, p.text, cv::Point(p.x, p.baseline), font, p.scale, cv::Scalar(255),
                  style.thickness, cv::LINE_AA);
  }
  // Align the nominal box; the extra rows above it (left of it once rotated) overhang the anchor.
  if (vertical) cv::rotate(mask, mask, cv::ROTATE_90_COUNTERCLOCKWISE);
  const double w = vertical ? l.size.height : l.size.width,
               hgt = vertical ? l.size.width : l.size.height;
  const double x0 = h == HAlign::left     ? anchor.x
                    : h == HAlign::centre ? anchor.x - w / 2
                                          : anchor.x - w;
  const double y0 = v == VAlign::top      ? anchor.y
                    : v == VAlign::centre ? anchor.y - hgt / 2
                                          : anchor.y - hgt;
  const int ox = static_cast<int>(std::lround(x0)) - (vertical ? l.extra : 0);
  const int oy = static_cast<int>(std::lround(y0)) - (vertical ? 0 : l.extra);
  const cv::Vec3d colour(style.colour.b, style.colour.g, style.colour.r);
  for (int r = 0; r < mask.rows; ++r) {
    const int y = oy + r;
    if (y < 0 || y >= image.rows) continue;
    for (int c = 0; c < mask.cols; ++c) {
      const int x = ox + c;
      if (x < 0 || x >= image.cols) continue;
      const double a = mask.at<std::uint8_t>(r, c) / 255.0;
      if (a <= 0.0) continue;
      cv::Vec3b& px = image.at<cv::Vec3b>(y, x);
      for (int k = 0; k < 3; ++k)
        px[k] = static_cast<std::uint8_t>(std::lround(px[k] * (1.0 - a) + colour[k] * a));
    }
  }
}

double figure_scale(int width, int height) {
  return std::max(0.35, std::min(width / 1200.0, height / 900.0));
}

FigureStyle figure_style(int width, int height) {
  FigureStyle f;
  const double s = figure_scale(width, height);
  f.scale = s;
  f.pad = 12.0 * s;
  f.tick_length = 9.0 * s;
  f.axis_width = std::max(1, static_cast<int>(std::lround(1.6 * s)));
  const int thin = std::max(1, static_cast<int>(std::lround(1.4 * s)));
  const int bold = std::max(1, static_cast<int>(std::lround(2.0 * s)));
  f.tick_font = TextStyle{0.66 * s, thin, Rgb{20, 20, 20}};
  f.label_font = TextStyle{0.8 * s, thin, Rgb{0, 0, 0}};
  f.title_font = TextStyle{0.95 * s, bold, Rgb{0, 0, 0}};
  return f;
}

}  // namespace fragmpm::analysis::detail

namespace fragmpm::analysis {

cv::Size label_extent(const std::string& utf8, double scale) {
  return detail::text_extent(detail::plain(utf8), detail::TextStyle{scale, 1, Rgb{}});
}

void draw_label(cv::Mat& image, const std::string& utf8, cv::Point top_left, double scale,
                Rgb colour) {
  detail::draw_text(image, detail::plain(utf8), cv::Point2d(top_left.x, top_left.y),
                    detail::HAlign::left, detail::VAlign::top, detail::TextStyle{scale, 1, colour});
}

}  // namespace fragmpm::analysis
