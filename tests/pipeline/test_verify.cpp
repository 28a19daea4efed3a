// V1 (docs/verification.md): the bar's centre-of-mass velocity error against the closed form must
// fall with h at first order or better, for CPDI, linear and quadratic B-spline shape functions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>

#include "fragmpm/pipeline/verify.hpp"

using namespace fragmpm::pipeline;

TEST(VerifyBar, ErrorFallsAtFirstOrderOrBetter) {
  VerifyOptions options;
  options.quick = true;  // h = L/10, L/20, L/40
  const auto rows = verify_bar(options);
  ASSERT_EQ(rows.size(), 9u);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    // The B-spline's interpolant at the supported end is ⅛ of the first interior node's velocity,
    // not 0 (the wall holds the nodes on and behind its plane, and the basis reaches 1.5 cells):
    // the bar vibrates as if about h/4 longer. Measured 0.110, 0.050, 0.024 against 0.024,
    // 0.0099, 0.0044 for linear hats (docs/verification.md).
    const double bound = rows[i].variant == "bspline2" ? 0.12 : 0.03;
    EXPECT_LT(rows[i].error, bound) << rows[i].variant << " level " << rows[i].level;
    if (i > 0 && rows[i].variant == rows[i - 1].variant) {
      EXPECT_LT(rows[i].error, rows[i - 1].error);
      // Measured 1.31 and 1.16 for CPDI and linear, 1.14 and 1.07 for the B-spline.
      EXPECT_GT(observed_order(rows[i - 1], rows[i]), 0.9);
    }
  }
}

TEST(VerifyBar, ObservedOrderOfAnExactPowerLaw) {
  VerifyRow coarse, fine;
  coarse.cell_size = 0.2;
  fine.cell_size = 0.1;
  coarse.error = 0.08;
  fine.error = 0.02;
  EXPECT_NEAR(observed_order(coarse, fine), 2.0, 1e-12);
  fine.error = 0.0;
  EXPECT_TRUE(std::isnan(observed_order(coarse, fine)));
  // Same cell, halved time step (a study in Δt): the order is taken over Δt.
  fine.cell_size = coarse.cell_size;
  coarse.dt = 1e-6;
  fine.dt = 0.5e-6;
  fine.error = 0.04;
  EXPECT_NEAR(observed_order(coarse, fine), 1.0, 1e-12);
}

TEST(VerifyReport, TargetsDecidePassOrFail) {
  const std::string dir =
      (std::filesystem::temp_directory_path() / "fragmpm_test_verify_report").string();
  VerifyRow row{.case_name = std::string("case"),
                .variant = std::string("v"),
                .cell_size = 1e-3,
                .metric = std::string("metric"),
                .value = 1.05,
                .reference = 1.0,
                .error = 0.05};
  EXPECT_FALSE(row.has_target());
  EXPECT_TRUE(report_case(dir, "case", {row}));  // no target: nothing to miss
  row.target_low = 0.98;
  row.target_high = 1.02;
  EXPECT_TRUE(row.has_target());
  EXPECT_FALSE(row.passed());
  EXPECT_FALSE(report_case(dir, "case", {row}));
  row.value = 1.01;
  EXPECT_TRUE(report_case(dir, "case", {row}));
  VerifyRow below = row;
  below.target_high = std::numeric_limits<double>::infinity();
  below.value = 0.5;  // only a lower bound: 0.5 < 0.98 misses it
  EXPECT_FALSE(report_case(dir, "case", {row, below}));
}

// A run stopped short by --max-steps reports no rows: nothing is written, and the CSV of an
// earlier, finished invocation stays as it was.
TEST(VerifyReport, NoRowsWriteNothingAndKeepTheEarlierCsv) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / "fragmpm_test_verify_no_rows";
  std::filesystem::remove_all(dir);
  EXPECT_TRUE(report_case(dir.string(), "case", {}));
  EXPECT_FALSE(std::filesystem::exists(dir / "case.csv"));
  const VerifyRow row{.case_name = std::string("case"),
                      .variant = std::string("v"),
                      .metric = std::string("m"),
                      .value = 1.0,
                      .reference = 1.0,
                      .error = 0.0};
  EXPECT_TRUE(report_case(dir.string(), "case", {row}));
  const auto size = std::filesystem::file_size(dir / "case.csv");
  EXPECT_TRUE(report_case(dir.string(), "case", {}));
  EXPECT_EQ(std::filesystem::file_size(dir / "case.csv"), size);
}

// A comma in a row's name must not shift the CSV's columns: the error-versus-time figure reads the
// file back by splitting at commas (a plate-impact row's name once held one, and the figure was
// refused).
TEST(VerifyReport, CsvKeepsTwelveColumnsWhateverTheNames) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / "fragmpm_test_verify_commas";
  std::filesystem::remove_all(dir);
  const VerifyRow row{.case_name = std::string("case"),
                      .variant = std::string("a,b"),
                      .metric = std::string("angle (notch end to tip, before branching)"),
                      .value = 1.0,
                      .reference = 1.0,
                      .error = 0.0};
  EXPECT_TRUE(report_case(dir.string(), "case", {row}));
  std::ifstream csv(dir / "case.csv");
  std::string line;
  int lines = 0;
  while (std::getline(csv, line)) {
    ++lines;
    EXPECT_EQ(std::count(line.begin(), line.end(), ','), 11) << line;
  }
  EXPECT_EQ(lines, 2);
  std::filesystem::remove_all(dir);
}

// `--variant` / `--level`: a selection runs only what it names, keeps the full table's CSV, and
// refuses a name or level the case does not have.
TEST(VerifySelection, PicksNamedRunsAndRefusesUnknownOnes) {
  VerifyOptions options;
  EXPECT_TRUE(selected(options, "anything", 3));  // no selection: every run
  options.variants = {"b"};
  EXPECT_TRUE(selected(options, "b", 0));
  EXPECT_FALSE(selected(options, "a", 0));
  options.level = 1;
  EXPECT_TRUE(selected(options, "b", 1));
  EXPECT_FALSE(selected(options, "b", 0));
  EXPECT_NO_THROW(check_selection(options, "case", {"a", "b"}, 2));
  EXPECT_THROW(check_selection(options, "case", {"a", "b"}, 1), std::invalid_argument);
  options.level = -1;
  options.variants = {"c"};
  EXPECT_THROW(check_selection(options, "case", {"a", "b"}, 2), std::invalid_argument);

  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / "fragmpm_test_verify_selection";
  std::filesystem::remove_all(dir);
  const VerifyRow row{.case_name = std::string("case"),
                      .variant = std::string("b"),
                      .metric = std::string("metric"),
                      .value = 1.0,
                      .reference = 1.0,
                      .error = 0.0};
  EXPECT_TRUE(report_case(dir.string(), "case", {row}, "b-level1"));
  EXPECT_TRUE(std::filesystem::exists(dir / "case-b-level1.csv"));
  EXPECT_FALSE(std::filesystem::exists(dir / "case.csv"));
  std::filesystem::remove_all(dir);
}
