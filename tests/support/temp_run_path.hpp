#pragma once
// Run-file paths for tests: unique to this process (test runs may overlap) and removed with their
// .xmf when the test binary exits.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

namespace fragmpm::test_support {

/// TempDir()/PREFIX_PID_NAME.h5, with any earlier file of that name and its .xmf removed.
inline std::string temp_run_path(const std::string& prefix, const std::string& name) {
  struct Cleanup {
    std::vector<std::string> paths;
    ~Cleanup() {
      std::error_code ec;
      for (const std::string& p : paths) {
        std::filesystem::remove(p, ec);
        std::filesystem::remove(std::filesystem::path(p).replace_extension(".xmf"), ec);
      }
    }
  };
  static Cleanup cleanup;
  const std::string path =
      ::testing::TempDir() + prefix + "_" + std::to_string(getpid()) + "_" + name + ".h5";
  std::filesystem::remove(path);
  std::filesystem::remove(std::filesystem::path(path).replace_extension(".xmf"));
  cleanup.paths.push_back(path);
  return path;
}

}  // namespace fragmpm::test_support
