#pragma once
// Checks shared by the tests of report.html (pipeline and pool).
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>
#include <string>

namespace fragmpm::test {

/// The number of figures `page` shows; every one must exist under `dir`, where the page is.
inline int count_existing_report_images(const std::string& page, const std::filesystem::path& dir) {
  const std::regex image(R"re(<img src="([^"]+)")re");
  int images = 0;
  for (auto it = std::sregex_iterator(page.begin(), page.end(), image);
       it != std::sregex_iterator(); ++it, ++images)
    EXPECT_TRUE(std::filesystem::exists(dir / (*it)[1].str())) << (*it)[1].str();
  return images;
}

}  // namespace fragmpm::test
