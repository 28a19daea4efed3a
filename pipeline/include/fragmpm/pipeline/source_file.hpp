#pragma once
// Data files of the source tree that commands need at run time (the demo's micrograph, the grain
// file of the three-grain scene): scenes are compiled into the program, these files are not.
#include <string>

namespace fragmpm::pipeline {

/// Path of `relative` (a path inside the source tree, e.g. "images/x.png"), looked for first under
/// $FRAGMPM_SOURCE_DIR, then beside the executable and in every folder above it (./build/fragmpm
/// of a clone finds <clone>/images), then in the working directory and every folder above it.
/// Throws PipelineError (pipeline_job.hpp) naming `what` and where it looked.
std::string find_source_file(const std::string& relative, const std::string& what);

}  // namespace fragmpm::pipeline
