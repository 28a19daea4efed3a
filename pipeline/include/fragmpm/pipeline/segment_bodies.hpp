#pragma once
// Grains as scene bodies (for the scene compiler): particles at the scene's cell
// size from a micrograph (`[bodies] image = "…"`) or from a grain file (`grains = "grains.h5"`).
// Particles are in the image's physical frame (origin at the lower-left corner of the window,
// y up, SI); the scene translates them. body = grain row (label − 1), material = grain phase
// (remap to scene materials with body_materials_from_phases when the scene names them).
#include <cstdint>
#include <string>
#include <vector>

#include "fragmpm/mpm/particles.hpp"
#include "fragmpm/pipeline/segment_grains.hpp"
#include "fragmpm/pipeline/segment_options.hpp"
#include "fragmpm/pipeline/segment_particles.hpp"

namespace fragmpm::pipeline {

struct GrainBodies {
  mpm::Particles<2> particles;
  std::vector<Grain> grains;            ///< row k = body k
  std::vector<std::string> body_names;  ///< "grain <label>", index = body id
  double pixel_size = 0.0;              ///< [m]
  double width = 0.0, height = 0.0;     ///< extent of the window [m]
};

/// Segments `options.image_path` and samples its grains at `sampling`; density_of_phase[k] is the
/// density of phase k [kg/m³] (one value per phase: options.phase_bands.size() + 1).
/// Throws SegmentInputError for bad input (the message names the file and what is wrong).
GrainBodies grain_bodies_from_image(const SegmentOptions& options, const ParticleSampling& sampling,
                                    const std::vector<double>& density_of_phase);

/// Reads a grain file and samples its /labels at `sampling` (the scene's cell size; the file's own
/// /particles are not used, so the scene decides the resolution). Throws mpm::RunFileError for an
/// unreadable file and SegmentInputError when a grain's phase has no density.
GrainBodies grain_bodies_from_file(const std::string& path, const ParticleSampling& sampling,
                                   const std::vector<double>& density_of_phase);

}  // namespace fragmpm::pipeline
