// `fragmpm segment` from the command line: a good run, and every kind of bad input exits with 2
// and a message that says what is wrong.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <string>

#include "fragmpm/pipeline/segment_file.hpp"
#include "fragmpm/pipeline/segment_synthetic.hpp"

namespace fp = fragmpm::pipeline;
namespace fs = std::filesystem;

namespace {

struct Outcome {
  int code = -1;
  std::string output;
};

// One directory per test: ctest runs the tests of this file in parallel processes, which must not
// share log or output files.
fs::path dir() {
  const fs::path p = fs::temp_directory_path() / "fragmpm_test_segment_cli" /
                     ::testing::UnitTest::GetInstance()->current_test_info()->name();
  fs::create_directories(p);
  return p;
}

Outcome run(const std::string& arguments) {
  const fs::path log = dir() / "log.txt";
  const std::string command =
      std::string(FRAGMPM_BINARY) + " segment " + arguments + " > " + log.string() + " 2>&1";
  const int status = std::system(command.c_str());
  Outcome o;
  o.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  o.output = text.str();
  return o;
}

std::string disks_png() {
  const fs::path p = dir() / "disks.png";
  if (!fs::exists(p)) cv::imwrite(p.string(), fp::synthetic_disks().image);
  return p.string();
}

void expect_bad_input(const std::string& arguments, const std::string& expected_text) {
  const Outcome o = run(arguments);
  EXPECT_EQ(o.code, 2) << arguments << "\n" << o.output;
  EXPECT_NE(o.output.find(expected_text), std::string::npos)
      << arguments << "\nexpected '" << expected_text << "' in:\n"
      << o.output;
}

}  // namespace

TEST(SegmentCli, SegmentsAnImageAndWritesGrainFileAndPreview) {
  const std::string out = (dir() / "disks.h5").string(),
                    preview = (dir() / "disks_preview.png").string();
  const Outcome o = run(disks_png() + " --pixel-size 2um -o " + out + " --preview " + preview +
                        " --cell-size 8um --overwrite");
  ASSERT_EQ(o.code, 0) << o.output;
  EXPECT_NE(o.output.find("12 grains"), std::string::npos) << o.output;
  const fp::GrainFile g = fp::read_grain_file(out);
  EXPECT_EQ(g.grains.size(), 12u);
  EXPECT_DOUBLE_EQ(g.pixel_size, 2e-6);
  EXPECT_DOUBLE_EQ(g.sampling.cell_size, 8e-6);
  const cv::Mat p = cv::imread(preview);
  EXPECT_EQ(p.cols, 640);
  EXPECT_GT(p.rows, 480);  // image plus caption strip
  // The existing grain file is not replaced without --overwrite.
  expect_bad_input(disks_png() + " --pixel-size 2um -o " + out, "exists");
}

TEST(SegmentCli, MissingUnreadableAndCorruptFiles) {
  const std::string out = " -o " + (dir() / "bad.h5").string() + " --overwrite";
  expect_bad_input((dir() / "no_such_image.png").string() + " --pixel-size 1um" + out,
                   "no such file");
  const fs::path empty = dir() / "empty.png";
  std::ofstream(empty).close();
  expect_bad_input(empty.string() + " --pixel-size 1um" + out, "empty");
  const fs::path text = dir() / "text.png";
  std::ofstream(text) << "this is not an image\n";
  expect_bad_input(text.string() + " --pixel-size 1um" + out, "cannot read the image");
  // A PNG cut in half.
  const std::string whole = disks_png();
  const fs::path cut = dir() / "truncated.png";
  {
    std::ifstream in(whole, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  }
  expect_bad_input(cut.string() + " --pixel-size 1um" + out, "cannot read the image");
  expect_bad_input(dir().string() + " --pixel-size 1um" + out, "not a regular file");
}

TEST(SegmentCli, DegenerateImages) {
  const std::string out = " -o " + (dir() / "bad.h5").string() + " --overwrite";
  const fs::path one = dir() / "one_pixel.png";
  cv::imwrite(one.string(), cv::Mat(1, 1, CV_8U, cv::Scalar(200)));
  expect_bad_input(one.string() + " --pixel-size 1um" + out, "at least 2 × 2");
  const fs::path line = dir() / "one_row.png";
  cv::imwrite(line.string(), cv::Mat(1, 50, CV_8U, cv::Scalar(200)));
  expect_bad_input(line.string() + " --pixel-size 1um" + out, "at least 2 × 2");
  const fs::path flat = dir() / "uniform.png";
  cv::imwrite(flat.string(), cv::Mat(40, 40, CV_8U, cv::Scalar(90)));
  expect_bad_input(flat.string() + " --pixel-size 1um" + out, "same grey level");
  // All background / all foreground at the chosen threshold.
  expect_bad_input(disks_png() + " --pixel-size 1um --level 250" + out, "no grain pixels");
  expect_bad_input(disks_png() + " --pixel-size 1um --level 10" + out, "every pixel is grain");
}

TEST(SegmentCli, BadOptions) {
  const std::string out = " -o " + (dir() / "bad.h5").string() + " --overwrite";
  expect_bad_input(disks_png() + " --pixel-size 0um" + out,
                   "--pixel-size must be a positive length");
  expect_bad_input(disks_png() + " --pixel-size -1um" + out,
                   "--pixel-size must be a positive length");
  expect_bad_input(disks_png() + " --pixel-size 3kg" + out, "--pixel-size '3kg'");
  expect_bad_input(disks_png() + out, "pixel-size");  // required
  expect_bad_input(disks_png() + " --pixel-size 1um --crop 600,400,100,100" + out,
                   "not inside the image");
  expect_bad_input(disks_png() + " --pixel-size 1um --crop -5,0,100,100" + out,
                   "not inside the image");
  expect_bad_input(disks_png() + " --pixel-size 1um --crop 10,10,100" + out, "four integers");
  expect_bad_input(disks_png() + " --pixel-size 1um --crop 10,10,0,5" + out, "at least 2 × 2");
  expect_bad_input(disks_png() + " --pixel-size 1um --threshold fixed" + out, "needs --level");
  expect_bad_input(disks_png() + " --pixel-size 1um --threshold adaptive --block 40" + out, "odd");
  expect_bad_input(disks_png() + " --pixel-size 1um --neck-ratio 1.5" + out, "--neck-ratio");
  expect_bad_input(disks_png() + " --pixel-size 1um --phase-bands 200,100" + out, "ascending");
  expect_bad_input(
      disks_png() + " --pixel-size 1um --phase-bands 100 --density 2650,2700,2800" + out,
      "--density");
  expect_bad_input(disks_png() + " --pixel-size 1um --cell-size 0um" + out, "--cell-size");
  expect_bad_input(disks_png() + " --pixel-size 1um --min-area 100000" + out, "no grains left");
  expect_bad_input(disks_png() + " --pixel-size 1um --input pebbles" + out, "pebbles");
}
