#pragma once
// Shared by the tests that run a scene whole and in parts: a fresh folder per test and the
// bit-for-bit comparison of one /series dataset of two run files.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <string>

#include "fragmpm/mpm/run_file.hpp"

namespace fragmpm::test_support {

/// TempDir()/fragmpm_NAME, emptied and created.
inline std::filesystem::path fresh_directory(const std::string& name) {
  const std::filesystem::path dir =
      std::filesystem::path(::testing::TempDir()) / ("fragmpm_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

/// /series/NAME of run files `a` and `b` agree bit for bit.
inline void expect_series_identical(const std::string& a, const std::string& b,
                                    const std::string& name) {
  const auto sa = mpm::read_series(a, name), sb = mpm::read_series(b, name);
  ASSERT_EQ(sa.size(), sb.size()) << name;
  EXPECT_EQ(std::memcmp(sa.data(), sb.data(), sa.size() * sizeof(double)), 0) << name;
}

}  // namespace fragmpm::test_support
