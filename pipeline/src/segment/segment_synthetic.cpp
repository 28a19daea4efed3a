#include "fragmpm/pipeline/segment_synthetic.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <numbers>
#include <opencv2/core.hpp>
#include <random>

namespace fragmpm::pipeline {

namespace {

constexpr int kWidth = 640;
constexpr int kHeight = 480;

/// A grain given by an inside test; pixels whose centre is inside are painted (first grain wins).
struct Shape {
  std::function<bool(double x, double y)> inside;
  cv::Rect bounds;
};

SyntheticImage render(const std::string& name, const std::vector<Shape>& shapes,
                      std::vector<SyntheticGrain> grains, const std::vector<int>& grey,
                      int background) {
  SyntheticImage s;
  s.name = name;
  s.image = cv::Mat(kHeight, kWidth, CV_8U, cv::Scalar(background));
  s.truth = cv::Mat::zeros(kHeight, kWidth, CV_32S);
  const cv::Rect all(0, 0, kWidth, kHeight);
  for (std::size_t k = 0; k < shapes.size(); ++k) {
    const cv::Rect b = shapes[k].bounds & all;
    for (int r = b.y; r < b.y + b.height; ++r)
      for (int c = b.x; c < b.x + b.width; ++c)
        if (s.truth.at<std::int32_t>(r, c) == 0 && shapes[k].inside(c + 0.5, r + 0.5)) {
          s.truth.at<std::int32_t>(r, c) = static_cast<std::int32_t>(k) + 1;
          s.image.at<unsigned char>(r, c) = static_cast<unsigned char>(grey[k]);
        }
  }
  s.grains = std::move(grains);
  return s;
}

Shape disk(double cx, double cy, double r) {
  return {[=](double x, double y) { return (x - cx) * (x - cx) + (y - cy) * (y - cy) < r * r; },
          cv::Rect(static_cast<int>(cx - r) - 1, static_cast<int>(cy - r) - 1,
                   static_cast<int>(2 * r) + 3, static_cast<int>(2 * r) + 3)};
}

/// Area of the part of a disk of radius r beyond a chord at distance x from its centre.
double segment_area(double r, double x) {
  return r * r * std::acos(x / r) - x * std::sqrt(r * r - x * x);
}

}  // namespace

SyntheticImage synthetic_disks() {
  const std::array<double, 12> radii{10, 13, 16, 19, 22, 25, 28, 31, 34, 37, 40, 42};
  std::vector<Shape> shapes;
  std::vector<SyntheticGrain> grains;
  for (int k = 0; k < 12; ++k) {
    const double cx = 80.0 + 160.0 * (k % 4), cy = 80.0 + 160.0 * (k / 4);
    const double r = radii[static_cast<std::size_t>(k)];
    shapes.push_back(disk(cx, cy, r));
    grains.push_back({cx, cy, std::numbers::pi * r * r, 0});
  }
  return render("disks", shapes, grains, std::vector<int>(12, kSyntheticGrain),
                kSyntheticBackground);
}

SyntheticImage synthetic_irregular(std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> amp(-0.08, 0.08), phase(0.0, 2.0 * std::numbers::pi),
      jitter(-10.0, 10.0), radius(22.0, 45.0);
  std::vector<Shape> shapes;
  std::vector<SyntheticGrain> grains;
  for (int k = 0; k < 12; ++k) {
    const double cx = 80.0 + 160.0 * (k % 4) + jitter(rng),
                 cy = 80.0 + 160.0 * (k / 4) + jitter(rng);
    const double r0 = radius(rng);
    std::array<double, 3> a{}, phi{};
    double sum_sq = 0.0;
    for (std::size_t m = 0; m < 3; ++m) {
      a[m] = amp(rng);
      phi[m] = phase(rng);
      sum_sq += a[m] * a[m];
    }
    auto rho = [=](double theta) {
      double f = 1.0;
      for (std::size_t m = 0; m < 3; ++m)
        f += a[m] * std::cos(static_cast<double>(m + 2) * theta + phi[m]);
      return r0 * f;
    };
    const double rmax = r0 * 1.25;
    shapes.push_back({[=](double x, double y) {
                        const double dx = x - cx, dy = y - cy;
                        return std::hypot(dx, dy) < rho(std::atan2(dy, dx));
                      },
                      cv::Rect(static_cast<int>(cx - rmax) - 1, static_cast<int>(cy - rmax) - 1,
                               static_cast<int>(2 * rmax) + 3, static_cast<int>(2 * rmax) + 3)});
    // ½ ∫ r² dθ with the cross terms of distinct harmonics integrating to zero.
    grains.push_back({cx, cy, std::numbers::pi * r0 * r0 * (1.0 + 0.5 * sum_sq), 0});
  }
  return render("irregular", shapes, grains, std::vector<int>(12, kSyntheticGrain),
                kSyntheticBackground);
}

SyntheticImage synthetic_touching_pairs() {
  // (r1, r2, centre distance as a fraction of r1 + r2)
  const std::array<std::array<double, 3>, 6> pairs{{{30, 30, 0.90},
                                                    {25, 25, 0.85},
                                                    {32, 22, 0.93},
                                                    {35, 20, 0.95},
                                                    {28, 24, 0.90},
                                                    {22, 22, 0.88}}};
  std::vector<Shape> shapes;
  std::vector<SyntheticGrain> grains;
  for (int k = 0; k < 6; ++k) {
    const auto [r1, r2, f] = pairs[static_cast<std::size_t>(k)];
    const double d = f * (r1 + r2);
    const double cx = 107.0 + 213.0 * (k % 3), cy = 120.0 + 240.0 * (k / 3);
    // Along a diagonal so the split is not axis-aligned.
    const double ux = std::cos(0.6 + k), uy = std::sin(0.6 + k);
    const double x1 = cx - 0.5 * d * ux, y1 = cy - 0.5 * d * uy;
    const double x2 = cx + 0.5 * d * ux, y2 = cy + 0.5 * d * uy;
    // Split along the radical axis: a point belongs to the disk of smaller power |p − c|² − r².
    auto power1 = [=](double x, double y) {
      return (x - x1) * (x - x1) + (y - y1) * (y - y1) - r1 * r1;
    };
    auto power2 = [=](double x, double y) {
      return (x - x2) * (x - x2) + (y - y2) * (y - y2) - r2 * r2;
    };
    Shape s1 = disk(x1, y1, r1), s2 = disk(x2, y2, r2);
    shapes.push_back(
        {[=](double x, double y) { return power1(x, y) < 0.0 && power1(x, y) <= power2(x, y); },
         s1.bounds});
    shapes.push_back(
        {[=](double x, double y) { return power2(x, y) < 0.0 && power2(x, y) < power1(x, y); },
         s2.bounds});
    const double a1 = (d * d + r1 * r1 - r2 * r2) / (2.0 * d);  // chord distance from centre 1
    const double a2 = d - a1;
    grains.push_back({x1, y1, std::numbers::pi * r1 * r1 - segment_area(r1, a1), 0});
    grains.push_back({x2, y2, std::numbers::pi * r2 * r2 - segment_area(r2, a2), 0});
  }
  return render("touching_pairs", shapes, grains, std::vector<int>(12, kSyntheticGrain),
                kSyntheticBackground);
}

SyntheticImage synthetic_border_disks() {
  // Inside: six disks; cut: five disks whose centres lie near or beyond an edge.
  const std::array<std::array<double, 3>, 11> disks{{{140, 130, 30},
                                                     {320, 120, 26},
                                                     {500, 140, 32},
                                                     {150, 340, 28},
                                                     {330, 350, 34},
                                                     {490, 330, 24},
                                                     {10, 240, 30},
                                                     {320, -8, 25},
                                                     {632, 60, 22},
                                                     {250, 478, 27},
                                                     {636, 470, 30}}};
  std::vector<Shape> shapes;
  std::vector<SyntheticGrain> grains;
  for (const auto& [cx, cy, r] : disks) {
    shapes.push_back(disk(cx, cy, r));
    grains.push_back({cx, cy, std::numbers::pi * r * r, 0});
  }
  SyntheticImage s = render("border_disks", shapes, grains, std::vector<int>(11, kSyntheticGrain),
                            kSyntheticBackground);
  for (std::size_t k = 6; k < s.grains.size(); ++k)  // cut disks: the pixels that are in the image
    s.grains[k].area = cv::countNonZero(s.truth == static_cast<int>(k) + 1);
  return s;
}

SyntheticImage synthetic_two_phase() {
  std::vector<Shape> shapes;
  std::vector<SyntheticGrain> grains;
  std::vector<int> grey;
  for (int k = 0; k < 12; ++k) {
    const double cx = 80.0 + 160.0 * (k % 4), cy = 80.0 + 160.0 * (k / 4);
    const double r = 25.0 + 1.5 * k;
    shapes.push_back(disk(cx, cy, r));
    grains.push_back({cx, cy, std::numbers::pi * r * r, k % 2});
    grey.push_back(k % 2 ? 230 : 120);
  }
  return render("two_phase", shapes, grains, grey, 30);
}

void add_gaussian_noise(cv::Mat& image, double sigma, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  const double top = image.depth() == CV_16U ? 65535.0 : 255.0;
  for (int r = 0; r < image.rows; ++r)
    for (int c = 0; c < image.cols; ++c) {
      if (image.depth() == CV_16U) {
        auto& v = image.at<std::uint16_t>(r, c);
        v = static_cast<std::uint16_t>(
            std::clamp(std::lround(v + noise(rng)), 0L, static_cast<long>(top)));
      } else {
        auto& v = image.at<unsigned char>(r, c);
        v = static_cast<unsigned char>(
            std::clamp(std::lround(v + noise(rng)), 0L, static_cast<long>(top)));
      }
    }
}

cv::Mat to_16bit(const cv::Mat& image8, double gain, double offset) {
  cv::Mat out;
  image8.convertTo(out, CV_16U, gain, offset);
  return out;
}

}  // namespace fragmpm::pipeline
