// Shape measures shared by grains and fragments (docs/design.md): closed forms for rectangles,
// disks and ellipses, and the invariance that makes pixels and particle domains interchangeable.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <opencv2/core.hpp>
#include <vector>

#include "fragmpm/analysis/region_shape.hpp"

namespace fa = fragmpm::analysis;
using std::numbers::pi;

namespace {

/// Label image with the pixels whose centres (in the y-up physical frame, pixel size 1) satisfy
/// `inside` set to `label`.
template <class Inside>
void paint(cv::Mat& labels, int label, Inside inside) {
  for (int r = 0; r < labels.rows; ++r)
    for (int c = 0; c < labels.cols; ++c)
      if (inside(c + 0.5, labels.rows - r - 0.5)) labels.at<int>(r, c) = label;
}

}  // namespace

TEST(RegionShape, RectangleOfPixelsHasExactMoments) {
  // a × b pixels: the pixel variances (n² − 1)/12 plus ImageJ's 1/12 give exactly a²/12, b²/12.
  const int a = 40, b = 10;
  const double s = 2e-6;
  cv::Mat labels = cv::Mat::zeros(50, 60, CV_32S);
  labels(cv::Rect(7, 20, a, b)).setTo(3);
  const auto regions = fa::label_region_shapes(labels, s);
  ASSERT_EQ(regions.size(), 1u);
  const fa::LabelRegion& r = regions[0];
  EXPECT_EQ(r.label, 3);
  EXPECT_EQ(r.pixels, a * b);
  EXPECT_EQ(r.bbox, cv::Rect(7, 20, a, b));
  EXPECT_FALSE(r.touches_border);
  EXPECT_DOUBLE_EQ(r.centroid_col, 7 + a / 2.0);
  EXPECT_DOUBLE_EQ(r.centroid_row, 20 + b / 2.0);
  const fa::RegionShape& sh = r.shape;
  EXPECT_NEAR(sh.area / (a * b * s * s), 1.0, 1e-12);
  EXPECT_NEAR(sh.equivalent_diameter, std::sqrt(4.0 * a * b / pi) * s, 1e-18);
  EXPECT_NEAR(sh.centroid_x, (7 + a / 2.0) * s, 1e-18);
  EXPECT_NEAR(sh.centroid_y, (50 - 20 - b / 2.0) * s, 1e-18);
  EXPECT_NEAR(sh.roundness, double(b) / a, 1e-12);
  EXPECT_NEAR(sh.aspect_ratio, double(a) / b, 1e-10);
  EXPECT_NEAR(sh.orientation, 0.0, 1e-12);
  // Ellipse rescaled to the area: π M m / 4 = A with m/M = b/a, so M = 2a/√π.
  EXPECT_NEAR(sh.major_axis, 2.0 * a / std::sqrt(pi) * s, 1e-15);
  EXPECT_NEAR(pi * sh.major_axis * sh.minor_axis / 4.0, sh.area, 1e-22);
  // Crofton: n0 = 2b, n90 = 2a, n45 = n135 = 2(a + b − 1).
  const double crofton = pi / 8.0 * (2.0 * (a + b) + 4.0 * (a + b - 1) / std::numbers::sqrt2) * s;
  EXPECT_NEAR(sh.perimeter, crofton, 1e-15);
}

TEST(RegionShape, DiskIsRoundWithCroftonPerimeter) {
  const double R = 60.0;
  cv::Mat labels = cv::Mat::zeros(160, 160, CV_32S);
  paint(labels, 1, [&](double x, double y) { return std::hypot(x - 80.3, y - 79.6) < R; });
  const fa::RegionShape sh = fa::label_region_shapes(labels, 1.0)[0].shape;
  EXPECT_NEAR(sh.area / (pi * R * R), 1.0, 0.002);
  EXPECT_NEAR(sh.equivalent_diameter / (2 * R), 1.0, 0.001);
  EXPECT_GT(sh.roundness, 0.995);
  EXPECT_NEAR(sh.perimeter / (2 * pi * R), 1.0, 0.01);
  EXPECT_NEAR(sh.centroid_x, 80.3, 0.05);  // pixelation of the outline moves it a little
  EXPECT_NEAR(sh.centroid_y, 79.6, 0.05);
}

TEST(RegionShape, RotatedEllipseGivesAxisRatioAndAngle) {
  const double A = 70.0, B = 28.0, angle = pi / 6.0;  // 30° from +x towards +y
  cv::Mat labels = cv::Mat::zeros(200, 200, CV_32S);
  paint(labels, 1, [&](double x, double y) {
    const double dx = x - 100, dy = y - 100;
    const double u = dx * std::cos(angle) + dy * std::sin(angle),
                 v = -dx * std::sin(angle) + dy * std::cos(angle);
    return (u * u) / (A * A) + (v * v) / (B * B) < 1.0;
  });
  const fa::RegionShape sh = fa::label_region_shapes(labels, 1.0)[0].shape;
  EXPECT_NEAR(sh.area / (pi * A * B), 1.0, 0.003);
  EXPECT_NEAR(sh.roundness, B / A, 0.005);
  EXPECT_NEAR(sh.aspect_ratio, A / B, 0.03);
  EXPECT_NEAR(sh.orientation, angle, 0.005);
  EXPECT_NEAR(sh.major_axis / (2 * A), 1.0, 0.005);
  EXPECT_NEAR(sh.minor_axis / (2 * B), 1.0, 0.005);
  // Ramanujan's perimeter of the ellipse.
  const double h = (A - B) * (A - B) / ((A + B) * (A + B));
  const double ramanujan = pi * (A + B) * (1 + 3 * h / (10 + std::sqrt(4 - 3 * h)));
  EXPECT_NEAR(sh.perimeter / ramanujan, 1.0, 0.02);
}

TEST(RegionShape, LatticeOfParticleDomainsEqualsOneRectangle) {
  // 10 × 5 square domains of side h: own moments h²/12 plus the spread give the moments of the
  // 10h × 5h rectangle exactly, as for pixels.
  const double h = 1e-4;
  std::vector<fa::ShapeCell> cells;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 5; ++j)
      cells.push_back(
          fa::parallelogram_cell((i + 0.5) * h + 3.0, (j + 0.5) * h - 1.0, h, 0.0, 0.0, h));
  const fa::RegionShape sh = fa::region_shape(cells);
  EXPECT_NEAR(sh.area, 50 * h * h, 1e-20);
  EXPECT_NEAR(sh.roundness, 0.5, 1e-9);
  EXPECT_NEAR(sh.aspect_ratio, 2.0, 1e-8);
  EXPECT_NEAR(sh.centroid_x, 3.0 + 5 * h, 1e-12);
  EXPECT_NEAR(sh.centroid_y, -1.0 + 2.5 * h, 1e-12);
  EXPECT_TRUE(std::isnan(sh.perimeter));
  // One domain of the whole rectangle has the same shape.
  const fa::ShapeCell whole =
      fa::parallelogram_cell(3.0 + 5 * h, -1.0 + 2.5 * h, 10 * h, 0.0, 0.0, 5 * h);
  const fa::RegionShape one = fa::region_shape(std::vector<fa::ShapeCell>{whole});
  EXPECT_NEAR(one.roundness, sh.roundness, 1e-9);
  EXPECT_NEAR(one.major_axis, sh.major_axis, 1e-12);
}

TEST(RegionShape, ShearedDomainEqualsItsSubdivision) {
  // A sheared parallelogram split into 4 × 4 similar pieces has the same moments (exact algebra).
  const double r1x = 3.0, r1y = 0.5, r2x = 1.2, r2y = 2.0, cx = 10.0, cy = -4.0;
  const fa::RegionShape whole = fa::region_shape(
      std::vector<fa::ShapeCell>{fa::parallelogram_cell(cx, cy, r1x, r1y, r2x, r2y)});
  std::vector<fa::ShapeCell> pieces;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      const double s = (i + 0.5) / 4 - 0.5, t = (j + 0.5) / 4 - 0.5;
      pieces.push_back(fa::parallelogram_cell(cx + s * r1x + t * r2x, cy + s * r1y + t * r2y,
                                              r1x / 4, r1y / 4, r2x / 4, r2y / 4));
    }
  const fa::RegionShape split = fa::region_shape(pieces);
  EXPECT_NEAR(split.area, std::abs(r1x * r2y - r1y * r2x), 1e-12);
  EXPECT_NEAR(split.area, whole.area, 1e-12);
  EXPECT_NEAR(split.roundness, whole.roundness, 1e-12);
  EXPECT_NEAR(split.orientation, whole.orientation, 1e-12);
  EXPECT_NEAR(split.centroid_x, cx, 1e-12);
  EXPECT_NEAR(split.centroid_y, cy, 1e-12);
}

TEST(RegionShape, FarFromTheOriginKeepsItsDigits) {
  std::vector<fa::ShapeCell> near, far;
  for (int i = 0; i < 30; ++i)
    for (int j = 0; j < 7; ++j) {
      near.push_back(fa::pixel_cell(i + 0.5, j + 0.5, 1.0));
      far.push_back(fa::pixel_cell(1e7 + i + 0.5, -3e6 + j + 0.5, 1.0));
    }
  EXPECT_NEAR(fa::region_shape(far).roundness, fa::region_shape(near).roundness, 1e-9);
  EXPECT_NEAR(fa::region_shape(near).roundness, 7.0 / 30.0, 1e-12);
}

TEST(RegionShape, SinglePixelAndEmptyRegion) {
  const fa::RegionShape one =
      fa::region_shape(std::vector<fa::ShapeCell>{fa::pixel_cell(0.5, 0.5, 1.0)});
  EXPECT_DOUBLE_EQ(one.area, 1.0);
  EXPECT_DOUBLE_EQ(one.roundness, 1.0);
  EXPECT_DOUBLE_EQ(one.aspect_ratio, 1.0);
  const fa::RegionShape none = fa::region_shape(std::vector<fa::ShapeCell>{});
  EXPECT_DOUBLE_EQ(none.area, 0.0);
}

TEST(RegionShape, SparseLabelsBorderFlagsAndOrder) {
  cv::Mat labels = cv::Mat::zeros(20, 30, CV_32S);
  labels(cv::Rect(0, 5, 4, 4)).setTo(1000000);  // touches the left border
  labels(cv::Rect(10, 5, 3, 2)).setTo(5);
  labels(cv::Rect(20, 16, 2, 4)).setTo(7);  // touches the bottom border
  const auto regions = fa::label_region_shapes(labels, 1.0);
  ASSERT_EQ(regions.size(), 3u);
  EXPECT_EQ(regions[0].label, 5);
  EXPECT_EQ(regions[1].label, 7);
  EXPECT_EQ(regions[2].label, 1000000);
  EXPECT_FALSE(regions[0].touches_border);
  EXPECT_TRUE(regions[1].touches_border);
  EXPECT_TRUE(regions[2].touches_border);
  EXPECT_EQ(regions[0].pixels, 6);
  EXPECT_EQ(regions[2].pixels, 16);
}

TEST(RegionShape, RejectsWrongLabelType) {
  cv::Mat wrong = cv::Mat::zeros(4, 4, CV_8U);
  EXPECT_THROW(fa::label_region_shapes(wrong, 1.0), std::invalid_argument);
  cv::Mat labels = cv::Mat::zeros(4, 4, CV_32S);
  EXPECT_THROW(fa::label_region_shapes(labels, 0.0), std::invalid_argument);
}
