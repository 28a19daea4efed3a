// Off-screen figures (docs/design.md "Figures"): nice ticks, line plots with their axes,
// particle figures with colour-map colours at known pixels, clear errors on bad input, and
// `fragmpm render` through the binary on a small run file.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "../support/read_text.hpp"
#include "fragmpm/analysis/axis_ticks.hpp"
#include "fragmpm/analysis/colour_map.hpp"
#include "fragmpm/analysis/figure_error.hpp"
#include "fragmpm/analysis/frame_figure.hpp"
#include "fragmpm/analysis/offscreen.hpp"
#include "fragmpm/analysis/particle_figure.hpp"
#include "fragmpm/analysis/plot.hpp"
#include "fragmpm/analysis/series_figures.hpp"
#include "fragmpm/analysis/si_format.hpp"
#include "fragmpm/analysis/verify_plot.hpp"
#include "fragmpm/mpm/run_file.hpp"

namespace fs = std::filesystem;
using namespace fragmpm;
using namespace fragmpm::analysis;

using fragmpm::test_support::read_text;

namespace {

/// A fresh directory unique to this process (test runs may overlap), removed at exit.
fs::path figure_directory(const std::string& name) {
  struct Cleanup {
    std::vector<fs::path> dirs;
    ~Cleanup() {
      std::error_code ec;
      for (const fs::path& d : dirs) fs::remove_all(d, ec);
    }
  };
  static Cleanup cleanup;
  const fs::path dir =
      fs::path(::testing::TempDir()) / ("fragmpm_figures_" + std::to_string(getpid()) + "_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  cleanup.dirs.push_back(dir);
  return dir;
}

int run_fragmpm(const std::string& arguments, const fs::path& log) {
  const std::string command =
      std::string(FRAGMPM_BINARY) + " " + arguments + " > " + log.string() + " 2>&1";
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

cv::Vec3b pixel(const cv::Mat& image, double x, double y) {
  return image.at<cv::Vec3b>(static_cast<int>(std::floor(y)), static_cast<int>(std::floor(x)));
}

bool is_colour(const cv::Vec3b& bgr, Rgb c, int tolerance = 0) {
  return std::abs(bgr[2] - c.r) <= tolerance && std::abs(bgr[1] - c.g) <= tolerance &&
         std::abs(bgr[0] - c.b) <= tolerance;
}

bool is_dark(const cv::Vec3b& bgr) {
  return bgr[0] < 60 && bgr[1] < 60 && bgr[2] < 60;
}
bool is_white(const cv::Vec3b& bgr) {
  return bgr[0] == 255 && bgr[1] == 255 && bgr[2] == 255;
}

/// Three unit squares (side 1 mm) in a row, 3 mm apart, centres at x = 0, 3, 6 mm.
ParticleFigure three_squares() {
  ParticleFigure f;
  const double h = 1e-3;
  for (int i = 0; i < 3; ++i) {
    f.x.push_back({3.0 * h * i, 0.0});
    f.r1.push_back({h, 0.0});
    f.r2.push_back({0.0, h});
  }
  f.width = 900;
  f.height = 600;
  f.title = "three squares";
  f.time = 2.5e-6;
  return f;
}

}  // namespace

TEST(AxisTicks, LinearTicksAreMultiplesOfOneTwoFive) {
  EXPECT_DOUBLE_EQ(nice_step(10.0, 5), 2.0);
  EXPECT_DOUBLE_EQ(nice_step(1.0, 6), 0.2);
  EXPECT_DOUBLE_EQ(nice_step(3e-4, 6), 5e-5);
  EXPECT_DOUBLE_EQ(nice_step(7.0, 6), 1.0);
  const AxisTicks t = linear_ticks(0.0, 0.93);  // ±4 %: [-0.0372, 0.9672], step 0.2
  ASSERT_EQ(t.major.size(), 5u);
  for (std::size_t k = 0; k < t.major.size(); ++k) EXPECT_NEAR(t.major[k], 0.2 * k, 1e-15);
  EXPECT_EQ(plain_text(t.labels[0]), "0.0");
  EXPECT_EQ(plain_text(t.labels[4]), "0.8");
  EXPECT_TRUE(t.multiplier.empty());
  // Large values carry an engineering multiplier instead of long labels.
  const AxisTicks big = linear_ticks(0.0, 4.2e6);
  EXPECT_EQ(plain_text(big.multiplier), "x10^6");
  EXPECT_EQ(plain_text(big.labels[1]), "1");
  // A constant series still gets a range around its value.
  const AxisTicks flat = linear_ticks(5.0, 5.0);
  EXPECT_LT(flat.lo, 5.0);
  EXPECT_GT(flat.hi, 5.0);
}

TEST(AxisTicks, LogTicksAreDecadesOrOneTwoFive) {
  const AxisTicks wide = log_ticks(1e-3, 1e2);
  ASSERT_EQ(wide.major.size(), 6u);
  EXPECT_NEAR(wide.major.front(), 1e-3, 1e-18);
  EXPECT_NEAR(wide.major.back(), 1e2, 1e-12);
  EXPECT_EQ(plain_text(wide.labels.front()), "0.001");
  EXPECT_EQ(plain_text(wide.labels.back()), "100");
  // 2..9 in each of the five decades between the labels, and 7, 8, 9 × 10^-4 in the 4 % margin
  // (0.2 decades) below 10^-3.
  EXPECT_EQ(wide.minor.size(), 5u * 8u + 3u);
  const AxisTicks tiny = log_ticks(1e-9, 1e-6);
  EXPECT_EQ(plain_text(tiny.labels.front()), "10^-9");
  const AxisTicks narrow = log_ticks(0.03, 0.6);  // one and a bit decades: 0.05, 0.1, 0.2, 0.5
  ASSERT_EQ(narrow.major.size(), 4u);
  EXPECT_EQ(plain_text(narrow.labels[0]), "0.05");
  EXPECT_EQ(plain_text(narrow.labels[3]), "0.5");
}

TEST(FigureText, SiFormattingAndScaleBars) {
  EXPECT_EQ(format_si(1e-3, "m"), "1 mm");
  EXPECT_EQ(format_si(2e-4, "m"), "200 \u00b5m");
  EXPECT_EQ(format_si(12.5e-6, "s"), "12.5 \u00b5s");
  EXPECT_EQ(format_si(999.7, "m"), "1 km");
  EXPECT_EQ(format_si(-3.25e6, "Pa"), "-3.25 MPa");
  EXPECT_DOUBLE_EQ(scale_bar_length(0.3e-3), 2e-4);
  EXPECT_DOUBLE_EQ(scale_bar_length(1.0), 1.0);
  EXPECT_DOUBLE_EQ(scale_bar_length(4.9e-3), 2e-3);
  EXPECT_DOUBLE_EQ(scale_bar_length(5e-3), 5e-3);
}

TEST(FrameFigure, MaximumPrincipalStressOfTwoByTwoCauchyStress) {
  Eigen::Matrix2d s;
  s << 3.0, 1.0, 1.0, 1.0;  // eigenvalues 2 ± √2
  EXPECT_NEAR(max_principal_stress(s), 2.0 + std::sqrt(2.0), 1e-14);
  s << -5e6, 0.0, 0.0, 2e6;  // uniaxial compression along x, tension along y
  EXPECT_DOUBLE_EQ(max_principal_stress(s), 2e6);
  EXPECT_EQ(parse_frame_field("stress"), FrameField::stress);
  try {
    parse_frame_field("pressure");
    FAIL() << "an unknown field must be refused";
  } catch (const FigureError& e) {
    EXPECT_NE(std::string(e.what()).find("damage, temperature, speed, stress, body"),
              std::string::npos)
        << e.what();
  }
}

TEST(Offscreen, ContextRendersWithoutDisplay) {
  unsetenv("DISPLAY");  // OSMesa never needs one
  OffscreenContext gl(64, 32);
  const cv::Mat image = gl.read_bgr();
  ASSERT_EQ(image.cols, 64);
  ASSERT_EQ(image.rows, 32);
  EXPECT_TRUE(is_white(image.at<cv::Vec3b>(31, 63)));  // cleared to the white figure background
  EXPECT_THROW(OffscreenContext(0, 10), FigureError);
}

TEST(LinePlot, AxesAreDrawnAndTheSeriesFollowsItsLine) {
  PlotSpec spec;
  spec.title = "y = 2x";
  spec.x_label = "x [m]";
  spec.y_label = "y [m]";
  spec.width = 800;
  spec.height = 600;
  LineSeries s;
  s.label = "y = 2x";
  for (int i = 0; i <= 10; ++i) {
    s.x.push_back(i);
    s.y.push_back(2.0 * i);
  }
  spec.series.push_back(s);
  const PlotFrame f = plot_frame(spec);
  const cv::Mat image = render_line_plot(spec);
  ASSERT_EQ(image.cols, 800);
  ASSERT_EQ(image.rows, 600);
  // The axis frame: the column just left of the plot area and the row just below it are dark
  // over their whole length.
  for (int y = f.top; y < f.bottom; ++y)
    ASSERT_TRUE(is_dark(image.at<cv::Vec3b>(y, f.left - 1))) << "row " << y;
  for (int x = f.left; x < f.right; ++x)
    ASSERT_TRUE(is_dark(image.at<cv::Vec3b>(f.bottom, x))) << "column " << x;
  // The data map puts x = 0 and x = 10 inside the plot area, ticks at 0, 2, …, 10.
  ASSERT_EQ(f.x.major.size(), 6u);
  EXPECT_GT(f.to_px(0.0), f.left);
  EXPECT_LT(f.to_px(10.0), f.right);
  // The series colour lies along the straight line y = 2x, sampled between its ends.
  const Rgb colour = series_colour(0);
  for (int k = 1; k < 40; ++k) {
    const double x = 10.0 * k / 40.0;
    const double px = f.to_px(x), py = f.to_py(2.0 * x);
    bool found = false;
    for (int dy = -1; dy <= 1 && !found; ++dy)
      for (int dx = -1; dx <= 1 && !found; ++dx)
        found = is_colour(pixel(image, px + dx, py + dy), colour, 12);
    EXPECT_TRUE(found) << "no series colour at x = " << x << " (pixel " << px << ", " << py << ")";
  }
  // Away from the line and the grid (x = 9, y = 3), the plot area is background.
  EXPECT_TRUE(is_white(pixel(image, f.to_px(9.0), f.to_py(3.0))));
  // Tick labels: dark ink under the x axis below the tick at x = 10.
  int ink = 0;
  for (int y = f.bottom + 12; y < f.bottom + 45; ++y)
    for (int x = static_cast<int>(f.to_px(10.0)) - 15; x < static_cast<int>(f.to_px(10.0)) + 15;
         ++x)
      ink += image.at<cv::Vec3b>(y, x)[1] < 160 ? 1 : 0;  // antialiased strokes: mid-grey counts
  EXPECT_GT(ink, 20) << "the tick label '10' is drawn under its tick";
}

TEST(LinePlot, BadInputGivesClearErrors) {
  PlotSpec spec;
  spec.title = "cdf";
  spec.log_x = true;
  spec.series.push_back(LineSeries{"diameters", {1e-4, 0.0, 3e-4}, {0.1, 0.5, 1.0}, false});
  try {
    render_line_plot(spec);
    FAIL() << "a zero on a log axis must be refused";
  } catch (const FigureError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("series 1 'diameters', point 2: x = 0 is not positive"), std::string::npos)
        << m;
    EXPECT_NE(m.find("log x axis"), std::string::npos) << m;
  }
  spec.log_x = false;
  spec.log_y = true;
  spec.series[0].y[0] = -0.5;
  EXPECT_THROW(render_line_plot(spec), FigureError);
  spec.log_y = false;
  spec.series[0].y.pop_back();
  EXPECT_THROW(render_line_plot(spec), FigureError);  // 3 x values, 2 y values
  spec.series.clear();
  EXPECT_THROW(write_line_plot(spec, "unused.png"), FigureError);  // nothing to draw
  spec.series.push_back(LineSeries{"nan", {0.0, 1.0}, {0.0, std::nan("")}, false});
  EXPECT_THROW(render_line_plot(spec), FigureError);
}

TEST(ParticleFigure, SquaresTakeTheirColourMapColourAndBackgroundElsewhere) {
  ParticleFigure fig = three_squares();
  fig.values = {0.0, 0.5, 1.0};
  fig.field_name = "damage";
  fig.vmin = 0.0;
  fig.vmax = 1.0;
  const ParticleFrame f = particle_frame(fig);
  const cv::Mat image = render_particle_figure(fig);
  ASSERT_EQ(image.cols, 900);
  ASSERT_EQ(image.rows, 600);
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector2d c = f.to_pixel(fig.x[i]);
    EXPECT_TRUE(is_colour(pixel(image, c.x(), c.y()), viridis(fig.values[i]))) << "square " << i;
    // A quarter side from the centre is still inside the square.
    const Eigen::Vector2d q = f.to_pixel(fig.x[i] + Eigen::Vector2d(0.25e-3, -0.25e-3));
    EXPECT_TRUE(is_colour(pixel(image, q.x(), q.y()), viridis(fig.values[i]))) << "square " << i;
  }
  // Between the squares and above them: background.
  for (double gap : {1.5e-3, 4.5e-3}) {
    const Eigen::Vector2d g = f.to_pixel({gap, 0.0});
    EXPECT_TRUE(is_white(pixel(image, g.x(), g.y()))) << "gap at x = " << gap;
  }
  const Eigen::Vector2d above = f.to_pixel({3e-3, 1.2e-3});
  EXPECT_TRUE(is_white(pixel(image, above.x(), above.y())));
  // Colour bar: viridis from bottom (0) to top (1) down its middle column.
  ASSERT_GT(f.bar_bottom - f.bar_top, 100);
  const double mid = 0.5 * (f.bar_left + f.bar_right);
  for (int y = f.bar_top; y < f.bar_bottom; y += 7) {
    const double t = (f.bar_bottom - 0.5 - y) / (f.bar_bottom - f.bar_top);
    ASSERT_TRUE(is_colour(pixel(image, mid, y), viridis(t))) << "colour bar row " << y;
  }
  EXPECT_TRUE(is_colour(pixel(image, mid, f.bar_bottom - 1), viridis(0.0)));
  EXPECT_TRUE(is_colour(pixel(image, mid, f.bar_top), viridis(1.0)));
  // Scale bar: 2 mm (the longest 1-2-5 length within 30 % of the 7 mm wide domain).
  EXPECT_DOUBLE_EQ(f.scale_bar_length, 2e-3);
}

TEST(ParticleFigure, IdsTakeCategoricalColours) {
  ParticleFigure fig = three_squares();
  fig.ids = {4, 0, -1};
  fig.id_name = "fragment";
  const ParticleFrame f = particle_frame(fig);
  const cv::Mat image = render_particle_figure(fig);
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector2d c = f.to_pixel(fig.x[i]);
    EXPECT_TRUE(is_colour(pixel(image, c.x(), c.y()), categorical_colour(fig.ids[i])))
        << "square " << i;
  }
  EXPECT_TRUE(is_colour(pixel(image, f.to_pixel(fig.x[2]).x(), f.to_pixel(fig.x[2]).y()),
                        no_data_colour()));
  EXPECT_NE(categorical_colour(0), categorical_colour(1));
  EXPECT_NE(categorical_colour(10), categorical_colour(11));
}

TEST(ParticleFigure, BadInputGivesClearErrors) {
  ParticleFigure fig = three_squares();
  EXPECT_THROW(render_particle_figure(fig), FigureError);  // neither values nor ids
  fig.values = {0.0, 1.0};
  EXPECT_THROW(render_particle_figure(fig), FigureError);  // 3 particles, 2 values
  fig.values = {0.0, 0.5, 1.0};
  for (auto& r : fig.r1) r.setZero();
  try {
    render_particle_figure(fig);
    FAIL() << "zero-area domains must be refused";
  } catch (const FigureError& e) {
    EXPECT_NE(std::string(e.what()).find("zero area"), std::string::npos) << e.what();
  }
}

TEST(VerifyPlot, WritesPngAndRefusesAWrongHeader) {
  const fs::path dir = figure_directory("verify");
  const fs::path csv = dir / "bar.csv", png = dir / "bar.png";
  {
    std::ofstream out(csv);
    out << "case,variant,level,cell_size_m,particles,dt_s,steps,wall_s,metric,value,reference,"
           "error\n";
    for (int level = 0; level < 3; ++level)
      out << "bar,cpdi," << level << ",0.1,10,1e-6,100," << 0.1 * std::pow(4.0, level)
          << ",period,1,1," << 0.1 * std::pow(0.25, level) << "\n";
    out << "bar,cpdi,3,0.1,10,1e-6,100,1.0,period,1,1,0\n";  // exact: cannot sit on a log axis
  }
  write_verify_plot(csv.string(), png.string());
  const cv::Mat image = cv::imread(png.string());
  EXPECT_EQ(image.cols, 1200);
  EXPECT_EQ(image.rows, 900);
  { std::ofstream(dir / "bad.csv") << "case,variant,level\nbar,cpdi,0\n"; }
  try {
    write_verify_plot((dir / "bad.csv").string(), (dir / "bad.png").string());
    FAIL() << "a wrong header must be refused";
  } catch (const FigureError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.csv:1: header"), std::string::npos) << e.what();
  }
}

TEST(RenderCommand, BadInputExitsWithCodeTwo) {
  const fs::path dir = figure_directory("render_bad");
  EXPECT_EQ(run_fragmpm("render " + (dir / "missing.h5").string() + " --field damage -o " +
                            (dir / "a.png").string(),
                        dir / "log1"),
            2);
  EXPECT_NE(read_text(dir / "log1").find("no such file"), std::string::npos)
      << read_text(dir / "log1");
  EXPECT_EQ(run_fragmpm("render " + (dir / "missing.h5").string() + " --field pressure -o " +
                            (dir / "a.png").string(),
                        dir / "log2"),
            2);
  EXPECT_NE(read_text(dir / "log2").find("unknown field 'pressure'"), std::string::npos)
      << read_text(dir / "log2");
  EXPECT_FALSE(fs::exists(dir / "a.png"));
}

TEST(RenderCommand, RendersATinyRunFileToThePngSizeAsked) {
  const fs::path dir = figure_directory("render_run");
  const std::string run = (dir / "tiny.h5").string();
  // A 10 × 5 block of 0.1 mm particles with damage 0.5, and two series rows with two walls.
  mpm::Particles<2> p;
  const double h = 1e-4;
  p.resize(50);
  for (int i = 0; i < 50; ++i) {
    p.x[i] = mpm::Vec<2>((i % 10 + 0.5) * h, (i / 10 + 0.5) * h);
    p.domain[i] << h, 0.0, 0.0, h;
    p.v[i] = mpm::Vec<2>(0.0, -1.0);
    p.damage[i] = 0.5;
    p.stress[i] << -1e6, 0.0, 0.0, -2e6;
    p.body[i] = i % 10 < 5 ? 0 : 1;
    p.volume0[i] = h * h;
    p.mass[i] = 2650 * h * h;
  }
  {
    mpm::RunMeta meta;
    meta.scene_path = "tiny.toml";
    meta.scene_text = "# test";
    meta.wall_names = {"top", "bottom"};
    auto file = mpm::RunFile<2>::create(run, meta, true);
    file.write_frame(0, 0.0, p, {});
    std::vector<mpm::SeriesRow<2>> rows(3);
    for (int k = 0; k < 3; ++k) {
      rows[k].step = k;
      rows[k].time = 1e-7 * k;
      rows[k].dt = 1e-7;
      rows[k].kinetic = 1e-3 * (3 - k);
      rows[k].strain = 1e-3 * k;
      rows[k].wall_force = {mpm::Vec<2>(0.0, 100.0 * k), mpm::Vec<2>(0.0, -100.0 * k)};
      rows[k].wall_displacement = {mpm::Vec<2>(0.0, -1e-6 * k), mpm::Vec<2>::Zero()};
    }
    file.append_series(rows);
    file.write_frame(2, 2e-7, p, {"x", "r1", "r2", "v"});  // frame 1 keeps no damage
  }
  const std::string png = (dir / "damage.png").string();
  ASSERT_EQ(run_fragmpm("render " + run + " --field damage --frame 0 -o " + png +
                            " --width 640 --height 480",
                        dir / "log"),
            0)
      << read_text(dir / "log");
  cv::Mat image = cv::imread(png);
  ASSERT_FALSE(image.empty());
  EXPECT_EQ(image.cols, 640);
  EXPECT_EQ(image.rows, 480);
  // The block is drawn in viridis(0.5): a 2:1 block filling most of the width covers > 20 000
  // pixels.
  int block = 0;
  for (int y = 0; y < image.rows; ++y)
    for (int x = 0; x < image.cols; ++x)
      block += is_colour(image.at<cv::Vec3b>(y, x), viridis(0.5)) ? 1 : 0;
  EXPECT_GT(block, 20000);
  // Refuses to replace the PNG without --overwrite, and replaces it with.
  EXPECT_EQ(run_fragmpm("render " + run + " --field body --frame 0 -o " + png, dir / "log"), 2);
  EXPECT_NE(read_text(dir / "log").find("--overwrite"), std::string::npos)
      << read_text(dir / "log");
  EXPECT_EQ(cv::imread(png).cols, 640) << "the refused render left the file alone";
  EXPECT_EQ(run_fragmpm("render " + run + " --field body --frame 0 -o " + png + " --overwrite",
                        dir / "log"),
            0)
      << read_text(dir / "log");
  EXPECT_EQ(cv::imread(png).cols, 1200);
  // Frames that do not exist, fields the frame lacks, and the run's series plots.
  EXPECT_EQ(
      run_fragmpm("render " + run + " --field damage --frame 7 -o " + (dir / "f7.png").string(),
                  dir / "log"),
      2);
  EXPECT_NE(read_text(dir / "log").find("frames 0 to 1"), std::string::npos)
      << read_text(dir / "log");
  EXPECT_EQ(run_fragmpm("render " + run + " --field damage -o " + (dir / "last.png").string(),
                        dir / "log"),
            2);
  EXPECT_NE(read_text(dir / "log").find("/frames/000001/damage"), std::string::npos)
      << read_text(dir / "log");
  EXPECT_EQ(
      run_fragmpm("render " + run + " --field temperature --frame 0 -o " + (dir / "t.png").string(),
                  dir / "log"),
      2);
  EXPECT_EQ(run_fragmpm("render " + run + " --field speed -o " + (dir / "speed.png").string(),
                        dir / "log"),
            0)
      << read_text(dir / "log");
  // Fragments, labelled as analyze does: the two bodies of frame 0 are two fragments of 25
  // particles each, drawn in the first two categorical colours in equal areas.
  const std::string fragments_png = (dir / "fragments.png").string();
  ASSERT_EQ(
      run_fragmpm("render " + run + " --field fragment --frame 0 -o " + fragments_png, dir / "log"),
      0)
      << read_text(dir / "log");
  image = cv::imread(fragments_png);
  int first = 0, second = 0;
  for (int y = 0; y < image.rows; ++y)
    for (int x = 0; x < image.cols; ++x) {
      first += is_colour(image.at<cv::Vec3b>(y, x), categorical_colour(0)) ? 1 : 0;
      second += is_colour(image.at<cv::Vec3b>(y, x), categorical_colour(1)) ? 1 : 0;
    }
  EXPECT_GT(first, 50000);
  EXPECT_NEAR(static_cast<double>(second) / first, 1.0, 0.05);
  EXPECT_EQ(
      run_fragmpm("render " + run + " --field fragment --frame 1 -o " + (dir / "f1.png").string(),
                  dir / "log"),
      2);
  EXPECT_NE(read_text(dir / "log").find("/frames/000001/damage"), std::string::npos)
      << read_text(dir / "log");
  EXPECT_EQ(run_fragmpm("render " + run + " --series energy -o " + (dir / "energy.png").string(),
                        dir / "log"),
            0)
      << read_text(dir / "log");
  EXPECT_EQ(
      run_fragmpm("render " + run + " --series force-displacement -o " + (dir / "fd.png").string(),
                  dir / "log"),
      0)
      << read_text(dir / "log");
  EXPECT_EQ(cv::imread((dir / "fd.png").string()).rows, 900);
  EXPECT_EQ(run_fragmpm("render " + run + " --series pressure -o " + (dir / "p.png").string(),
                        dir / "log"),
            2);
}

TEST(SeriesFigures, FixedWallReactionIsPlottedAgainstTime) {
  const fs::path dir = figure_directory("fixed_wall");
  const std::string run = (dir / "impact.h5").string();
  {
    mpm::RunMeta meta;
    meta.wall_names = {"anvil"};
    auto file = mpm::RunFile<2>::create(run, meta, true);
    std::vector<mpm::SeriesRow<2>> rows(4);
    for (int k = 0; k < 4; ++k) {
      rows[k].step = k;
      rows[k].time = 2e-6 * k;
      rows[k].wall_force = {mpm::Vec<2>(3e3 * k, 4e3 * k)};  // |F| = 5 kN/m per step
      rows[k].wall_displacement = {mpm::Vec<2>::Zero()};
    }
    file.append_series(rows);
  }
  const PlotSpec spec = force_displacement_spec(run, {"anvil"});
  ASSERT_EQ(spec.series.size(), 1u);
  EXPECT_EQ(spec.x_label, "time [\u00b5s]");
  EXPECT_EQ(spec.y_label, "reaction force |F| [kN/m]");
  EXPECT_DOUBLE_EQ(spec.series[0].x[3], 6.0);   // 6 µs
  EXPECT_DOUBLE_EQ(spec.series[0].y[3], 15.0);  // 15 kN/m
  EXPECT_THROW(force_displacement_spec(run, {}), FigureError);
}

TEST(SeriesFigures, EnergyFigureDrawsEveryTermOfTheBalance) {
  // A phase-field bar pulled by a traction load: the load's work goes into kinetic, strain and
  // crack energy and the transfer loss; the balance error is what they leave. The figure must draw
  // every term, so that the drawn stores and losses less the drawn work reproduce the drawn error
  // at every row (docs/design.md §2.4); gravity and crushed flow, zero throughout, are left off.
  const fs::path dir = figure_directory("energy_terms");
  const std::string run = (dir / "pulled.h5").string();
  {
    auto file = mpm::RunFile<2>::create(run, mpm::RunMeta{}, true);
    std::vector<mpm::SeriesRow<2>> rows(4);
    for (int k = 0; k < 4; ++k) {
      rows[k].step = k;
      rows[k].time = 1e-6 * k;
      rows[k].kinetic = 3.0 * k;
      rows[k].strain = 2.0 * k;
      rows[k].totals.fracture_energy = 4.0 * k;
      rows[k].totals.transfer_dissipation = 0.5 * k;
      rows[k].totals.load_work = 10.0 * k;
      rows[k].balance_error = (3.0 + 2.0 + 4.0 + 0.5 - 10.0) * k;
    }
    file.append_series(rows);
  }
  const PlotSpec spec = energy_plot_spec(run);
  double sign_of_balance = 0.0;
  std::vector<double> drawn(4, 0.0), error(4, 0.0);
  bool crack = false, load = false;
  for (const LineSeries& s : spec.series) {
    EXPECT_NE(s.label, "gravity work");
    EXPECT_NE(s.label, "crushed flow");
    crack = crack || s.label == "crack energy (phase field)";
    load = load || s.label == "load work";
    ASSERT_EQ(s.y.size(), 4u) << s.label;
    if (s.label == "balance error") {
      sign_of_balance = 1.0;
      error = s.y;
      continue;
    }
    const bool put_in = s.label == "load work" || s.label == "wall work" ||
                        s.label == "gravity work" || s.label.starts_with("history excess");
    const double sign = put_in ? -1.0 : 1.0;
    for (int k = 0; k < 4; ++k) drawn[k] += sign * s.y[k];
  }
  EXPECT_TRUE(crack);
  EXPECT_TRUE(load);
  ASSERT_EQ(sign_of_balance, 1.0);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(drawn[k], error[k], 1e-12) << "row " << k;
  EXPECT_NEAR(error[3], -1.5, 1e-12);  // J/m: drawn unscaled
}

TEST(SeriesFigures, LongRunsPlotWindowMeansOfTheForce) {
  // 2000 steps of Δt = 1 ns under a steady 5 kN/m on a platen moving at 1 m/s, except that every
  // 100th step is cut to 1 ps and carries an 11 ns-worth impulse, as when the wall plane passes a
  // row of grid nodes. A load cell reads impulse over time: a window of 4.95 ns (400 windows) that
  // holds a spike and at least 4 ordinary steps reads at most 5 kN/m · (4 + 11) / 4 = 18.75 kN/m,
  // not the 55 GN/m of the spike's own step; every other window reads exactly 5 kN/m.
  const fs::path dir = figure_directory("window_means");
  const std::string run = (dir / "crush.h5").string();
  const int n = 2000;
  {
    mpm::RunMeta meta;
    meta.wall_names = {"platen"};
    auto file = mpm::RunFile<2>::create(run, meta, true);
    std::vector<mpm::SeriesRow<2>> rows(n);
    double t = 0.0;
    for (int k = 0; k < n; ++k) {
      const bool spike = k % 100 == 50;
      rows[k].step = k + 1;
      rows[k].dt = spike ? 1e-12 : 1e-9;
      t += rows[k].dt;
      rows[k].time = t;
      const double force = spike ? 5e3 * 11e-9 / 1e-12 : 5e3;
      rows[k].wall_force = {mpm::Vec<2>(0.0, force)};
      rows[k].wall_displacement = {mpm::Vec<2>(0.0, -1.0 * t)};
    }
    file.append_series(rows);
  }
  const PlotSpec spec = force_displacement_spec(run, {"platen"});
  ASSERT_EQ(spec.series.size(), 1u);
  const LineSeries& s = spec.series[0];
  EXPECT_NE(spec.title.find("means over"), std::string::npos) << spec.title;
  EXPECT_EQ(s.y.size(), 400u);
  EXPECT_EQ(spec.y_label, "reaction force |F| [kN/m]");
  int spikes = 0;
  for (double f : s.y) {
    EXPECT_GE(f, 5.0 - 1e-9);
    EXPECT_LE(f, 18.75 + 1e-6);
    if (f > 5.0 + 1e-9) ++spikes;
  }
  EXPECT_EQ(spikes, n / 100);
  EXPECT_EQ(spec.x_label, "wall displacement |u| [\u00b5m]");
  EXPECT_NEAR(s.x.back(), 1.98 - 0.5 * 0.00495, 1e-3);  // mean travel over the last window [µm]
}

TEST(FrameFigure, StressColourRangeIsClippedToThePercentilesOfLargeFrames) {
  mpm::Particles<2> p;
  const int n = 1001;
  p.resize(n);
  for (int i = 0; i < n; ++i) {
    p.x[i] = mpm::Vec<2>(1e-4 * i, 0.0);
    p.domain[i] << 1e-4, 0.0, 0.0, 1e-4;
    p.stress[i] << -1e6 * i, 0.0, 0.0, -2e9;  // max principal: −i MPa
  }
  p.stress[0] << 5e9, 0.0, 0.0, -2e9;  // one extreme particle
  ParticleFigure f = frame_figure(p, FrameField::stress, 0.0, "s");
  ASSERT_TRUE(f.vmin && f.vmax);
  EXPECT_DOUBLE_EQ(*f.vmin, -990.0);  // 1st percentile of {5000, −1, …, −1000}: the 11th smallest
  EXPECT_DOUBLE_EQ(*f.vmax, -10.0);
  EXPECT_NE(f.field_name.find("1-99 %"), std::string::npos);
  p.resize(100);  // too few particles for percentiles: the full range
  f = frame_figure(p, FrameField::stress, 0.0, "s");
  EXPECT_FALSE(f.vmin.has_value());
  EXPECT_EQ(f.field_name, "max principal stress");
}

TEST(ParticleFigure, NoIdSharesTheGreyOfNone) {
  for (std::int64_t id = 0; id < 1000; ++id)
    ASSERT_NE(categorical_colour(id), no_data_colour()) << id;
}

// Figure text is drawn with a TrueType font (DejaVu Sans from Debian's fonts-dejavu-core), so µ is
// its own glyph: a label with "µs" must not render like one with "us", as it did when the text was
// transliterated to ASCII for the Hershey fonts.
TEST(FigureText, MicroSignIsDrawnAsItsOwnGlyph) {
  const auto plot = [](const std::string& unit) {
    fragmpm::analysis::PlotSpec spec;
    spec.title = "t";
    spec.x_label = "time [" + unit + "]";
    spec.y_label = "y";
    spec.series.push_back({"", {0.0, 1.0}, {0.0, 1.0}, false});
    spec.width = 400;
    spec.height = 300;
    return fragmpm::analysis::render_line_plot(spec);
  };
  const cv::Mat micro = plot("\u00b5s"), ascii = plot("us");
  ASSERT_EQ(micro.size(), ascii.size());
  cv::Mat difference;
  cv::absdiff(micro, ascii, difference);
  EXPECT_GT(cv::countNonZero(difference.reshape(1)), 10);
}
