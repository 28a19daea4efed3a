// `fragmpm run` end to end: exit codes for bad input and numerical failure, refusal to overwrite,
// the run file's contents, and a restart that reproduces an uninterrupted run bit for bit.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "../support/departure_scene.hpp"
#include "../support/read_text.hpp"
#include "../support/run_file_checks.hpp"
#include "fragmpm/mpm/run_file.hpp"

namespace fs = std::filesystem;
using namespace fragmpm;

using fragmpm::test_support::expect_series_identical;
using fragmpm::test_support::fresh_directory;
using fragmpm::test_support::read_text;

namespace {

int run_fragmpm(const std::string& arguments, const std::string& log) {
  const std::string command = std::string(FRAGMPM_BINARY) + " " + arguments + " > " + log + " 2>&1";
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

const std::string disk_bounce = std::string(FRAGMPM_SOURCE_DIR) + "/scenes/disk-bounce.toml";

}  // namespace

TEST(RunCommand, WritesRunFileWithFramesSeriesAndXdmf) {
  const fs::path dir = fresh_directory("run");
  const std::string out = (dir / "bounce.h5").string();
  ASSERT_EQ(run_fragmpm("run " + disk_bounce + " -o " + out + " --max-steps 400 -q",
                        (dir / "log").string()),
            0)
      << read_text((dir / "log").string());
  auto file = mpm::RunFile<2>::open_existing(out);
  EXPECT_GE(file.frame_count(), 2);
  const auto time = mpm::read_series(out, "time");
  EXPECT_EQ(time.size(), 401u);  // the initial state and 400 steps
  EXPECT_TRUE(fs::exists(dir / "bounce.xmf"));
  EXPECT_NE(file.meta().scene_text.find("disk"), std::string::npos);
  const std::string log = read_text((dir / "log").string());
  EXPECT_NE(log.find("module thermal"), std::string::npos) << "the log says which modules run";
  EXPECT_NE(log.find("end state: largest J = det F "), std::string::npos) << log;
}

TEST(RunCommand, RefusesToOverwriteAnExistingRunFile) {
  const fs::path dir = fresh_directory("overwrite");
  const std::string out = (dir / "bounce.h5").string();
  { std::ofstream(out) << "a user's file"; }
  EXPECT_EQ(run_fragmpm("run " + disk_bounce + " -o " + out + " -q", (dir / "log").string()), 2);
  EXPECT_EQ(read_text(out), "a user's file");
  EXPECT_NE(read_text((dir / "log").string()).find(out), std::string::npos);
}

TEST(RunCommand, BadSceneExitsWithCode2AndNamesTheLine) {
  const fs::path dir = fresh_directory("bad");
  const std::string scene = (dir / "bad.toml").string();
  std::string text = read_text(disk_bounce);
  text.replace(text.find("E = \"10 MPa\""), 12, "E = \"10 m\"");
  { std::ofstream(scene) << text; }
  EXPECT_EQ(run_fragmpm("run " + scene + " -o " + (dir / "x.h5").string(), (dir / "log").string()),
            2);
  const std::string log = read_text((dir / "log").string());
  EXPECT_NE(log.find("bad.toml:"), std::string::npos) << log;
  EXPECT_NE(log.find("E"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(dir / "x.h5"));
  EXPECT_EQ(run_fragmpm("run " + (dir / "missing.toml").string(), (dir / "log2").string()), 2);
}

TEST(RunCommand, NumericalFailureExitsWithCode3AndKeepsFrames) {
  // A fixed Δt just below the CFL = 1 limit of the initial state (5.8 μs) is accepted, but the disk
  // speeds up under a huge gravity until the step is unstable: the run must stop with a diagnostic.
  const fs::path dir = fresh_directory("fail");
  const std::string scene = (dir / "unstable.toml").string();
  std::string text = read_text(disk_bounce);
  text.replace(text.find("cfl = 0.4"), 9, "cfl = 1.0\ndt = \"5.5 us\"");
  text.replace(text.find("\"-9.81 m/s2\""), 12, "\"-9.81e7 m/s2\"");
  { std::ofstream(scene) << text; }
  const std::string out = (dir / "unstable.h5").string();
  EXPECT_EQ(run_fragmpm("run " + scene + " -o " + out + " -q", (dir / "log").string()), 3)
      << read_text((dir / "log").string());
  auto file = mpm::RunFile<2>::open_existing(out);
  EXPECT_GE(file.frame_count(), 1);  // the initial frame at least
  EXPECT_NE(read_text((dir / "log").string()).find("particle"), std::string::npos);
}

/// Runs `scene` into `parts` stopped after `stop_step` steps, then continues it with --restart
/// from the checkpoint.
void run_stopped_and_restarted(const fs::path& dir, const std::string& scene,
                               const std::string& parts, long long stop_step) {
  ASSERT_EQ(
      run_fragmpm("run " + scene + " -o " + parts + " -q --max-steps " + std::to_string(stop_step),
                  (dir / "log2").string()),
      0);
  ASSERT_EQ(run_fragmpm("run --restart " + parts + " -q", (dir / "log3").string()), 0)
      << read_text((dir / "log3").string());
}

/// Runs `scene` to its end into DIR/whole.h5, and into DIR/parts.h5 stopped after `stop_step`
/// steps and restarted.
void run_whole_and_restarted(const fs::path& dir, const std::string& scene, long long stop_step) {
  ASSERT_EQ(run_fragmpm("run " + scene + " -o " + (dir / "whole.h5").string() + " -q",
                        (dir / "log1").string()),
            0)
      << read_text((dir / "log1").string());
  run_stopped_and_restarted(dir, scene, (dir / "parts.h5").string(), stop_step);
}

/// The series `name` of two run files agrees bit for bit.
/// Runs the disk bounce to 4 ms whole and in two parts (stopped at step 517, restarted from the
/// checkpoint) and checks that the last frames and the series agree bit for bit.
void expect_restart_bit_identical(const std::string& name, bool apic) {
  const fs::path dir = fresh_directory(name);
  const std::string whole = (dir / "whole.h5").string(), parts = (dir / "parts.h5").string();
  const std::string scene = (dir / "short.toml").string();
  std::string text = read_text(disk_bounce);
  text.replace(text.find("end_time = \"20 ms\""), 18, "end_time = \"4 ms\"");
  // APIC carries C_p across the restart in the checkpoint.
  if (apic) text.replace(text.find("cfl = 0.4"), 9, "cfl = 0.4\ntransfer = \"apic\"");
  { std::ofstream(scene) << text; }
  ASSERT_NO_FATAL_FAILURE(run_whole_and_restarted(dir, scene, 517));
  auto a = mpm::RunFile<2>::open_existing(whole);
  auto b = mpm::RunFile<2>::open_existing(parts);
  double time_a = 0, time_b = 0;
  long long step_a = 0, step_b = 0;
  const auto pa = a.read_frame(a.frame_count() - 1, &time_a, &step_a);
  const auto pb = b.read_frame(b.frame_count() - 1, &time_b, &step_b);
  EXPECT_EQ(step_a, step_b);
  EXPECT_EQ(std::memcmp(&time_a, &time_b, sizeof(double)), 0);
  ASSERT_EQ(pa.size(), pb.size());
  EXPECT_EQ(std::memcmp(pa.x.data(), pb.x.data(), pa.size() * sizeof(pa.x[0])), 0);
  EXPECT_EQ(std::memcmp(pa.v.data(), pb.v.data(), pa.size() * sizeof(pa.v[0])), 0);
  EXPECT_EQ(std::memcmp(pa.stress.data(), pb.stress.data(), pa.size() * sizeof(pa.stress[0])), 0);
  for (const char* series : {"kinetic", "angular_momentum"})
    expect_series_identical(whole, parts, series);
}

// The phase field resumes from the checkpoint's d and history: the next solve starts from the same
// particles and the same guess, and the crack energy (a state the checkpoint keeps) is restored.
TEST(RunCommand, PhaseFieldRestartReproducesUninterruptedRunBitForBit) {
  const fs::path dir = fresh_directory("restart-phase-field");
  const std::string whole = (dir / "whole.h5").string(), parts = (dir / "parts.h5").string();
  const std::string scene = (dir / "bar.toml").string();
  std::string text =
      read_text(std::string(FRAGMPM_SOURCE_DIR) + "/scenes/verify/phase-field-bar.toml");
  const std::string cell = "cell_size = \"0.25 mm\"", end = "end_time = \"30 us\"";
  text.replace(text.find(cell), cell.size(), "cell_size = \"0.5 mm\"");
  text.replace(text.find(end), end.size(), "end_time = \"12 us\"");
  { std::ofstream(scene) << text; }
  ASSERT_NO_FATAL_FAILURE(run_whole_and_restarted(dir, scene, 150));
  auto a = mpm::RunFile<2>::open_existing(whole);
  auto b = mpm::RunFile<2>::open_existing(parts);
  const auto pa = a.read_frame(a.frame_count() - 1);
  const auto pb = b.read_frame(b.frame_count() - 1);
  ASSERT_EQ(pa.size(), pb.size());
  EXPECT_EQ(std::memcmp(pa.damage.data(), pb.damage.data(), pa.size() * sizeof(double)), 0);
  EXPECT_EQ(std::memcmp(pa.stress.data(), pb.stress.data(), pa.size() * sizeof(pa.stress[0])), 0);
  EXPECT_GT(mpm::read_series(whole, "fracture_energy").back(), 0.0);  // cracked by 12 µs
  for (const char* series : {"fracture_energy", "balance_error"})
    expect_series_identical(whole, parts, series);
}

TEST(RunCommand, RestartReproducesUninterruptedRunBitForBit) {
  expect_restart_bit_identical("restart", false);
}

TEST(RunCommand, RestartReproducesUninterruptedApicRunBitForBit) {
  expect_restart_bit_identical("restart-apic", true);
}

// A softening particle books the mean of ψ_t over each step, so its next release starts from the
// ψ_t the last step ended with (constitutive_update.hpp). A restart recomputes that value from the
// checkpointed F and d; stopped at step 517, in the middle of the pulled bar's softening (damage
// dissipation grows from step 420 to 840), the run must book the same dissipation, bit for bit.
TEST(RunCommand, RestartInTheMiddleOfSofteningReproducesTheDissipationBitForBit) {
  const fs::path dir = fresh_directory("restart-softening");
  const std::string whole = (dir / "whole.h5").string(), parts = (dir / "parts.h5").string();
  const std::string scene = std::string(FRAGMPM_SOURCE_DIR) + "/scenes/verify/bar-tension.toml";
  ASSERT_NO_FATAL_FAILURE(run_whole_and_restarted(dir, scene, 517));
  for (const char* series : {"dissipated", "balance_error", "kinetic"})
    expect_series_identical(whole, parts, series);
  // The stop fell inside the softening: some dissipation before it, more than as much after.
  const auto steps = mpm::read_series(whole, "step");
  const auto dissipated = mpm::read_series(whole, "dissipated");
  std::size_t stop = 0;
  while (stop < steps.size() && steps[stop] < 517.0) ++stop;
  ASSERT_LT(stop, steps.size());
  EXPECT_GT(dissipated[stop], 0.0);
  EXPECT_GT(dissipated.back(), 2.0 * dissipated[stop]);
}

namespace {

// A one-particle pellet flying out of the domain at 100 m/s (it leaves at step 950 of 0.05 µs)
// beside a block pushed by a traction; `[grid] outside = "remove"` takes it out of the run.
const std::string departure_scene =
    test_support::departure_scene("30 mm", "remove", 1100, "[output]\ninterval = \"20 us\"\n");

}  // namespace

TEST(RunCommand, RestartAcrossARemovalReproducesUninterruptedRunBitForBit) {
  const fs::path dir = fresh_directory("departure");
  const std::string scene = (dir / "departure.toml").string();
  { std::ofstream(scene) << departure_scene; }
  const std::string whole = (dir / "whole.h5").string();
  ASSERT_EQ(run_fragmpm("run " + scene + " -o " + whole + " -q", (dir / "log").string()), 0)
      << read_text((dir / "log").string());
  const std::string log = read_text((dir / "log").string());
  EXPECT_NE(log.find("left the domain and removed: 1 particles"), std::string::npos) << log;
  const auto lost_mass = mpm::read_series(whole, "lost_mass");
  ASSERT_EQ(lost_mass.size(), 1101u);
  EXPECT_EQ(lost_mass.front(), 0.0);
  {
    auto file = mpm::RunFile<2>::open_existing(whole);
    const auto first = file.read_frame(0), last = file.read_frame(file.frame_count() - 1);
    EXPECT_EQ(lost_mass.back(), first.mass[0]);  // the pellet, ρ s² = 1.95 g/m
    EXPECT_NEAR(first.mass[0], 7800.0 * 0.5e-3 * 0.5e-3, 1e-15);
    ASSERT_EQ(last.size() + 1, first.size());
    EXPECT_EQ(last.id.front(), 1);  // the block's particles, renumbered, keep their step-0 index
    EXPECT_EQ(last.id.back(), static_cast<std::int32_t>(first.size() - 1));
  }
  // Stopped before the removal (step 517) and after it (step 1000), then restarted.
  for (const long long split : {517LL, 1000LL}) {
    const std::string parts = (dir / ("parts" + std::to_string(split) + ".h5")).string();
    ASSERT_NO_FATAL_FAILURE(run_stopped_and_restarted(dir, scene, parts, split));
    auto a = mpm::RunFile<2>::open_existing(whole);
    auto b = mpm::RunFile<2>::open_existing(parts);
    const auto pa = a.read_frame(a.frame_count() - 1);
    const auto pb = b.read_frame(b.frame_count() - 1);
    ASSERT_EQ(pa.size(), pb.size()) << split;
    EXPECT_EQ(pa.id, pb.id) << split;
    EXPECT_EQ(std::memcmp(pa.x.data(), pb.x.data(), pa.size() * sizeof(pa.x[0])), 0) << split;
    EXPECT_EQ(std::memcmp(pa.v.data(), pb.v.data(), pa.size() * sizeof(pa.v[0])), 0) << split;
    EXPECT_EQ(std::memcmp(pa.stress.data(), pb.stress.data(), pa.size() * sizeof(pa.stress[0])), 0)
        << split;
    for (const char* series :
         {"kinetic", "balance_error", "lost_mass", "lost_kinetic", "lost_momentum", "load_work"}) {
      const auto ka = mpm::read_series(whole, series), kb = mpm::read_series(parts, series);
      ASSERT_EQ(ka.size(), kb.size()) << series << " " << split;
      EXPECT_EQ(std::memcmp(ka.data(), kb.data(), ka.size() * sizeof(double)), 0)
          << series << " " << split;
    }
  }
  // The fragment analysis matches the remaining particles to the first frame by id and counts the
  // one that left.
  ASSERT_EQ(run_fragmpm(
                "analyze " + whole + " --csv-only --no-figures -o " + (dir / "fragments").string(),
                (dir / "log4").string()),
            0)
      << read_text((dir / "log4").string());
  const std::string table = read_text(dir / "fragments" / "fragment_series.csv");
  EXPECT_NE(table.find("departed_particles"), std::string::npos) << table;
  const std::string last_line =
      table.substr(table.rfind('\n', table.size() - 2) + 1);  // the last frame, after the removal
  EXPECT_NE(last_line.find(",1,0.00195"), std::string::npos) << table;
}

TEST(BenchCommand, UnknownRowOfTheDamageLawComparisonExitsWithCode2) {
  // `fragmpm bench --law` names rows of the comparison by their label; a label that is none of
  // them is refused before anything runs, with the labels there are.
  const fs::path dir = fresh_directory("bench-law");
  EXPECT_EQ(run_fragmpm("bench --law \"pf cubic\" --threads 1", (dir / "log").string()), 2);
  const std::string log = read_text((dir / "log").string());
  EXPECT_NE(log.find("--law \"pf cubic\" is not a row"), std::string::npos) << log;
  EXPECT_NE(log.find("\"pf cubic, multigrid\""), std::string::npos) << log;
}
