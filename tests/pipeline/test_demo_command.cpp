// `fragmpm pipeline` (and the scene edit behind `fragmpm demo`): IMAGE put into the scene's image
// bodies without moving any line; refusal to write into a non-empty directory without --overwrite,
// a missing image and a scene without an image body give exit code 2; a tiny end-to-end run writes
// the preview, run file, figures and summary. The full demo is not run here (minutes).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include "../support/read_text.hpp"
#include "fragmpm/pipeline/embedded_scenes.hpp"
#include "fragmpm/pipeline/pipeline_job.hpp"
#include "fragmpm/pipeline/scene.hpp"
#include "report_test_support.hpp"

namespace fs = std::filesystem;
namespace fp = fragmpm::pipeline;

using fragmpm::test_support::read_text;

namespace {

int run_fragmpm(const std::string& arguments, const fs::path& log) {
  const std::string command =
      std::string(FRAGMPM_BINARY) + " " + arguments + " > " + log.string() + " 2>&1";
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

fs::path fresh_directory(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("fragmpm_pipeline_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

const std::string kImage = std::string(FRAGMPM_SOURCE_DIR) + "/images/miocene_sandstone_window.png";

/// A 60 x 45 um window (a few grains at 5 um cells) under a platen at 15 m/s for 0.1 us: a few
/// hundred particles and ~60 steps. `image` is replaced by the pipeline.
constexpr const char* kTinyScene = R"(
[grid]
cell_size = "5 um"
min = ["-10 um", "-10 um"]
max = ["70 um", "55 um"]
particles_per_cell = 2

[[materials]]
name = "quartz"
E = "50 GPa"
nu = 0.2
density = "2.3 g/cm3"
damage = "rankine"
strength = "25 MPa"
fracture_energy = "0.1 N/mm"

[[bodies]]
name = "sandstone"
material = "quartz"
image = "replaced-by-the-pipeline.png"
pixel_size = "1 um"
input = "classes"
crop = [300, 200, 60, 45]

[[walls]]
name = "floor"
point = ["0 um", "0 um"]
normal = [0, 1]

[[walls]]
name = "platen"
point = ["0 um", "45 um"]
normal = [0, -1]
velocity = { type = "constant", value = ["0 m/s", "-15 m/s"] }

[stop]
end_time = "0.1 us"

[output]
interval = "0.05 us"
)";

fs::path write_tiny_scene(const fs::path& dir) {
  const fs::path scene = dir / "tiny.toml";
  std::ofstream(scene) << kTinyScene;
  return scene;
}

}  // namespace

TEST(PipelineScene, ImageIsReplacedInPlaceKeepingEveryLine) {
  const std::string text =
      "[grid]\ncell_size = \"5 um\"\n\n[[bodies]]\nname = \"a\"\nimage   =  'x.png'  # grains\n"
      "[[bodies]]\nname = \"b\"\nshape = \"disk\"\n";
  const std::string out = fp::scene_with_image(text, "s.toml", "/data/my \"odd\" image.png");
  EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), std::count(text.begin(), text.end(), '\n'));
  const toml::table t = toml::parse(out);
  EXPECT_EQ(t["bodies"][0]["image"].value<std::string>(), "/data/my \"odd\" image.png");
  EXPECT_FALSE(t["bodies"][1]["image"]);
  EXPECT_NE(out.find("# grains\n"), std::string::npos);  // the rest of the line stays
}

TEST(PipelineScene, DemoSceneHasAnImageBody) {
  const std::string& text = fp::embedded_scene("demo/sandstone-crush.toml");
  const toml::table t = toml::parse(fp::scene_with_image(text, "demo", "/x/y.png"));
  EXPECT_EQ(t["bodies"][0]["image"].value<std::string>(), "/x/y.png");
}

TEST(PipelineScene, DemoSceneCrushesSeveralGrainsBetweenPlatens) {
  // The embedded demo on the shipped image: several grains ([XLS21] §4.5.1 needs grains to crush
  // against each other), a platen that moves and a stop on its travel large enough for the grains
  // to crack — at least 20 % of the window height (150 um) — reached before the end time.
  const std::string text =
      fp::scene_with_image(fp::embedded_scene("demo/sandstone-crush.toml"), "demo", kImage);
  const auto problem = fp::parse_scene(text, "demo");
  EXPECT_GE(problem.body_names.size(), 5u);
  EXPECT_GT(problem.particles.size(), 1000u);
  ASSERT_GE(problem.stop.platen, 0);
  const auto& platen = problem.walls.at(static_cast<std::size_t>(problem.stop.platen));
  EXPECT_EQ(platen.name, "platen");
  EXPECT_GE(problem.stop.platen_displacement, 0.2 * 150e-6);
  EXPECT_GE(platen.velocity.displacement(problem.stop.end_time).norm(),
            problem.stop.platen_displacement);
  // The platen touches grains from the start, so it starts at rest: at full speed (20 m/s) at once
  // it would send a rho c v = 210 MPa wave through grains of 25 MPa tensile strength.
  EXPECT_EQ(platen.velocity.velocity(0.0).norm(), 0.0);
  EXPECT_GT(platen.velocity.velocity(problem.stop.end_time).norm(), 10.0);
}

TEST(PipelineScene, DemoPackHasFortyWholeGrainsAndHeats) {
  // The default demo: the whole window, at least 40 grains not cut by its edges, the thermal
  // module on (friction and damage heating as [XLS21] §4.5), the platen ramped from rest, and a
  // stop on its travel (10 % of the 750 um height) reached before the end time.
  const std::string text =
      fp::scene_with_image(fp::embedded_scene("demo/sandstone-pack.toml"), "demo",
                           std::string(FRAGMPM_SOURCE_DIR) + "/images/miocene_sandstone_pack.png");
  const auto problem = fp::parse_scene(text, "demo");
  std::size_t whole = 0;
  for (std::size_t b = 0; b < problem.body_names.size(); ++b) {
    double lowest_x = 1.0, highest_x = -1.0, lowest_y = 1.0, highest_y = -1.0;
    for (std::size_t p = 0; p < problem.particles.size(); ++p) {
      if (problem.particles.body[p] != static_cast<int>(b)) continue;
      lowest_x = std::min(lowest_x, problem.particles.x[p][0]);
      highest_x = std::max(highest_x, problem.particles.x[p][0]);
      lowest_y = std::min(lowest_y, problem.particles.x[p][1]);
      highest_y = std::max(highest_y, problem.particles.x[p][1]);
    }
    // A grain cut by the window has particles within one particle spacing (5 um) of an edge.
    if (lowest_x > 5e-6 && highest_x < 995e-6 && lowest_y > 5e-6 && highest_y < 745e-6) ++whole;
  }
  EXPECT_GE(whole, 40u);
  EXPECT_TRUE(problem.thermal.active());
  ASSERT_GE(problem.stop.platen, 0);
  const auto& platen = problem.walls.at(static_cast<std::size_t>(problem.stop.platen));
  EXPECT_EQ(platen.velocity.velocity(0.0).norm(), 0.0);
  EXPECT_GE(problem.stop.platen_displacement, 0.1 * 750e-6 - 1e-12);
  EXPECT_GE(platen.velocity.displacement(problem.stop.end_time).norm(),
            problem.stop.platen_displacement);
}

TEST(DemoCommand, RefusesNonEmptyDirectoryBeforeSimulating) {
  const fs::path dir = fresh_directory("demo_refuse");
  const fs::path out = dir / "out";
  fs::create_directories(out);
  std::ofstream(out / "keep.txt") << "mine\n";
  // The demo looks for its micrograph first; a build directory outside the source tree finds it
  // only through FRAGMPM_SOURCE_DIR.
  setenv("FRAGMPM_SOURCE_DIR", FRAGMPM_SOURCE_DIR, 1);
  EXPECT_EQ(run_fragmpm("demo -q -o " + out.string(), dir / "log.txt"), 2);
  const std::string log = read_text(dir / "log.txt");
  EXPECT_NE(log.find("fragmpm demo: -o " + out.string()), std::string::npos) << log;
  EXPECT_NE(log.find("--overwrite"), std::string::npos) << log;
  EXPECT_EQ(read_text(out / "keep.txt"), "mine\n");
  EXPECT_FALSE(fs::exists(out / "run.h5"));
}

TEST(PipelineScene, SceneWithoutImageBodyIsRejected) {
  EXPECT_THROW(
      fp::scene_with_image("[[bodies]]\nname = \"a\"\nshape = \"disk\"\n", "s.toml", "/x.png"),
      fp::PipelineError);
  EXPECT_THROW(fp::scene_with_image("[[bodies]\n", "s.toml", "/x.png"), fp::PipelineError);
}

TEST(PipelineCommand, RefusesNonEmptyDirectoryWithoutOverwrite) {
  const fs::path dir = fresh_directory("refuse");
  const fs::path scene = write_tiny_scene(dir);
  const fs::path out = dir / "out";
  fs::create_directories(out);
  std::ofstream(out / "keep.txt") << "mine\n";
  const int code = run_fragmpm(
      "pipeline " + kImage + " --scene " + scene.string() + " -o " + out.string(), dir / "log.txt");
  EXPECT_EQ(code, 2);
  EXPECT_NE(read_text(dir / "log.txt").find("--overwrite"), std::string::npos)
      << read_text(dir / "log.txt");
  EXPECT_EQ(read_text(out / "keep.txt"), "mine\n");
  EXPECT_FALSE(fs::exists(out / "run.h5"));
}

TEST(PipelineCommand, MissingImageIsBadInput) {
  const fs::path dir = fresh_directory("no_image");
  const fs::path scene = write_tiny_scene(dir);
  const int code = run_fragmpm("pipeline " + (dir / "nope.png").string() + " --scene " +
                                   scene.string() + " -o " + (dir / "out").string(),
                               dir / "log.txt");
  EXPECT_EQ(code, 2);
  EXPECT_NE(read_text(dir / "log.txt").find("nope.png: no such file"), std::string::npos)
      << read_text(dir / "log.txt");
  EXPECT_FALSE(fs::exists(dir / "out"));
}

TEST(PipelineCommand, SceneWithoutImageBodyIsBadInput) {
  const fs::path dir = fresh_directory("no_image_body");
  const fs::path scene = dir / "disk.toml";
  std::ofstream(scene) << "[[bodies]]\nname = \"a\"\nshape = \"disk\"\n";
  const int code = run_fragmpm(
      "pipeline " + kImage + " --scene " + scene.string() + " -o " + (dir / "out").string(),
      dir / "log.txt");
  EXPECT_EQ(code, 2);
  EXPECT_NE(read_text(dir / "log.txt").find("image"), std::string::npos)
      << read_text(dir / "log.txt");
}

TEST(PipelineCommand, TinyRunWritesEverything) {
  const fs::path dir = fresh_directory("tiny");
  const fs::path scene = write_tiny_scene(dir);
  const fs::path out = dir / "out";
  fs::create_directories(out);
  std::ofstream(out / "old.txt") << "old\n";  // non-empty: needs --overwrite
  const int code = run_fragmpm("pipeline " + kImage + " --scene " + scene.string() + " -o " +
                                   out.string() + " --overwrite --threads 1 -q",
                               dir / "log.txt");
  const std::string log = read_text(dir / "log.txt");
  ASSERT_EQ(code, 0) << log;
  EXPECT_TRUE(fs::exists(out / "run.h5"));
  EXPECT_TRUE(fs::exists(out / "run.xmf"));
  EXPECT_TRUE(fs::exists(out / "segmentation.png"));
  EXPECT_TRUE(fs::exists(out / "figures" / "damage_last.png"));
  EXPECT_TRUE(fs::exists(out / "figures" / "energy.png"));
  EXPECT_TRUE(fs::exists(out / "fragments" / "fragment_series.csv"));
  for (const char* file :
       {"figures/speed_last.png", "figures/stress_last.png", "figures/body_last.png",
        "figures/force_displacement.png", "fragments/cdf_equivalent_diameter.png",
        "fragments/cdf_equivalent_diameter_mass.png", "fragments/cdf_roundness.png",
        "fragments/cdf_roundness_mass.png", "fragments/fragment_count.png",
        "fragments/fragment_size.png"})
    EXPECT_TRUE(fs::exists(out / file)) << file;
  // Frames 0, 1, 2 (0.1 us at 0.05 us intervals): the default analysis includes the last.
  EXPECT_TRUE(fs::exists(out / "fragments" / "fragments_000002.csv"));
  EXPECT_TRUE(fs::exists(out / "figures" / "fragments_000002.png"));
  const std::string summary = read_text(out / "summary.txt");
  EXPECT_NE(summary.find("grains:"), std::string::npos) << summary;
  EXPECT_NE(summary.find("% of input"), std::string::npos) << summary;
  EXPECT_NE(summary.find("fragments (resolved; fines apart)"), std::string::npos) << summary;
  EXPECT_NE(summary.find("wall time:"), std::string::npos) << summary;
  // The extremes of the last frame (the values are tested in test_state_extremes.cpp).
  EXPECT_NE(summary.find("end state:  largest J = det F "), std::string::npos) << summary;
  EXPECT_NE(summary.find("with J > 2, largest |principal stress| "), std::string::npos) << summary;
  EXPECT_NE(summary.find("(frame 2, t = 100 ns)"), std::string::npos) << summary;
  EXPECT_NE(log.find(summary.substr(0, 24)), std::string::npos);  // the summary is printed too

  // report.html: every figure it shows exists, and it names the run's numbers.
  const std::string page = read_text(out / "report.html");
  EXPECT_GE(fragmpm::test::count_existing_report_images(page, out),
            14);  // preview, 4 fields, fragment map, 6 statistics, energy, force
  const std::smatch particles = [&] {
    std::smatch m;
    std::regex_search(summary, m, std::regex(R"((\d+) particles\n)"));
    return m;
  }();
  ASSERT_FALSE(particles.empty()) << summary;
  EXPECT_NE(page.find("<th>particles</th><td>" + particles[1].str() + "</td>"), std::string::npos);
  std::smatch steps;
  ASSERT_TRUE(std::regex_search(summary, steps, std::regex(R"(run: +(\d+) steps)")));
  EXPECT_NE(page.find(steps[1].str() + " steps to t = "), std::string::npos);
  EXPECT_NE(page.find("energy balance"), std::string::npos);
  EXPECT_NE(page.find("largest volume ratio J"), std::string::npos);
  // The largest stress and the departures have no limit: read, not judged, and not counted.
  EXPECT_NE(page.find("<th>largest |principal stress|</th><td>"), std::string::npos);
  EXPECT_EQ(page.find("<td class=\"info\">info</td>"),
            page.find("</td>", page.find("<th>largest |principal stress|</th>")) + 5);
  std::smatch verdict;
  if (std::regex_search(page, verdict, std::regex(R"((\d+) of (\d+) checks need a look)"))) {
    EXPECT_EQ(verdict[2].str(), "2") << "energy balance and J are the demo's limited checks";
  }
  EXPECT_EQ(page.find("<script"), std::string::npos);
  EXPECT_EQ(page.find("http"), std::string::npos);  // nothing from the network
}
