// Quantity strings → SI: exact conversions from the definitions of the units, and refusals that
// name the expected kind.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "fragmpm/pipeline/units.hpp"

namespace fp = fragmpm::pipeline;
using K = fp::QuantityKind;

namespace {

std::string error_of(const std::string& text, K kind) {
  try {
    fp::parse_quantity(text, kind);
  } catch (const fp::UnitError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(Units, BareNumbersAreSI) {
  EXPECT_DOUBLE_EQ(fp::parse_quantity("0.001", K::length), 0.001);
  EXPECT_DOUBLE_EQ(fp::parse_quantity("  7e9 ", K::pressure), 7e9);
  EXPECT_DOUBLE_EQ(fp::parse_quantity("-9.81", K::acceleration), -9.81);
  EXPECT_DOUBLE_EQ(fp::parse_quantity("+3", K::time), 3.0);
}

TEST(Units, ExamplesFromTheDesign) {
  EXPECT_DOUBLE_EQ(fp::parse_quantity("50 GPa", K::pressure), 50e9);
  EXPECT_DOUBLE_EQ(fp::parse_quantity("0.1 mm", K::length), 1e-4);
  EXPECT_DOUBLE_EQ(fp::parse_quantity("2.3 g/cm3", K::density), 2300.0);
  EXPECT_DOUBLE_EQ(fp::parse_quantity("250 us", K::time), 2.5e-4);
  EXPECT_DOUBLE_EQ(fp::parse_quantity("800 C", K::temperature), 1073.15);
  EXPECT_DOUBLE_EQ(fp::parse_quantity("300 K", K::temperature), 300.0);
  EXPECT_DOUBLE_EQ(fp::parse_quantity("1e-7 s", K::time), 1e-7);
  EXPECT_DOUBLE_EQ(fp::parse_quantity("10 m/s", K::velocity), 10.0);
  EXPECT_DOUBLE_EQ(fp::parse_quantity("9.81 m/s2", K::acceleration), 9.81);
  EXPECT_DOUBLE_EQ(fp::parse_quantity("1 kHz", K::frequency), 1000.0);
  EXPECT_DOUBLE_EQ(fp::parse_quantity("3 rad/s", K::angular_velocity), 3.0);
  EXPECT_DOUBLE_EQ(fp::parse_quantity("800 J/(kg K)", K::specific_heat), 800.0);
  EXPECT_DOUBLE_EQ(fp::parse_quantity("1.5 W/(m K)", K::conductivity), 1.5);
}

TEST(Units, EquivalentSpellings) {
  // One density written five ways: 2300 kg/m3.
  for (const char* s :
       {"2300 kg/m3", "2300 kg/m^3", "2.3 g/cm^3", "2.3 g cm^-3", "2.3 g/cm\xC2\xB3"})
    EXPECT_NEAR(fp::parse_quantity(s, K::density), 2300.0, 1e-9) << s;
  EXPECT_NEAR(fp::parse_quantity("2.3 g\xC2\xB7"
                                 "cm\xE2\x81\xBB\xC2\xB3",
                                 K::density),
              2300.0, 1e-9);
  EXPECT_NEAR(fp::parse_quantity("5 \xC2\xB5s", K::time), 5e-6, 1e-20);
  EXPECT_NEAR(fp::parse_quantity("5 \xCE\xBCs", K::time), 5e-6, 1e-20);
  EXPECT_NEAR(fp::parse_quantity("5us", K::time), 5e-6, 1e-20);
  EXPECT_NEAR(fp::parse_quantity("2 ms", K::time), 2e-3, 1e-18);
  EXPECT_NEAR(fp::parse_quantity("3 km", K::length), 3000.0, 1e-9);
  EXPECT_NEAR(fp::parse_quantity("1 N/mm2", K::pressure), 1e6, 1e-6);
  EXPECT_NEAR(fp::parse_quantity("2 bar", K::pressure), 2e5, 1e-6);
  EXPECT_NEAR(fp::parse_quantity("1 m s^-2", K::acceleration), 1.0, 1e-15);
  EXPECT_NEAR(fp::parse_quantity("1 m/s/s", K::acceleration), 1.0, 1e-15);
  EXPECT_NEAR(fp::parse_quantity("100 J/m2", K::energy_per_area), 100.0, 1e-12);
  EXPECT_NEAR(fp::parse_quantity("8e-6 1/K", K::expansion), 8e-6, 1e-20);
  EXPECT_NEAR(fp::parse_quantity("25 \xC2\xB0"
                                 "C",
                                 K::temperature),
              298.15, 1e-12);
  EXPECT_NEAR(fp::parse_quantity("-273.15 degC", K::temperature), 0.0, 1e-12);
}

TEST(Units, AnglesKeepTheirTwoPi) {
  EXPECT_NEAR(fp::parse_quantity("180 deg", K::angle), std::numbers::pi, 1e-15);
  EXPECT_NEAR(fp::parse_quantity("360 deg/s", K::angular_velocity), 2.0 * std::numbers::pi, 1e-14);
  // Hz is cycles per second, not radians per second: refused where an angular velocity is expected.
  EXPECT_NE(error_of("1 Hz", K::angular_velocity).find("angular velocity"), std::string::npos);
  EXPECT_NE(error_of("1 rad/s", K::frequency).find("frequency"), std::string::npos);
}

TEST(Units, WrongKindNamesWhatWasExpectedAndFound) {
  const std::string e = error_of("5 m", K::pressure);
  EXPECT_NE(e.find("expected a pressure"), std::string::npos) << e;
  EXPECT_NE(e.find("Pa"), std::string::npos) << e;
  EXPECT_NE(e.find("\"5 m\""), std::string::npos) << e;
  EXPECT_NE(e.find("a length"), std::string::npos) << e;
  EXPECT_NE(error_of("800 C", K::length).find("a temperature"), std::string::npos);
  EXPECT_NE(error_of("1 m2/s", K::velocity).find("m^2 s^-1"), std::string::npos);
}

TEST(Units, UnreadableQuantities) {
  for (const char* s : {"", "GPa", "abc", "5 furlongs", "5 m/", "5 J/kg K", "5 (m", "5 m^", "5 mC",
                        "nan", "inf m", "5 m)", "5 m^x"})
    EXPECT_FALSE(error_of(s, K::length).empty()) << s;
  EXPECT_NE(error_of("5 J/kg K", K::specific_heat).find("parentheses"), std::string::npos);
  EXPECT_NE(error_of("5 furlongs", K::length).find("unknown unit 'furlongs'"), std::string::npos);
  EXPECT_NE(error_of("C", K::temperature).find("does not start with a number"), std::string::npos);
  EXPECT_NE(error_of("10 C/s", K::temperature).find("Celsius"), std::string::npos);
}
