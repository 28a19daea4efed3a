// Grain files (docs/design.md): write, read back, refuse to overwrite, reject foreign files; grains
// as scene bodies from an image or a grain file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "fragmpm/mpm/hdf5_io.hpp"
#include "fragmpm/pipeline/segment.hpp"
#include "fragmpm/pipeline/segment_bodies.hpp"
#include "fragmpm/pipeline/segment_file.hpp"
#include "fragmpm/pipeline/segment_particles.hpp"
#include "fragmpm/pipeline/segment_synthetic.hpp"
#include "segment_test_support.hpp"

namespace fp = fragmpm::pipeline;
namespace fs = std::filesystem;

namespace {

fs::path temp_file(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / "fragmpm_test_segment_file";
  fs::create_directories(dir);
  return dir / name;
}

}  // namespace

TEST(SegmentFile, RoundTrip) {
  const fp::SyntheticImage d = fp::synthetic_touching_pairs();
  fp::SegmentOptions o = fp::testing::micrometre_options("pairs.png");
  o.crop = cv::Rect(10, 20, 600, 440);
  const fp::Segmentation s = fp::segment(d.image, o);
  const fp::ParticleSampling sampling{5e-6, 2};
  const auto particles = fp::particles_from_labels(s.table.labels, s.pixel_size, sampling,
                                                   fp::material_of_labels(s.table), {2500.0});
  const fs::path path = temp_file("pairs.h5");
  fs::remove(path);
  fp::write_grain_file(path.string(), s, particles, {sampling, {2500.0}, "split = true\n"}, false);

  const fp::GrainFile g = fp::read_grain_file(path.string());
  EXPECT_EQ(g.image_path, "pairs.png");
  EXPECT_DOUBLE_EQ(g.pixel_size, 1e-6);
  EXPECT_EQ(g.window, cv::Rect(10, 20, 600, 440));
  EXPECT_EQ(cv::countNonZero(g.labels != s.table.labels), 0);
  ASSERT_EQ(g.grains.size(), s.table.grains.size());
  for (std::size_t k = 0; k < g.grains.size(); ++k) {
    EXPECT_EQ(g.grains[k].label, s.table.grains[k].label);
    EXPECT_EQ(g.grains[k].pixels, s.table.grains[k].pixels);
    EXPECT_DOUBLE_EQ(g.grains[k].shape.area, s.table.grains[k].shape.area);
    EXPECT_DOUBLE_EQ(g.grains[k].shape.roundness, s.table.grains[k].shape.roundness);
    EXPECT_DOUBLE_EQ(g.grains[k].shape.centroid_y, s.table.grains[k].shape.centroid_y);
    EXPECT_EQ(g.grains[k].touches_border, s.table.grains[k].touches_border);
  }
  ASSERT_EQ(g.particles.size(), particles.size());
  for (std::size_t k = 0; k < particles.size(); ++k) {
    EXPECT_EQ(g.particles.x[k], particles.x[k]);
    EXPECT_EQ(g.particles.domain[k], particles.domain[k]);
    EXPECT_EQ(g.particles.surface[k], particles.surface[k]);
    EXPECT_EQ(g.particles.body[k], particles.body[k]);
    EXPECT_DOUBLE_EQ(g.particles.mass[k], particles.mass[k]);
  }
  EXPECT_DOUBLE_EQ(g.sampling.cell_size, 5e-6);
  EXPECT_EQ(g.sampling.particles_per_cell, 2);

  // An existing file is kept unless overwriting is asked for.
  EXPECT_THROW(fp::write_grain_file(path.string(), s, particles, {sampling, {2500.0}, ""}, false),
               fragmpm::mpm::RunFileError);
  EXPECT_NO_THROW(
      fp::write_grain_file(path.string(), s, particles, {sampling, {2500.0}, ""}, true));
}

TEST(SegmentFile, ForeignFilesAreRejected) {
  const fs::path text = temp_file("not_hdf5.h5");
  std::ofstream(text) << "hello\n";
  EXPECT_THROW(fp::read_grain_file(text.string()), fragmpm::mpm::RunFileError);
  EXPECT_THROW(fp::read_grain_file(temp_file("missing.h5").string()), fragmpm::mpm::RunFileError);
  // An HDF5 file that is not a grain file.
  const fs::path other = temp_file("other.h5");
  {
    const auto f = fragmpm::mpm::h5::File::create(other.string(), true);
    f.root().set_attribute("format", "something else");
  }
  try {
    fp::read_grain_file(other.string());
    FAIL() << "expected RunFileError";
  } catch (const fragmpm::mpm::RunFileError& e) {
    EXPECT_NE(std::string(e.what()).find("not a grain file"), std::string::npos) << e.what();
  }
}

TEST(SegmentFile, BodiesFromImageAndFromGrainFileAgree) {
  // The scene's two routes to grains give the same particles at the scene's cell size.
  const fs::path image = temp_file("pairs_for_bodies.png");
  cv::imwrite(image.string(), fp::synthetic_touching_pairs().image);
  fp::SegmentOptions o = fp::testing::micrometre_options(image.string());
  const fp::ParticleSampling scene{6e-6, 2};
  const fp::GrainBodies direct = fp::grain_bodies_from_image(o, scene, {2650.0});
  EXPECT_EQ(direct.grains.size(), 12u);
  EXPECT_EQ(direct.body_names.size(), 12u);
  EXPECT_EQ(direct.body_names[0], "grain 1");
  EXPECT_DOUBLE_EQ(direct.width, 640e-6);

  const fp::Segmentation s = fp::segment(o);
  const auto coarse = fp::particles_from_labels(s.table.labels, s.pixel_size, {10e-6, 1},
                                                fp::material_of_labels(s.table), {2650.0});
  const fs::path file = temp_file("pairs_for_bodies.h5");
  fp::write_grain_file(file.string(), s, coarse, {{10e-6, 1}, {2650.0}, ""}, true);
  const fp::GrainBodies from_file = fp::grain_bodies_from_file(file.string(), scene, {2650.0});
  ASSERT_EQ(from_file.particles.size(), direct.particles.size());
  for (std::size_t k = 0; k < direct.particles.size(); ++k) {
    EXPECT_EQ(from_file.particles.x[k], direct.particles.x[k]);
    EXPECT_EQ(from_file.particles.body[k], direct.particles.body[k]);
    EXPECT_EQ(from_file.particles.surface[k], direct.particles.surface[k]);
  }
  EXPECT_THROW(fp::grain_bodies_from_file(file.string(), scene, {}), fp::SegmentInputError);
}
