#pragma once
// The whole of a text file, for tests that compare or edit what a command wrote or a scene holds.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace fragmpm::test_support {

/// The file's contents; empty when it cannot be read (the caller's expectations then fail).
inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace fragmpm::test_support
