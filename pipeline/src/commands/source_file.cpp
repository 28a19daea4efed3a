// Finding data files of the source tree at run time (source_file.hpp).
#include "fragmpm/pipeline/source_file.hpp"

#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>
#include <vector>

#include "fragmpm/pipeline/pipeline_job.hpp"

namespace fragmpm::pipeline {

namespace fs = std::filesystem;

std::string find_source_file(const std::string& relative, const std::string& what) {
  std::vector<fs::path> roots;
  if (const char* env = std::getenv("FRAGMPM_SOURCE_DIR"); env && *env) roots.emplace_back(env);
  std::error_code ec;
  auto add_ancestors = [&](fs::path p) {
    for (; !p.empty(); p = p.parent_path()) {
      roots.push_back(p);
      if (p == p.root_path()) break;
    }
  };
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) add_ancestors(exe.parent_path());
  const fs::path cwd = fs::current_path(ec);
  if (!ec) add_ancestors(cwd);
  for (const fs::path& root : roots)
    if (fs::is_regular_file(root / relative, ec)) return (root / relative).string();
  throw PipelineError(
      fmt::format("cannot find {} ({}): looked under $FRAGMPM_SOURCE_DIR, the folders above the "
                  "executable and above the working directory; set FRAGMPM_SOURCE_DIR to the "
                  "FragMPM source tree",
                  relative, what));
}

}  // namespace fragmpm::pipeline
