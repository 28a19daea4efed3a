// Scenes with bodies from a micrograph or a grain file: every grain its own body,
// particle area per grain equal to the grain's area, surface flags at every grain boundary, errors
// with file, line and key.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "fragmpm/pipeline/scene.hpp"
#include "fragmpm/pipeline/segment.hpp"
#include "fragmpm/pipeline/segment_file.hpp"
#include "fragmpm/pipeline/segment_particles.hpp"
#include "fragmpm/pipeline/segment_synthetic.hpp"

namespace fp = fragmpm::pipeline;
namespace mpm = fragmpm::mpm;
namespace fs = std::filesystem;

namespace {

// Pixel 1 µm, cell 2 µm, 2 particles per cell per direction: particle spacing 1 µm, so the lattice
// points of the window are the pixel centres. A box body comes first to check body numbering.
const std::string kScene = R"([grid]
cell_size = "2 um"
min = ["0 um", "0 um"]
max = ["1000 um", "800 um"]

[[materials]]
name = "quartz"
E = "50 GPa"
nu = 0.2
density = "2.3 g/cm3"

[[bodies]]
name = "block"
material = "quartz"
shape = "box"
min = ["10 um", "10 um"]
max = ["50 um", "50 um"]

[[bodies]]
name = "rock"
material = "quartz"
image = "disks.png"
pixel_size = "1 um"
origin = ["100 um", "200 um"]
velocity = ["0 m/s", "-1 m/s"]

[stop]
end_time = "1 us"
)";

/// A temp directory holding the synthetic disks image; scenes are written next to it. One per
/// process: ctest -j runs these tests in parallel processes, and one must not read the image while
/// another is writing it.
fs::path fixture_dir() {
  const fs::path dir =
      fs::path(::testing::TempDir()) / ("fragmpm_scene_image_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  if (!fs::exists(dir / "disks.png"))
    cv::imwrite((dir / "disks.png").string(), fp::synthetic_disks().image);
  return dir;
}

std::string write_scene(const std::string& name, const std::string& text) {
  const fs::path path = fixture_dir() / name;
  std::ofstream(path) << text;
  return path.string();
}

std::string replace(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "test setup: '" << from << "' not in scene";
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

int line_of(const std::string& text, const std::string& marker) {
  const auto at = text.find(marker);
  return 1 + static_cast<int>(
                 std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
}

void expect_error(const std::string& text, const std::string& marker, const std::string& key,
                  const std::string& explanation) {
  const std::string path = write_scene("bad.toml", text);
  try {
    fp::load_scene(path);
    ADD_FAILURE() << "no error; expected key " << key;
  } catch (const fp::SceneError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.line, line_of(text, marker)) << what;
    EXPECT_EQ(e.key, key) << what;
    EXPECT_NE(what.find(path + ":" + std::to_string(e.line) + ": key '" + key + "'"),
              std::string::npos)
        << what;
    EXPECT_NE(what.find(explanation), std::string::npos) << what;
  }
}

/// Checks the grains of a problem whose body 0 is the box and bodies 1 … are the disks' grains.
void expect_disk_grains(const mpm::Problem<2>& p, const std::string& entry) {
  const fp::SyntheticImage truth = fp::synthetic_disks();
  ASSERT_EQ(p.body_names.size(), 1 + truth.grains.size());
  EXPECT_EQ(p.body_names[0], "block");
  EXPECT_EQ(p.body_names[1], entry + "-grain-1");
  const std::size_t nb = p.body_names.size();
  std::vector<double> area(nb, 0.0);
  std::vector<std::size_t> surface(nb, 0), count(nb, 0);
  for (std::size_t q = 0; q < p.particles.size(); ++q) {
    const auto b = static_cast<std::size_t>(p.particles.body[q]);
    area[b] += p.particles.volume0[q];
    surface[b] += p.particles.surface[q];
    ++count[b];
    if (b == 0) continue;
    // Inside the window placed with its lower-left corner at the origin.
    EXPECT_GT(p.particles.x[q].x(), 100e-6);
    EXPECT_LT(p.particles.x[q].x(), 100e-6 + 640e-6);
    EXPECT_GT(p.particles.x[q].y(), 200e-6);
    EXPECT_LT(p.particles.x[q].y(), 200e-6 + 480e-6);
    EXPECT_DOUBLE_EQ(p.particles.mass[q], 2300.0 * p.particles.volume0[q]);
    EXPECT_EQ(p.particles.material[q], 0);
  }
  EXPECT_NEAR(area[0], 40e-6 * 40e-6, 1e-15);
  // The synthetic disks are labelled in the segmentation's order, so match by area: every grain's
  // particle area is within 2 % of one distinct disk's analytic area π r².
  std::vector<bool> used(truth.grains.size(), false);
  for (std::size_t b = 1; b < nb; ++b) {
    EXPECT_GT(surface[b], 0u) << p.body_names[b];
    EXPECT_LT(surface[b], count[b]) << p.body_names[b] << ": every particle flagged";
    const double px = area[b] / 1e-12;
    std::size_t best = 0;
    for (std::size_t k = 1; k < truth.grains.size(); ++k)
      if (std::abs(truth.grains[k].area - px) < std::abs(truth.grains[best].area - px)) best = k;
    EXPECT_FALSE(used[best]);
    used[best] = true;
    EXPECT_NEAR(px / truth.grains[best].area, 1.0, 0.02) << p.body_names[b];
  }
}

}  // namespace

TEST(SceneImage, EveryGrainOfAnImageIsABody) {
  const mpm::Problem<2> p = fp::load_scene(write_scene("image.toml", kScene));
  expect_disk_grains(p, "rock");
  for (std::size_t q = 0; q < p.particles.size(); ++q)
    EXPECT_DOUBLE_EQ(p.particles.v[q].y(), p.particles.body[q] == 0 ? 0.0 : -1.0);
}

TEST(SceneImage, TouchingGrainsAreFlaggedOnBothSides) {
  const fs::path dir = fixture_dir();
  cv::imwrite((dir / "pairs.png").string(), fp::synthetic_touching_pairs().image);
  const mpm::Problem<2> p =
      fp::load_scene(write_scene("pairs.toml", replace(kScene, "disks.png", "pairs.png")));
  ASSERT_EQ(p.body_names.size(), 13u);
  // Lattice neighbours (spacing 1 µm) in different grains: both must carry the surface flag.
  std::map<std::pair<long, long>, std::size_t> at;
  for (std::size_t q = 0; q < p.particles.size(); ++q)
    if (p.particles.body[q] > 0)
      at[{std::lround(p.particles.x[q].x() * 1e6 - 0.5),
          std::lround(p.particles.x[q].y() * 1e6 - 0.5)}] = q;
  std::size_t contacts = 0;
  for (const auto& [ij, q] : at)
    for (const auto& d : {std::pair<long, long>{1, 0}, {0, 1}}) {
      const auto it = at.find({ij.first + d.first, ij.second + d.second});
      if (it == at.end() || p.particles.body[it->second] == p.particles.body[q]) continue;
      ++contacts;
      EXPECT_EQ(p.particles.surface[q], 1);
      EXPECT_EQ(p.particles.surface[it->second], 1);
    }
  EXPECT_GT(contacts, 6u * 10u);  // six contacts, each a chord of more than ten pixels
}

TEST(SceneImage, GrainFileGivesTheSameBodies) {
  const fs::path dir = fixture_dir();
  fp::SegmentOptions o;
  o.image_path = (dir / "disks.png").string();
  o.pixel_size = 1e-6;
  const fp::Segmentation s = fp::segment(o);
  const fp::ParticleSampling sampling{4e-6, 2};
  const mpm::Particles<2> particles = fp::particles_from_labels(
      s.table.labels, 1e-6, sampling, fp::material_of_labels(s.table), {2300.0});
  fp::write_grain_file((dir / "disks.h5").string(), s, particles, {sampling, {2300.0}, ""}, true);
  std::string text =
      replace(kScene, "image = \"disks.png\"\npixel_size = \"1 um\"", "grains = \"disks.h5\"");
  const mpm::Problem<2> p =
      fp::load_scene(write_scene("grains.toml", replace(text, "\"rock\"", "\"sand\"")));
  // The scene's cell size (particle spacing 1 µm) decides the resolution, not the file's 2 µm.
  expect_disk_grains(p, "sand");
}

TEST(SceneImage, MissingImageNamesLineAndKey) {
  expect_error(replace(kScene, "disks.png", "nothere.png"), "image = ", "bodies[1].image",
               "nothere.png");
}

TEST(SceneImage, BadPixelSizeNamesLineAndKey) {
  expect_error(replace(kScene, "\"1 um\"", "\"-1 um\""), "pixel_size", "bodies[1].pixel_size",
               "a positive length");
  expect_error(replace(kScene, "\"1 um\"", "\"1 s\""), "pixel_size", "bodies[1].pixel_size",
               "expected a length");
  expect_error(replace(kScene, "pixel_size = \"1 um\"\n", ""), "[[bodies]]\nname = \"rock\"",
               "bodies[1].pixel_size", "missing required key");
}

TEST(SceneImage, GrainsOutsideTheDomainAndUnknownKeys) {
  expect_error(replace(kScene, "[\"100 um\", \"200 um\"]", "[\"400 um\", \"200 um\"]"), "origin",
               "bodies[1].origin", "above grid.max in x");
  expect_error(replace(kScene, "origin =", "thresold = \"otsu\"\norigin ="), "thresold",
               "bodies[1].thresold", "unknown key");
  expect_error(replace(kScene, "origin =", "crop = [600, 0, 100, 100]\norigin ="), "crop",
               "bodies[1].crop", "crop");
}
