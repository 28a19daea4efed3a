// PNG output (see png_file.hpp).
#include "fragmpm/analysis/png_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "fragmpm/analysis/figure_error.hpp"

namespace fragmpm::analysis {

void write_png(const cv::Mat& image, const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  if (ext != ".png")
    throw FigureError(
        fmt::format("{}: figures are written as PNG; expected a path ending in .png", path));
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  if (!parent.empty() && !std::filesystem::is_directory(parent))
    throw FigureError(fmt::format("{}: directory {} does not exist", path, parent.string()));
  bool ok = false;
  try {
    ok = cv::imwrite(path, image);
  } catch (const cv::Exception& e) {
    throw FigureError(fmt::format("{}: cannot write PNG: {}", path, e.what()));
  }
  if (!ok)
    throw FigureError(fmt::format("{}: cannot write PNG (check permissions and free space)", path));
}

}  // namespace fragmpm::analysis
