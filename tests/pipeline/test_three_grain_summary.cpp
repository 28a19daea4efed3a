// The three-grain case's per-frame measures of the top grain (verify_three_grain.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "fragmpm/pipeline/verify_three_grain.hpp"

namespace fa = fragmpm::analysis;
namespace fp = fragmpm::pipeline;

namespace {

fa::FragmentStatistics fragment(double diameter, double roundness) {
  fa::FragmentStatistics f;
  f.equivalent_diameter = diameter;
  f.roundness = roundness;
  return f;
}

}  // namespace

TEST(ThreeGrainSummary, MeansLargestAndSampleDeviationOverResolvedFragments) {
  fa::FrameFragments frame;
  frame.fragments = {fragment(1e-3, 0.5), fragment(2e-3, 0.7), fragment(3e-3, 0.9)};
  frame.fines = {fragment(1e-5, 1.0), fragment(2e-5, 1.0)};
  fp::ThreeGrainSample s;
  s.peak_force = 12.0;  // not a fragment column: kept
  fp::summarize_top_grain(frame, s);
  EXPECT_EQ(s.fragments, 3);
  EXPECT_EQ(s.fines, 2);
  EXPECT_NEAR(s.mean_diameter, 2e-3, 1e-15);
  EXPECT_NEAR(s.largest_diameter, 3e-3, 1e-15);
  EXPECT_NEAR(s.diameter_deviation, 1e-3, 1e-15);  // (1 + 0 + 1)/(3 − 1) mm² → 1 mm
  EXPECT_NEAR(s.mean_roundness, 0.7, 1e-12);
  EXPECT_EQ(s.peak_force, 12.0);
}

TEST(ThreeGrainSummary, OneFragmentHasNoSpreadAndNoneGivesZeros) {
  fa::FrameFragments one;
  one.fragments = {fragment(5e-3, 0.8)};
  fp::ThreeGrainSample s;
  fp::summarize_top_grain(one, s);
  EXPECT_EQ(s.fragments, 1);
  EXPECT_EQ(s.diameter_deviation, 0.0);
  EXPECT_EQ(s.largest_diameter, 5e-3);
  fp::summarize_top_grain(fa::FrameFragments{}, s);
  EXPECT_EQ(s.fragments, 0);
  EXPECT_EQ(s.mean_diameter, 0.0);
  EXPECT_EQ(s.largest_diameter, 0.0);
  EXPECT_EQ(s.mean_roundness, 0.0);
}

TEST(ThreeGrainSummary, CsvHasOneRowPerSample) {
  const auto path = std::filesystem::temp_directory_path() / "fragmpm_three_grain_summary.csv";
  fp::ThreeGrainSample a, b;
  a.variant = "8 m/s";
  a.displacement = 0.2e-3;
  b.variant = "8 m/s";
  b.displacement = 0.8e-3;
  fp::write_three_grain_summary(path.string(), {a, b});
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line.rfind("variant,platen_speed_m_s,displacement_m,", 0), 0u) << line;
  EXPECT_NE(line.find("largest_temperature_rise_K"), std::string::npos);
  int rows = 0;
  while (std::getline(in, line)) ++rows;
  EXPECT_EQ(rows, 2);
}
