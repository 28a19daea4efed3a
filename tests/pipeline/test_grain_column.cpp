// Grains stacked into a column and scaled to a total area (grain_column.hpp), as the three-grain
// scene's grain file is made, and `fragmpm segment --stack` from the command line.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <stdexcept>

#include "fragmpm/pipeline/grain_column.hpp"
#include "fragmpm/pipeline/segment_file.hpp"

namespace fp = fragmpm::pipeline;
namespace fs = std::filesystem;

namespace {

/// A label image with a 10 × 6 box (label 1), a disk of radius 8 (label 2) and an L of two bars
/// (label 3), apart from each other.
cv::Mat three_shapes() {
  cv::Mat labels = cv::Mat::zeros(60, 80, CV_32SC1);
  cv::rectangle(labels, cv::Rect(2, 2, 10, 6), cv::Scalar(1), cv::FILLED);
  cv::circle(labels, cv::Point(40, 20), 8, cv::Scalar(2), cv::FILLED);
  cv::rectangle(labels, cv::Rect(10, 30, 4, 20), cv::Scalar(3), cv::FILLED);
  cv::rectangle(labels, cv::Rect(10, 46, 16, 4), cv::Scalar(3), cv::FILLED);
  return labels;
}

int pixels_of(const cv::Mat& labels, int value) {
  return cv::countNonZero(labels == value);
}

}  // namespace

TEST(GrainColumn, KeepsEveryGrainAndScalesToTheTotalArea) {
  const cv::Mat labels = three_shapes();
  const double area = 94e-6;  // [m²]
  const fp::GrainColumn c = fp::stack_grains(labels, {2, 1, 3}, area, 3);
  ASSERT_EQ(c.labels.type(), CV_16UC1);
  // Each grain keeps its pixels; the k-th chosen one has value k + 1.
  EXPECT_EQ(pixels_of(c.labels, 1), pixels_of(labels, 2));
  EXPECT_EQ(pixels_of(c.labels, 2), pixels_of(labels, 1));
  EXPECT_EQ(pixels_of(c.labels, 3), pixels_of(labels, 3));
  EXPECT_EQ(c.grain_pixels, pixels_of(labels, 1) + pixels_of(labels, 2) + pixels_of(labels, 3));
  // The pixel size gives the requested total area.
  EXPECT_NEAR(static_cast<double>(c.grain_pixels) * c.pixel_size * c.pixel_size, area,
              1e-12 * area);
  // A margin of background all round.
  const cv::Rect box = cv::boundingRect(c.labels > 0);
  EXPECT_EQ(box.x, 3);
  EXPECT_EQ(box.y, 3);
  EXPECT_EQ(c.labels.cols - box.x - box.width, 3);
  EXPECT_EQ(c.labels.rows - box.y - box.height, 3);
}

TEST(GrainColumn, StacksBottomFirstTouchingAndCentred) {
  const fp::GrainColumn c = fp::stack_grains(three_shapes(), {2, 1, 3}, 1e-6, 0);
  auto centre = [&](int value) {
    const cv::Moments m = cv::moments(c.labels == value, true);
    return cv::Point2d(m.m10 / m.m00, m.m01 / m.m00);
  };
  // Rows run down: the first grain is lowest (largest row), the last highest.
  EXPECT_GT(centre(1).y, centre(2).y);
  EXPECT_GT(centre(2).y, centre(3).y);
  // Centroids on one vertical axis (to the rounding of a pixel).
  EXPECT_NEAR(centre(1).x, centre(2).x, 1.0);
  EXPECT_NEAR(centre(1).x, centre(3).x, 1.0);
  // Neighbours touch: some pixel of the upper grain sits right above one of the lower grain, and
  // no row gap separates them.
  for (int lower = 1; lower <= 2; ++lower) {
    int contacts = 0;
    for (int r = 1; r < c.labels.rows; ++r)
      for (int col = 0; col < c.labels.cols; ++col)
        if (c.labels.at<std::uint16_t>(r, col) == lower &&
            c.labels.at<std::uint16_t>(r - 1, col) == lower + 1)
          ++contacts;
    EXPECT_GT(contacts, 0) << "grain " << lower + 1 << " does not rest on grain " << lower;
  }
  // The box (6 rows) sits on the disk (17 rows) and the L (20 rows) on the box: no gaps, so the
  // column is at most their heights added.
  EXPECT_LE(c.labels.rows, 17 + 6 + 20);
}

TEST(GrainColumn, RefusesBadChoices) {
  const cv::Mat labels = three_shapes();
  EXPECT_THROW(fp::stack_grains(labels, {}, 1e-6, 0), std::invalid_argument);
  EXPECT_THROW(fp::stack_grains(labels, {1, 1}, 1e-6, 0), std::invalid_argument);
  EXPECT_THROW(fp::stack_grains(labels, {4}, 1e-6, 0), std::invalid_argument);
  EXPECT_THROW(fp::stack_grains(labels, {1}, 0.0, 0), std::invalid_argument);
  EXPECT_THROW(fp::stack_grains(labels, {1}, 1e-6, -1), std::invalid_argument);
  cv::Mat bytes;
  labels.convertTo(bytes, CV_8U);
  EXPECT_THROW(fp::stack_grains(bytes, {1}, 1e-6, 0), std::invalid_argument);
}

namespace {

fs::path test_dir() {
  const fs::path p = fs::temp_directory_path() / "fragmpm_test_grain_column" /
                     ::testing::UnitTest::GetInstance()->current_test_info()->name();
  fs::create_directories(p);
  return p;
}

/// Runs `fragmpm segment ARGUMENTS`; exit code and output.
std::pair<int, std::string> segment(const std::string& arguments) {
  const fs::path log = test_dir() / "log.txt";
  const std::string command =
      std::string(FRAGMPM_BINARY) + " segment " + arguments + " > " + log.string() + " 2>&1";
  const int status = std::system(command.c_str());
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text.str()};
}

}  // namespace

TEST(GrainColumn, SegmentCommandWritesTheStackedColumn) {
  cv::Mat labels;
  three_shapes().convertTo(labels, CV_16U);
  const std::string png = (test_dir() / "shapes.png").string();
  cv::imwrite(png, labels);
  const std::string out = (test_dir() / "column.h5").string();
  const auto [code, log] = segment(png +
                                   " --pixel-size 1um --input labels --no-split --stack 2,1,3"
                                   " --stack-area 94mm2 --overwrite -o " +
                                   out);
  ASSERT_EQ(code, 0) << log;
  const fp::GrainFile file = fp::read_grain_file(out);
  ASSERT_EQ(file.grains.size(), 3u);
  double area = 0.0;
  for (const auto& g : file.grains) area += g.shape.area;
  EXPECT_NEAR(area, 94e-6, 1e-9 * 94e-6);

  EXPECT_EQ(segment(png +
                    " --pixel-size 1um --input labels --stack 2,9 --stack-area 94mm2"
                    " --overwrite -o " +
                    out)
                .first,
            2);
  EXPECT_EQ(
      segment(png + " --pixel-size 1um --input labels --stack 2,1 --overwrite -o " + out).first, 2);
  const auto [bad_unit, message] = segment(
      png + " --pixel-size 1um --input labels --stack 2,1 --stack-area 94mm --overwrite -o " + out);
  EXPECT_EQ(bad_unit, 2);
  EXPECT_NE(message.find("--stack-area"), std::string::npos) << message;
}
