// `fragmpm verify --variant NAME --level N`: one run of a long case without the others.
#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "fragmpm/pipeline/verify.hpp"

namespace fragmpm::pipeline {

const std::vector<std::string>& variant_selection_cases() {
  static const std::vector<std::string> cases{"plate-impact", "sphere-beam", "two-rings"};
  return cases;
}

bool selected(const VerifyOptions& options, const std::string& variant, int level) {
  if (options.level >= 0 && level != options.level) return false;
  return options.variants.empty() || std::find(options.variants.begin(), options.variants.end(),
                                               variant) != options.variants.end();
}

void check_selection(const VerifyOptions& options, const std::string& case_name,
                     const std::vector<std::string>& variants, int levels) {
  for (const std::string& name : options.variants)
    if (std::find(variants.begin(), variants.end(), name) == variants.end()) {
      std::string known;
      for (const std::string& v : variants) known += " " + v;
      throw std::invalid_argument("--variant: case '" + case_name + "' has no variant '" + name +
                                  "'; its variants:" + known);
    }
  if (options.level >= levels)
    throw std::invalid_argument(
        "--level " + std::to_string(options.level) + ": case '" + case_name + "' runs " +
        (levels == 1 ? std::string("level 0 only") : "levels 0 to " + std::to_string(levels - 1)) +
        (options.quick ? " with --quick" : ""));
}

}  // namespace fragmpm::pipeline
