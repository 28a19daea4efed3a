// Colour maps (see colour_map.hpp).
#include "fragmpm/analysis/colour_map.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace fragmpm::analysis {

namespace {

/// Ten qualitative colours of well-separated hue (blue, orange, green, red, purple, brown, pink,
/// navy, olive, cyan). No grey: grey is `no_data_colour()`, the colour of "none" (e.g. masked
/// particles and fines in a fragment figure), which no id may share.
constexpr std::array<Rgb, 10> qualitative{{{31, 119, 180},
                                           {255, 127, 14},
                                           {44, 160, 44},
                                           {214, 39, 40},
                                           {148, 103, 189},
                                           {140, 86, 75},
                                           {227, 119, 194},
                                           {40, 40, 120},
                                           {188, 189, 34},
                                           {23, 190, 207}}};

const std::array<Rgb, 256>& viridis_table() {
  static const std::array<Rgb, 256> table = [] {
    cv::Mat ramp(1, 256, CV_8UC1), coloured;
    for (int i = 0; i < 256; ++i) ramp.at<std::uint8_t>(0, i) = static_cast<std::uint8_t>(i);
    cv::applyColorMap(ramp, coloured, cv::COLORMAP_VIRIDIS);
    std::array<Rgb, 256> t{};
    for (int i = 0; i < 256; ++i) {
      const cv::Vec3b bgr = coloured.at<cv::Vec3b>(0, i);
      t[static_cast<std::size_t>(i)] = Rgb{bgr[2], bgr[1], bgr[0]};
    }
    return t;
  }();
  return table;
}

Rgb from_hsv(double hue_deg, double s, double v) {
  const double c = v * s, h = hue_deg / 60.0;
  const double x = c * (1.0 - std::abs(std::fmod(h, 2.0) - 1.0));
  double r = 0, g = 0, b = 0;
  if (h < 1)
    r = c, g = x;
  else if (h < 2)
    r = x, g = c;
  else if (h < 3)
    g = c, b = x;
  else if (h < 4)
    g = x, b = c;
  else if (h < 5)
    r = x, b = c;
  else
    r = c, b = x;
  const double m = v - c;
  auto byte = [m](double u) { return static_cast<std::uint8_t>(std::lround(255.0 * (u + m))); };
  return Rgb{byte(r), byte(g), byte(b)};
}

}  // namespace

Rgb no_data_colour() {
  return Rgb{160, 160, 160};
}

Rgb viridis(double t) {
  if (std::isnan(t)) return no_data_colour();
  const double u = std::clamp(t, 0.0, 1.0);
  return viridis_table()[static_cast<std::size_t>(std::lround(255.0 * u))];
}

Rgb categorical_colour(std::int64_t id) {
  if (id < 0) return no_data_colour();
  if (id < static_cast<std::int64_t>(qualitative.size()))
    return qualitative[static_cast<std::size_t>(id)];
  // Golden-angle hue steps: any two ids close in number are far apart in hue.
  const double golden_angle = 137.50776405003785;
  const double hue = std::fmod(static_cast<double>(id) * golden_angle, 360.0);
  const double s = (id % 2 == 0) ? 0.75 : 0.55;
  const double v = (id % 3 == 0) ? 0.70 : 0.92;
  return from_hsv(hue, s, v);
}

Rgb series_colour(std::size_t index) {
  return qualitative[index % qualitative.size()];
}

}  // namespace fragmpm::analysis
