// `fragmpm analyze` end to end on tiny run files written with RunFile<2>: frame choice by time, by
// platen displacement and by index; the CSV tables, the /fragments/ groups and the count series;
// clear messages and exit code 2 on bad input.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../support/read_text.hpp"
#include "fragmpm/mpm/hdf5_io.hpp"
#include "fragmpm/mpm/run_file.hpp"

namespace fs = std::filesystem;
namespace fm = fragmpm::mpm;

using fragmpm::test_support::read_text;

namespace {

constexpr double kSpacing = 1e-4;

int run_fragmpm(const std::string& arguments, const fs::path& log) {
  const std::string command =
      std::string(FRAGMPM_BINARY) + " " + arguments + " > " + log.string() + " 2>&1";
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::vector<std::string> lines(const fs::path& path) {
  std::vector<std::string> out;
  std::istringstream in(read_text(path));
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) out.push_back(line);
  return out;
}

fs::path fresh_directory(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("fragmpm_analyze_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

/// A 20 x 21 block of particles; `cuts` = 0 intact, 1 masked middle row (2 fragments), 2 also a
/// masked column through the upper half (3 fragments). With `two_bodies` the ten right-hand
/// columns are body 1.
fm::Particles<2> block(int cuts, bool two_bodies = false) {
  fm::Particles<2> P;
  P.resize(20 * 21);
  std::size_t p = 0;
  for (int j = 0; j < 21; ++j)
    for (int i = 0; i < 20; ++i, ++p) {
      P.x[p] = {(i + 0.5) * kSpacing, (j + 0.5) * kSpacing};
      P.volume0[p] = kSpacing * kSpacing;
      P.mass[p] = 2650.0 * kSpacing * kSpacing;
      P.domain[p] = fm::Mat<2>::Identity() * kSpacing;
      if (cuts >= 1 && j == 10) P.damage[p] = 1.0;
      if (cuts >= 2 && j > 10 && i == 9) P.damage[p] = 1.0;
      if (two_bodies && i >= 10) P.body[p] = 1;
    }
  return P;
}

/// Run file with frames at t = 0, 10, 20 µs (0, 1, 2 cuts) and a platen that has moved 0, 0.1, 0.2
/// mm. Without `damage` the frames keep every field but damage.
std::string write_run(const fs::path& dir, bool damage = true, bool two_bodies = false) {
  const std::string path = (dir / "tiny.h5").string();
  fm::RunMeta meta;
  meta.scene_path = "tiny.toml";
  meta.scene_text = "# written by the test";
  meta.wall_names = {"floor", "platen"};
  auto file = fm::RunFile<2>::create(path, meta, true);
  std::vector<std::string> fields;
  for (const std::string& f : fm::all_frame_fields())
    if (f != "temperature" && (damage || f != "damage")) fields.push_back(f);
  std::vector<fm::SeriesRow<2>> rows;
  for (int k = 0; k < 3; ++k) {
    fm::SeriesRow<2> row;
    row.step = 100 * k;
    row.time = 10e-6 * k;
    row.wall_force = {fm::Vec<2>::Zero(), fm::Vec<2>::Zero()};
    row.wall_displacement = {fm::Vec<2>::Zero(), fm::Vec<2>(0.0, -1e-4 * k)};
    rows.push_back(row);
    file.write_frame(row.step, row.time, block(k, two_bodies), fields);
  }
  file.append_series(rows);
  return path;
}

}  // namespace

TEST(AnalyzeCommand, TablesSeriesAndRunFileGroups) {
  const fs::path dir = fresh_directory("tables");
  const std::string run = write_run(dir);
  const fs::path out = dir / "out";
  ASSERT_EQ(run_fragmpm("analyze " + run + " --at 10us,20us -o " + out.string(), dir / "log"), 0)
      << read_text(dir / "log");
  const std::string log = read_text(dir / "log");
  EXPECT_NE(log.find("--at 10us -> frame 1"), std::string::npos) << log;
  EXPECT_NE(log.find("--at 20us -> frame 2"), std::string::npos) << log;

  // Frame 1: two 200-particle halves; frame 2: the upper half cut in two (9 + 10 columns x 10
  // rows).
  auto table1 = lines(out / "fragments_000001.csv");
  ASSERT_EQ(table1.size(), 3u);
  EXPECT_EQ(table1[0].rfind("id,particles,area_m2,equivalent_diameter_m,roundness", 0), 0u)
      << table1[0];
  EXPECT_EQ(table1[1].rfind("0,200,", 0), 0u) << table1[1];
  EXPECT_EQ(table1[2].rfind("1,200,", 0), 0u) << table1[2];
  auto table2 = lines(out / "fragments_000002.csv");
  ASSERT_EQ(table2.size(), 4u);
  EXPECT_EQ(table2[1].rfind("0,200,", 0), 0u);
  EXPECT_EQ(table2[2].rfind("1,100,", 0), 0u);
  EXPECT_EQ(table2[3].rfind("2,90,", 0), 0u);
  EXPECT_EQ(lines(out / "fines_000002.csv").size(), 1u);  // header only
  EXPECT_EQ(lines(out / "cdf_equivalent_diameter_000002.csv").size(), 4u);

  // The count series covers every frame, with the platen travel.
  auto series = lines(out / "fragment_series.csv");
  ASSERT_EQ(series.size(), 4u);
  EXPECT_EQ(series[0].rfind("frame,step,time_s,platen_displacement_m,fragments,fines", 0), 0u)
      << series[0];
  EXPECT_EQ(series[1].rfind("0,0,0,0,1,0,", 0), 0u) << series[1];
  EXPECT_EQ(series[2].rfind("1,100,1e-05,0.0001,2,0,", 0), 0u) << series[2];
  EXPECT_EQ(series[3].rfind("2,200,2e-05,0.0002,3,0,", 0), 0u) << series[3];
  for (const char* png :
       {"cdf_equivalent_diameter.png", "cdf_roundness_mass.png", "fragment_count.png"})
    EXPECT_GT(fs::file_size(out / png), 1000u) << png;

  // The run file holds the same tables, with units.
  const fm::h5::File file = fm::h5::File::open(run, false);
  const fm::h5::Group g = file.root().open_group("fragments/000002");
  EXPECT_EQ(g.attribute_int64("fragments"), 3);
  EXPECT_EQ(g.attribute_string("platen"), "platen");
  EXPECT_DOUBLE_EQ(g.attribute_double("platen_displacement"), 2e-4);
  const auto area = g.read<double>("table/area");
  ASSERT_EQ(area.values.size(), 3u);
  EXPECT_NEAR(area.values[0], 200 * kSpacing * kSpacing, 1e-18);
  EXPECT_EQ(g.open_dataset("table/area").attribute_string("units"), "m^2 (per unit thickness)");
  const auto mass_cdf = g.read<double>("cdf/equivalent_diameter/mass_fraction").values;
  ASSERT_EQ(mass_cdf.size(), 3u);
  EXPECT_NEAR(mass_cdf[0], 90.0 / 390.0, 1e-12);
  EXPECT_EQ(mass_cdf.back(), 1.0);
  const auto ids = g.read<std::int32_t>("particle_fragment").values;
  EXPECT_EQ(ids.size(), 420u);
  EXPECT_EQ(std::count(ids.begin(), ids.end(), -1), 30);  // the masked row and half column
  EXPECT_EQ(file.root().read<std::int64_t>("fragments/series/fragments").values,
            (std::vector<std::int64_t>{1, 2, 3}));
}

TEST(AnalyzeCommand, ChoosesFramesByPlatenDisplacementAndSaysWhenItReplacesGroups) {
  const fs::path dir = fresh_directory("displacement");
  const std::string run = write_run(dir);
  ASSERT_EQ(run_fragmpm("analyze " + run + " --at-displacement 0.19mm --no-figures", dir / "log"),
            0)
      << read_text(dir / "log");
  EXPECT_NE(read_text(dir / "log").find("--at-displacement 0.19mm -> frame 2"), std::string::npos)
      << read_text(dir / "log");
  EXPECT_TRUE(fs::exists(dir / "tiny_fragments" / "fragments_000002.csv"));  // default directory
  // --at tells a displacement from a time by its unit; analysing frame 2 again replaces its group.
  ASSERT_EQ(run_fragmpm("analyze " + run + " --at 0.2mm --frame 0 --no-figures", dir / "log2"), 0)
      << read_text(dir / "log2");
  const std::string log = read_text(dir / "log2");
  EXPECT_NE(log.find("--at 0.2mm -> frame 2"), std::string::npos) << log;
  EXPECT_NE(log.find("--frame 0 -> frame 0"), std::string::npos) << log;
  EXPECT_NE(log.find("/fragments/000002 replaced the group of an earlier analyze"),
            std::string::npos)
      << log;
}

TEST(AnalyzeCommand, BodyAnalysesOneBodysFragmentsAlone) {
  const fs::path dir = fresh_directory("body");
  const std::string run = write_run(dir, true, true);
  const fs::path out = dir / "out";
  ASSERT_EQ(run_fragmpm("analyze " + run + " --frame last --body 1 --no-figures -o " + out.string(),
                        dir / "log"),
            0)
      << read_text(dir / "log");
  const std::string log = read_text(dir / "log");
  EXPECT_NE(log.find("fragments of body 1 only (210 of 420 particles)"), std::string::npos) << log;
  // The whole block has three fragments at frame 2 (200, 100 and 90 particles); the right-hand
  // body alone is cut by the masked row only, into two of 10 columns x 10 rows.
  const auto table = lines(out / "fragments_000002.csv");
  ASSERT_EQ(table.size(), 3u);
  EXPECT_EQ(table[1].rfind("0,100,", 0), 0u) << table[1];
  EXPECT_EQ(table[2].rfind("1,100,", 0), 0u) << table[2];
  const auto series = lines(out / "fragment_series.csv");
  ASSERT_EQ(series.size(), 4u);
  EXPECT_EQ(series[1].rfind("0,0,0,0,1,0,", 0), 0u) << series[1];
  EXPECT_EQ(series[3].rfind("2,200,2e-05,0.0002,2,0,", 0), 0u) << series[3];
  // particle_fragment still has a row per particle of the frame: the other body's are -2, the
  // masked row's ten particles of body 1 are -1.
  const fm::h5::File file = fm::h5::File::open(run, false);
  const auto ids = file.root().read<std::int32_t>("fragments/000002/particle_fragment").values;
  ASSERT_EQ(ids.size(), 420u);
  EXPECT_EQ(std::count(ids.begin(), ids.end(), -2), 210);
  EXPECT_EQ(std::count(ids.begin(), ids.end(), -1), 10);
  // A body the run does not have is refused, naming those it has.
  EXPECT_EQ(run_fragmpm("analyze " + run + " --body 5 --no-figures", dir / "log"), 2);
  EXPECT_NE(read_text(dir / "log")
                .find("--body 5: no particle of that body in frame 0; the run's bodies are 0, 1"),
            std::string::npos)
      << read_text(dir / "log");
}

TEST(AnalyzeCommand, RunFileWithoutDamageDataExitsWith2) {
  const fs::path dir = fresh_directory("nodamage");
  const std::string run = write_run(dir, false);
  EXPECT_EQ(run_fragmpm("analyze " + run, dir / "log"), 2);
  const std::string log = read_text(dir / "log");
  EXPECT_NE(log.find("no 'damage' dataset"), std::string::npos) << log;
  EXPECT_NE(log.find(run), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(fs::path(dir) / "tiny_fragments" / "fragment_series.csv"));
}

TEST(AnalyzeCommand, FrameThatDoesNotExistExitsWith2) {
  const fs::path dir = fresh_directory("noframe");
  const std::string run = write_run(dir);
  EXPECT_EQ(run_fragmpm("analyze " + run + " --frame 7", dir / "log"), 2);
  std::string log = read_text(dir / "log");
  EXPECT_NE(log.find("no frame 7"), std::string::npos) << log;
  EXPECT_NE(log.find("3 frames"), std::string::npos) << log;
  EXPECT_EQ(run_fragmpm("analyze " + run + " --at 5ms", dir / "log"), 2);
  log = read_text(dir / "log");
  EXPECT_NE(log.find("no frame near t = 5 ms"), std::string::npos) << log;
  EXPECT_EQ(run_fragmpm("analyze " + run + " --at-displacement 3mm", dir / "log"), 2);
  EXPECT_NE(read_text(dir / "log").find("no frame near platen displacement 3 mm"),
            std::string::npos)
      << read_text(dir / "log");
}

TEST(AnalyzeCommand, OtherBadInputExitsWith2WithAMessage) {
  const fs::path dir = fresh_directory("bad");
  const std::string run = write_run(dir);
  struct Case {
    std::string arguments, message;
  };
  { std::ofstream(dir / "notes.h5") << "not an HDF5 file"; }
  { fm::h5::File::create((dir / "other.h5").string(), true).root().require_group("data"); }
  const Case cases[] = {
      {"analyze " + (dir / "missing.h5").string(), "missing.h5: no such file"},
      {"analyze " + (dir / "notes.h5").string(), "not a FragMPM run file"},
      {"analyze " + (dir / "other.h5").string(), "not a FragMPM run file (no /meta group)"},
      {"analyze " + run + " --platen top",
       "--platen 'top': the run has no such wall (its walls: floor, platen)"},
      {"analyze " + run + " --at 20", "--at '20': give a unit"},
      {"analyze " + run + " --at 20kg", "--at '20kg': expected a time"},
      {"analyze " + run + " --frame x", "--frame 'x': expected a frame index"},
      {"analyze " + run + " --d-mask 1.5", "d_mask must be in (0, 1]"},
      {"analyze " + run + " --min-particles 0", "at least 1"},
  };
  for (const Case& c : cases) {
    EXPECT_EQ(run_fragmpm(c.arguments, dir / "log"), 2) << c.arguments << "\n"
                                                        << read_text(dir / "log");
    EXPECT_NE(read_text(dir / "log").find(c.message), std::string::npos) << c.arguments << "\n"
                                                                         << read_text(dir / "log");
  }
}

TEST(AnalyzeCommand, RefusesToReplaceAGroupItDidNotWrite) {
  const fs::path dir = fresh_directory("foreign");
  const std::string run = write_run(dir);
  {
    const fm::h5::File file = fm::h5::File::open(run, true);
    file.root().require_group("fragments/000002").set_attribute("note", "a user's own analysis");
  }
  EXPECT_EQ(run_fragmpm("analyze " + run + " --frame last --no-figures", dir / "log"), 2);
  EXPECT_NE(read_text(dir / "log")
                .find("/fragments/000002 exists and was not written by fragmpm analyze"),
            std::string::npos)
      << read_text(dir / "log");
  const fm::h5::File file = fm::h5::File::open(run, false);
  EXPECT_EQ(file.root().open_group("fragments/000002").attribute_string("note"),
            "a user's own analysis");
  // --csv-only leaves the run file alone and still writes the tables.
  EXPECT_EQ(run_fragmpm("analyze " + run + " --frame last --no-figures --csv-only", dir / "log"), 0)
      << read_text(dir / "log");
  EXPECT_TRUE(fs::exists(dir / "tiny_fragments" / "fragments_000002.csv"));
}
