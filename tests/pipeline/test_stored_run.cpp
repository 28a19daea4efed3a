// A verification run kept in a run file (the plate-impact runs at the paper's cell): stopped after
// some steps and continued by the same call, it ends bit for bit where the uninterrupted run ends;
// a file that holds another scene's run, or no run at all, is refused and left as it was.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "../support/read_text.hpp"
#include "../support/run_file_checks.hpp"
#include "fragmpm/mpm/run_file.hpp"
#include "fragmpm/pipeline/scene.hpp"
#include "fragmpm/pipeline/stored_run.hpp"

namespace fs = std::filesystem;
using namespace fragmpm;
using fragmpm::test_support::expect_series_identical;
using fragmpm::test_support::fresh_directory;
using fragmpm::test_support::read_text;

namespace {

/// The pulled phase-field bar at h = 0.5 mm to `end` (it cracks by 12 µs).
std::string bar_scene(const std::string& end) {
  std::string text =
      read_text(std::string(FRAGMPM_SOURCE_DIR) + "/scenes/verify/phase-field-bar.toml");
  const std::string cell = "cell_size = \"0.25 mm\"", end_time = "end_time = \"30 us\"";
  text.replace(text.find(cell), cell.size(), "cell_size = \"0.5 mm\"");
  text.replace(text.find(end_time), end_time.size(), "end_time = \"" + end + "\"");
  return text;
}

mpm::Solver<2> bar_solver(const std::string& text) {
  return mpm::Solver<2>(pipeline::parse_scene(text, "phase-field-bar.toml"));
}

}  // namespace

TEST(StoredRun, StoppedAndContinuedEndsBitForBitWhereTheWholeRunEnds) {
  const fs::path dir = fresh_directory("stored-run");
  const std::string whole = (dir / "whole.h5").string(),
                    parts = (dir / "parts" / "run.h5").string();
  const std::string text = bar_scene("12 us");
  long long steps = 0;
  {
    mpm::Solver<2> solver = bar_solver(text);
    const pipeline::StoredRun run = pipeline::run_stored(solver, whole, 0, "whole");
    EXPECT_TRUE(run.finished);
    steps = run.steps;
    EXPECT_GT(run.largest_dt, 0.0);
  }
  ASSERT_GT(steps, 140);
  {  // the folder is created; 70 steps, then a stop with a checkpoint
    mpm::Solver<2> solver = bar_solver(text);
    const pipeline::StoredRun run = pipeline::run_stored(solver, parts, 70, "parts");
    EXPECT_FALSE(run.finished);
    EXPECT_EQ(run.steps, 70);
  }
  {  // 70 more
    mpm::Solver<2> solver = bar_solver(text);
    const pipeline::StoredRun run = pipeline::run_stored(solver, parts, 70, "parts");
    EXPECT_FALSE(run.finished);
    EXPECT_EQ(run.steps, 140);
  }
  {  // to the end
    mpm::Solver<2> solver = bar_solver(text);
    const pipeline::StoredRun run = pipeline::run_stored(solver, parts, 0, "parts");
    EXPECT_TRUE(run.finished);
    EXPECT_EQ(run.steps, steps);
  }
  const auto time = mpm::read_series(parts, "time");
  ASSERT_EQ(time.size(), static_cast<std::size_t>(steps) + 1);  // one row a step, none twice
  EXPECT_GT(mpm::read_series(parts, "fracture_energy").back(), 0.0);
  for (const char* series : {"fracture_energy", "strain", "balance_error"})
    expect_series_identical(whole, parts, series);
  {  // a finished run is reopened, not run again
    mpm::Solver<2> solver = bar_solver(text);
    const pipeline::StoredRun run = pipeline::run_stored(solver, parts, 0, "parts");
    EXPECT_TRUE(run.finished);
    EXPECT_EQ(run.steps, steps);
    EXPECT_EQ(mpm::read_series(parts, "time").size(), time.size());
  }
}

TEST(StoredRun, RefusesAFileOfAnotherSceneOrNoRunAndLeavesItAsItWas) {
  const fs::path dir = fresh_directory("stored-run-refused");
  const std::string path = (dir / "run.h5").string();
  {
    mpm::Solver<2> solver = bar_solver(bar_scene("12 us"));
    pipeline::run_stored(solver, path, 20, "first");
  }
  const std::string before = read_text(path);
  mpm::Solver<2> other = bar_solver(bar_scene("14 us"));
  try {
    pipeline::run_stored(other, path, 20, "other");
    FAIL() << "a run file of another scene was continued";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("another scene"), std::string::npos) << e.what();
  }
  EXPECT_EQ(read_text(path), before);
  const std::string user_file = (dir / "notes.h5").string();
  { std::ofstream(user_file) << "a user's notes"; }
  mpm::Solver<2> solver = bar_solver(bar_scene("12 us"));
  EXPECT_THROW(pipeline::run_stored(solver, user_file, 20, "notes"), std::invalid_argument);
  EXPECT_EQ(read_text(user_file), "a user's notes");
}
