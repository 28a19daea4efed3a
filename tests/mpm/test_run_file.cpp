// Run file (docs/design.md): exact round trips of frames and checkpoints, series truncation, XDMF.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "../support/read_text.hpp"
#include "../support/temp_run_path.hpp"
#include "fragmpm/mpm/run_file.hpp"

namespace fragmpm::mpm {
using fragmpm::test_support::read_text;

namespace {

std::string temp_path(const std::string& name) {
  return test_support::temp_run_path("fragmpm_run_file", name);
}

Particles<2> random_particles(std::size_t n, bool thermal, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Particles<2> p;
  p.resize(n, thermal);
  for (std::size_t i = 0; i < n; ++i) {
    p.x[i] = Vec<2>(u(rng), u(rng));
    p.v[i] = Vec<2>(u(rng), u(rng));
    p.F[i] << 1 + u(rng), u(rng), u(rng), 1 + u(rng);
    p.volume0[i] = 1 + u(rng);
    p.mass[i] = 2 + u(rng);
    p.domain[i] << u(rng), u(rng), u(rng), u(rng);
    p.stress[i] << 1e6 * u(rng), 1e6 * u(rng), 1e6 * u(rng), 1e6 * u(rng);
    p.damage[i] = 0.5 + 0.5 * u(rng);
    p.damage_history[i] = 1e7 * u(rng);
    p.surface[i] = static_cast<std::uint8_t>(i % 2);
    p.body[i] = static_cast<std::int32_t>(i % 3);
    p.material[i] = static_cast<std::int32_t>(i % 5) - 1;
    p.strength[i] = 1e7 * (1 + u(rng));
    if (thermal) p.temperature[i] = 300 + 10 * u(rng);
  }
  return p;
}

RunMeta test_meta() {
  RunMeta meta;
  meta.scene_path = "scenes/test.toml";
  meta.scene_text = "# a scene\n[time]\nend = \"1 ms\"  # μs and — survive as UTF-8\n";
  meta.modules = {{"elastic", true, "always"},
                  {"damage", false, "no material has a strength"},
                  {"thermal", false, ""}};
  meta.wall_names = {"top", "bottom"};
  return meta;
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

template <class M>
bool same_bits_eigen(const std::vector<M>& a, const std::vector<M>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::memcmp(a[i].data(), b[i].data(), sizeof(double) * a[i].size()) != 0) return false;
  return true;
}

/// Minimal XML well-formedness: every start tag is closed by a matching end tag, in order.
bool balanced_xml(const std::string& text, std::string* error) {
  std::vector<std::string> open;
  std::size_t pos = 0;
  while ((pos = text.find('<', pos)) != std::string::npos) {
    const std::size_t end = text.find('>', pos);
    if (end == std::string::npos) return *error = "unterminated tag", false;
    const std::string tag = text.substr(pos + 1, end - pos - 1);
    pos = end + 1;
    if (tag.empty() || tag[0] == '?' || tag[0] == '!') continue;
    if (tag[0] == '/') {
      if (open.empty() || open.back() != tag.substr(1))
        return *error = "unexpected </" + tag.substr(1) + ">", false;
      open.pop_back();
      continue;
    }
    if (tag.back() == '/') continue;  // self-closing
    open.push_back(tag.substr(0, tag.find_first_of(" \t\n")));
  }
  if (!open.empty()) return *error = "unclosed <" + open.back() + ">", false;
  return true;
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t pos = text.find(what); pos != std::string::npos; pos = text.find(what, pos + 1))
    ++n;
  return n;
}

TEST(RunFile, FrameRoundTripIsExact) {
  const std::string path = temp_path("frame");
  auto run = RunFile<2>::create(path, test_meta(), false);
  const Particles<2> p = random_particles(37, true, 1);
  EXPECT_EQ(run.write_frame(12, 0.25, p, {}), 0);
  EXPECT_EQ(run.write_frame(40, 0.5, p, {"v", "damage"}), 1);
  ASSERT_EQ(run.frame_count(), 2);

  double time = 0;
  long long step = 0;
  const Particles<2> q = run.read_frame(0, &time, &step);
  EXPECT_EQ(time, 0.25);
  EXPECT_EQ(step, 12);
  ASSERT_EQ(q.size(), p.size());
  EXPECT_TRUE(same_bits_eigen(q.x, p.x));
  EXPECT_TRUE(same_bits_eigen(q.v, p.v));
  EXPECT_TRUE(same_bits_eigen(q.F, p.F));
  EXPECT_TRUE(same_bits_eigen(q.domain, p.domain));  // r1, r2 are both columns in 2D
  EXPECT_TRUE(same_bits_eigen(q.stress, p.stress));
  EXPECT_EQ(q.volume0, p.volume0);
  EXPECT_EQ(q.mass, p.mass);
  EXPECT_EQ(q.damage, p.damage);
  EXPECT_EQ(q.surface, p.surface);
  EXPECT_EQ(q.body, p.body);
  EXPECT_EQ(q.material, p.material);
  EXPECT_EQ(q.temperature, p.temperature);

  // A frame with a field subset holds x plus those fields; the rest keep Particles defaults.
  const Particles<2> r = run.read_frame(1, &time, &step);
  EXPECT_EQ(step, 40);
  EXPECT_TRUE(same_bits_eigen(r.x, p.x));
  EXPECT_TRUE(same_bits_eigen(r.v, p.v));
  EXPECT_EQ(r.damage, p.damage);
  EXPECT_EQ(r.mass, std::vector<double>(p.size(), 0.0));
  EXPECT_TRUE(r.temperature.empty());

  // Units are stored with every dataset.
  const h5::File file = h5::File::open(path, false);
  const h5::Group frame = file.root().open_group("frames/000000");
  EXPECT_EQ(frame.open_dataset("x").attribute_string("units"), "m");
  EXPECT_EQ(frame.open_dataset("stress").attribute_string("units"), "Pa");
  EXPECT_EQ(frame.open_dataset("mass").attribute_string("units"), "kg/m (per unit thickness)");
  EXPECT_EQ(frame.open_dataset("F").dims(), (h5::Dims{37, 2, 2}));
  EXPECT_EQ(frame.open_dataset("r1").dims(), (h5::Dims{37, 2}));
  EXPECT_EQ(frame.attribute_double("time"), 0.25);
  EXPECT_EQ(frame.attribute_int64("step"), 12);
}

TEST(RunFile, FrameWithoutTemperatureOmitsIt) {
  const std::string path = temp_path("no_temperature");
  auto run = RunFile<2>::create(path, test_meta(), false);
  run.write_frame(0, 0.0, random_particles(5, false, 2), {});
  const h5::File file = h5::File::open(path, false);
  const h5::Group frame = file.root().open_group("frames/000000");
  EXPECT_FALSE(frame.exists("temperature"));
  EXPECT_EQ(frame.children().size(), all_frame_fields().size() - 1);
}

TEST(RunFile, UnknownFieldIsRejected) {
  const std::string path = temp_path("unknown_field");
  auto run = RunFile<2>::create(path, test_meta(), false);
  try {
    run.write_frame(0, 0.0, random_particles(3, false, 3), {"x", "velocity"});
    FAIL() << "expected RunFileError";
  } catch (const RunFileError& e) {
    EXPECT_NE(std::string(e.what()).find("'velocity'"), std::string::npos) << e.what();
  }
}

TEST(RunFile, CheckpointRoundTripIsBitExact) {
  const std::string path = temp_path("checkpoint");
  auto run = RunFile<2>::create(path, test_meta(), false);
  EXPECT_FALSE(run.read_checkpoint().has_value());

  Checkpoint<2> c;
  c.time = 1.0 / 3.0;
  c.step = 123456789012LL;
  c.totals.wall_work = 0.1;
  c.totals.gravity_work = -1e-300;
  c.totals.friction_work = 5e-324;  // subnormal
  c.totals.dissipated = 2.0 / 7.0;
  c.totals.initial_energy = 1e300;
  c.totals.fracture_energy = 1.0 / 11.0;
  c.particles = random_particles(29, true, 4);
  c.particles.x[3](1) = -0.0;
  c.particles.v[4](0) = 4.9e-324;
  c.particles.stress[5](0, 1) = std::nextafter(1.0, 2.0);
  // F_p⁻¹ of failed material that flowed: present only when a material can flow.
  c.particles.plastic_inverse.assign(c.particles.size(), Mat<2>::Identity());
  c.particles.plastic_inverse[7] << 1.0 / 3.0, 0.25, -1e-300, 3.0;
  // The phase field's warm start, in the middle of a run of direct solves.
  c.phase_field.node = {IVec<2>(3, -4), IVec<2>(5, 6)};
  c.phase_field.field = {0, 2};
  c.phase_field.solution = {1.0 / 3.0, -1e-300};
  c.phase_field.direct_solves_left = 17;
  c.phase_field.direct_run = 128;
  c.phase_field.multigrid = 1;
  c.phase_field.average_iterations = 123.25;
  // The system the kept multigrid levels were built from, in compressed rows over the 2 unknowns.
  c.phase_field.levels_outer = {0, 2, 3};
  c.phase_field.levels_inner = {0, 1, 1};
  c.phase_field.levels_values = {2.0, -1e-300, 1.0 / 3.0};
  c.phase_field.levels_age = 4;
  c.phase_field.levels_cycles = 11;
  c.phase_field.last_cycles = 12;
  run.write_checkpoint(c);
  // A second checkpoint of the same size is written in place: the file does not grow.
  c.particles.x[0](0) += 1.0;
  run.write_checkpoint(c);
  const auto size_after_two = std::filesystem::file_size(path);
  c.particles.x[0](0) += 1.0;
  run.write_checkpoint(c);
  EXPECT_EQ(std::filesystem::file_size(path), size_after_two);

  const auto r = run.read_checkpoint();
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(std::memcmp(&r->time, &c.time, sizeof(double)), 0);
  EXPECT_EQ(r->step, c.step);
  for (double EnergyAccumulators::*m :
       {&EnergyAccumulators::wall_work, &EnergyAccumulators::gravity_work,
        &EnergyAccumulators::friction_work, &EnergyAccumulators::dissipated,
        &EnergyAccumulators::initial_energy, &EnergyAccumulators::fracture_energy})
    EXPECT_EQ(std::memcmp(&(r->totals.*m), &(c.totals.*m), sizeof(double)), 0);
  const Particles<2>& p = c.particles;
  const Particles<2>& q = r->particles;
  EXPECT_TRUE(same_bits_eigen(q.x, p.x));
  EXPECT_TRUE(same_bits_eigen(q.v, p.v));
  EXPECT_TRUE(same_bits_eigen(q.F, p.F));
  EXPECT_TRUE(same_bits_eigen(q.domain, p.domain));
  EXPECT_TRUE(same_bits_eigen(q.stress, p.stress));
  ASSERT_EQ(q.plastic_inverse.size(), p.plastic_inverse.size());
  EXPECT_TRUE(same_bits_eigen(q.plastic_inverse, p.plastic_inverse));
  EXPECT_TRUE(same_bits(q.volume0, p.volume0));
  EXPECT_TRUE(same_bits(q.mass, p.mass));
  EXPECT_TRUE(same_bits(q.damage, p.damage));
  EXPECT_TRUE(same_bits(q.damage_history, p.damage_history));
  EXPECT_TRUE(same_bits(q.strength, p.strength));
  EXPECT_TRUE(same_bits(q.temperature, p.temperature));
  EXPECT_EQ(q.surface, p.surface);
  EXPECT_EQ(q.body, p.body);
  EXPECT_EQ(q.material, p.material);
  EXPECT_EQ(r->phase_field.node, c.phase_field.node);
  EXPECT_EQ(r->phase_field.field, c.phase_field.field);
  EXPECT_TRUE(same_bits(r->phase_field.solution, c.phase_field.solution));
  EXPECT_EQ(r->phase_field.direct_solves_left, 17);
  EXPECT_EQ(r->phase_field.direct_run, 128);
  EXPECT_EQ(r->phase_field.multigrid, 1);
  EXPECT_EQ(r->phase_field.average_iterations, 123.25);
  EXPECT_EQ(r->phase_field.levels_outer, c.phase_field.levels_outer);
  EXPECT_EQ(r->phase_field.levels_inner, c.phase_field.levels_inner);
  EXPECT_TRUE(same_bits(r->phase_field.levels_values, c.phase_field.levels_values));
  EXPECT_EQ(r->phase_field.levels_age, 4);
  EXPECT_EQ(r->phase_field.levels_cycles, 11);
  EXPECT_EQ(r->phase_field.last_cycles, 12);

  // A system with a few more entries is written over the last one's space, not beside it.
  auto with_entries = [&](int entries) {
    c.phase_field.levels_outer = {0, entries - 1, entries};
    c.phase_field.levels_inner.assign(static_cast<std::size_t>(entries), 1);
    c.phase_field.levels_values.assign(static_cast<std::size_t>(entries), 0.5);
    run.write_checkpoint(c);
  };
  with_entries(1000);
  const auto size_with_1000 = std::filesystem::file_size(path);
  with_entries(1010);
  EXPECT_EQ(std::filesystem::file_size(path), size_with_1000);
  const auto grown = run.read_checkpoint();
  ASSERT_TRUE(grown.has_value());
  EXPECT_EQ(grown->phase_field.levels_values.size(), 1010u);
  EXPECT_EQ(grown->phase_field.levels_outer.back(), 1010);

  // The checkpoint survives closing and reopening the file.
  run = RunFile<2>::open_existing(path);
  const auto again = run.read_checkpoint();
  ASSERT_TRUE(again.has_value());
  EXPECT_TRUE(same_bits_eigen(again->particles.x, p.x));
  EXPECT_EQ(again->step, c.step);
}

SeriesRow<2> row(long long step) {
  SeriesRow<2> r;
  r.step = step;
  r.time = 1e-3 * static_cast<double>(step);
  r.dt = 1e-3;
  r.kinetic = 10.0 * static_cast<double>(step);
  r.strain = 0.5;
  r.totals.wall_work = 2.0 * static_cast<double>(step);
  r.balance_error = 1e-12;
  r.momentum = Vec<2>(static_cast<double>(step), -static_cast<double>(step));
  r.wall_force = {Vec<2>(0.0, 100.0 * static_cast<double>(step)), Vec<2>(0.0, -1.0)};
  r.wall_displacement = {Vec<2>(0.0, -1e-6 * static_cast<double>(step)), Vec<2>::Zero()};
  return r;
}

TEST(RunFile, CheckpointWithLevelsOutsideTheUnknownsIsRefused) {
  // The system the kept multigrid levels were built from must be compressed rows over the
  // warm start's unknowns: a column past them is named, not read into a solve.
  const std::string path = temp_path("checkpoint-levels");
  auto run = RunFile<2>::create(path, test_meta(), false);
  Checkpoint<2> c;
  c.particles = random_particles(5, false, 1);
  c.phase_field.node = {IVec<2>(0, 0), IVec<2>(1, 0)};
  c.phase_field.field = {0, 0};
  c.phase_field.solution = {1.0, 1.0};
  c.phase_field.levels_outer = {0, 1, 2};
  c.phase_field.levels_inner = {0, 2};  // unknown 2 of 2
  c.phase_field.levels_values = {1.0, 1.0};
  run.write_checkpoint(c);
  try {
    run.read_checkpoint();
    FAIL() << "a column outside the unknowns was accepted";
  } catch (const RunFileError& error) {
    EXPECT_NE(std::string(error.what()).find("phase_field_levels"), std::string::npos)
        << error.what();
  }
}

TEST(RunFile, SeriesAppendAndTruncate) {
  const std::string path = temp_path("series");
  {
    auto run = RunFile<2>::create(path, test_meta(), false);
    run.append_series({row(1), row(2), row(3)});
    run.append_series({row(4), row(5)});
    run.write_frame(0, 0.0, random_particles(4, false, 5), {});
    run.write_frame(2, 2e-3, random_particles(4, false, 6), {});
    run.write_frame(4, 4e-3, random_particles(4, false, 7), {});
    EXPECT_EQ(read_series(path, "step"), (std::vector<double>{1, 2, 3, 4, 5}));
    EXPECT_EQ(read_series(path, "kinetic"), (std::vector<double>{10, 20, 30, 40, 50}));
    EXPECT_EQ(read_series(path, "momentum"),
              (std::vector<double>{1, -1, 2, -2, 3, -3, 4, -4, 5, -5}));
    EXPECT_EQ(read_series(path, "wall_top_force"),
              (std::vector<double>{0, 100, 0, 200, 0, 300, 0, 400, 0, 500}));
    EXPECT_EQ(read_series(path, "wall_bottom_force").size(), 10u);
    EXPECT_EQ(read_series(path, "wall_bottom_displacement").size(), 10u);
    EXPECT_EQ(read_series(path, "wall_work"), (std::vector<double>{2, 4, 6, 8, 10}));

    run.truncate_after(3);
    EXPECT_EQ(read_series(path, "step"), (std::vector<double>{1, 2, 3}));
    EXPECT_EQ(read_series(path, "momentum"), (std::vector<double>{1, -1, 2, -2, 3, -3}));
    EXPECT_EQ(read_series(path, "wall_top_displacement").size(), 6u);
    EXPECT_EQ(run.frame_count(), 2);
    EXPECT_THROW(run.read_frame(2), RunFileError);

    // Appending after a truncation continues from the kept rows; the next frame reuses index 2.
    run.append_series({row(4)});
    EXPECT_EQ(read_series(path, "step"), (std::vector<double>{1, 2, 3, 4}));
    EXPECT_EQ(run.write_frame(4, 4e-3, random_particles(4, false, 8), {}), 2);
  }
  auto run = RunFile<2>::open_existing(path);
  EXPECT_EQ(run.frame_count(), 3);
  const RunMeta meta = run.meta();
  const RunMeta expected = test_meta();
  EXPECT_EQ(meta.scene_path, expected.scene_path);
  EXPECT_EQ(meta.scene_text, expected.scene_text);
  EXPECT_EQ(meta.wall_names, expected.wall_names);
  ASSERT_EQ(meta.modules.size(), expected.modules.size());
  for (std::size_t k = 0; k < meta.modules.size(); ++k) {
    EXPECT_EQ(meta.modules[k].module, expected.modules[k].module);
    EXPECT_EQ(meta.modules[k].active, expected.modules[k].active);
    EXPECT_EQ(meta.modules[k].reason, expected.modules[k].reason);
  }
  run.truncate_after(0);
  EXPECT_TRUE(read_series(path, "time").empty());
  EXPECT_EQ(run.frame_count(), 1);
}

TEST(RunFile, SeriesRowWithWrongWallCountIsRejected) {
  const std::string path = temp_path("series_walls");
  auto run = RunFile<2>::create(path, test_meta(), false);
  SeriesRow<2> r = row(1);
  r.wall_force.pop_back();
  EXPECT_THROW(run.append_series({r}), RunFileError);
}

TEST(RunFile, BadWallNamesAreRejected) {
  for (const std::vector<std::string>& walls :
       {std::vector<std::string>{"a/b"}, {"top", "top"}, {""}, {"two\nlines"}}) {
    RunMeta meta = test_meta();
    meta.wall_names = walls;
    EXPECT_THROW(RunFile<2>::create(temp_path("bad_wall"), meta, false), RunFileError);
  }
}

TEST(RunFile, CreateRefusesExistingFile) {
  const std::string path = temp_path("exists");
  { auto run = RunFile<2>::create(path, test_meta(), false); }
  try {
    auto again = RunFile<2>::create(path, test_meta(), false);
    FAIL() << "expected RunFileError";
  } catch (const RunFileError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  auto replaced = RunFile<2>::create(path, test_meta(), true);
  EXPECT_EQ(replaced.frame_count(), 0);
}

TEST(RunFile, MissingFrameIsNamed) {
  const std::string path = temp_path("missing_frame");
  auto run = RunFile<2>::create(path, test_meta(), false);
  run.write_frame(0, 0.0, random_particles(3, false, 9), {});
  try {
    run.read_frame(5);
    FAIL() << "expected RunFileError";
  } catch (const RunFileError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("/frames/000005"), std::string::npos) << what;
    EXPECT_NE(what.find(path), std::string::npos) << what;
  }
}

TEST(RunFile, OpenChecksDimensionAndFile) {
  const std::string path = temp_path("dimension");
  { auto run = RunFile<2>::create(path, test_meta(), false); }
  EXPECT_THROW(RunFile<3>::open_existing(path), RunFileError);
  EXPECT_THROW(RunFile<2>::open_existing(path + ".missing"), RunFileError);
  EXPECT_THROW(read_series(path, "no_such_series"), RunFileError);
}

TEST(RunFile, FailureIsRecordedInMeta) {
  const std::string path = temp_path("failure");
  auto run = RunFile<2>::create(path, test_meta(), false);
  run.write_failure("step 17: J = -0.2 at particle 3");
  const h5::File file = h5::File::open(path, false);
  const h5::Group meta = file.root().open_group("meta");
  EXPECT_EQ(meta.attribute_string("failure"), "step 17: J = -0.2 at particle 3");
  EXPECT_EQ(meta.attribute_int64("dimension"), 2);
  EXPECT_EQ(meta.attribute_string("unit_system"), "SI; 2D quantities per unit thickness");
}

TEST(RunFile, XdmfDescribesEveryFrame) {
  const std::string path = temp_path("xdmf");
  const std::string xmf = std::filesystem::path(path).replace_extension(".xmf").string();
  const std::string name = std::filesystem::path(path).filename().string();
  auto run = RunFile<2>::create(path, test_meta(), false);
  ASSERT_TRUE(std::filesystem::exists(xmf));
  std::string error;
  EXPECT_TRUE(balanced_xml(read_text(xmf), &error)) << error;
  for (int k = 0; k < 3; ++k)
    run.write_frame(10 * k, 0.1 * k, random_particles(6, true, 10 + k), {});
  const std::string text = read_text(xmf);
  EXPECT_TRUE(balanced_xml(text, &error)) << error;
  for (const char* frame : {"000000", "000001", "000002"})
    EXPECT_NE(text.find(name + ":/frames/" + std::string(frame) + "/x"), std::string::npos)
        << frame;
  EXPECT_EQ(count(text, "<Time "), 3u);
  EXPECT_EQ(count(text, "GeometryType=\"XY\""), 3u);
  EXPECT_EQ(count(text, "Dimensions=\"6 2\""), 3u);       // x
  EXPECT_EQ(count(text, "Dimensions=\"6 3\""), 3u * 3u);  // v, r1, r2 padded to 3 components
  EXPECT_EQ(count(text, name + ":/xdmf/point_ids"), 3u);  // Polyvertex connectivity
  EXPECT_EQ(count(text, "Name=\"F\" AttributeType=\"Tensor\""), 3u);
  EXPECT_EQ(count(text, "Dimensions=\"6 3 3\""), 3u * 2u);  // F, stress padded to 3 x 3
  EXPECT_EQ(count(text, name + ":/xdmf/frames/000001/stress"), 1u);
  EXPECT_EQ(count(text, "Name=\"temperature\""), 3u);
  // vectors, tensors, scalars (volume0, mass, damage, surface, body, material, temperature, id)
  EXPECT_EQ(count(text, "<Attribute "), 3u * (3u + 2u + 8u));

  run.truncate_after(10);
  const std::string truncated = read_text(xmf);
  EXPECT_TRUE(balanced_xml(truncated, &error)) << error;
  EXPECT_EQ(truncated.find("/frames/000002/"), std::string::npos);
  EXPECT_EQ(count(truncated, "<Time "), 2u);

  // A smaller frame takes the first N point ids through a hyperslab.
  run.write_frame(20, 0.2, random_particles(3, false, 20), {});
  const std::string smaller = read_text(xmf);
  EXPECT_TRUE(balanced_xml(smaller, &error)) << error;
  EXPECT_NE(smaller.find("Format=\"XML\">0 1 3</DataItem>"), std::string::npos);
  EXPECT_EQ(count(smaller, "<Time "), 3u);
}

TEST(RunFile, ThreeDimensionalRoundTrip) {
  const std::string path = temp_path("three_d");
  RunMeta meta = test_meta();
  meta.wall_names = {"floor"};
  auto run = RunFile<3>::create(path, meta, false);
  Checkpoint<3> c;
  c.step = 7;
  c.particles.resize(4);
  for (std::size_t p = 0; p < 4; ++p) {
    c.particles.x[p] = Vec<3>(1.0 / (p + 1.0), 2.0, 3.0);
    c.particles.domain[p] << 1, 2, 3, 4, 5, 6, 7, 8, 9.0 / (p + 1.0);
    c.particles.F[p] = Mat<3>::Identity() * (1.0 + 0.1 * static_cast<double>(p));
  }
  run.write_frame(7, 0.5, c.particles, {});
  run.write_checkpoint(c);
  const Particles<3> frame = run.read_frame(0);
  EXPECT_TRUE(same_bits_eigen(frame.x, c.particles.x));
  EXPECT_TRUE(same_bits_eigen(frame.F, c.particles.F));
  EXPECT_EQ(frame.domain[2].col(1), c.particles.domain[2].col(1));  // frames hold r1 and r2 only
  const auto r = run.read_checkpoint();
  ASSERT_TRUE(r.has_value());
  EXPECT_TRUE(same_bits_eigen(r->particles.domain, c.particles.domain));
  const std::string xmf = read_text(std::filesystem::path(path).replace_extension(".xmf").string());
  EXPECT_EQ(count(xmf, "GeometryType=\"XYZ\""), 1u);
  EXPECT_EQ(count(xmf, "AttributeType=\"Tensor\""), 2u);
}

}  // namespace
}  // namespace fragmpm::mpm
