#pragma once
// Private to the scene compiler: [[bodies]] entries whose grains come from a micrograph
// (`image = "…"`) or a grain file (`grains = "grains.h5"`) instead of a shape.
#include <string>
#include <vector>

#include "fragmpm/mpm/problem.hpp"
#include "fragmpm/pipeline/segment_bodies.hpp"
#include "scene_toml.hpp"

namespace fragmpm::pipeline::scene_detail {

/// A grain-source entry, segmented and sampled, with its particles already placed in the scene
/// (translated by `origin`, given the entry's velocity and material); body ids 0 … grains − 1.
struct GrainEntry {
  std::string name;
  Section section;
  GrainBodies bodies;
  std::vector<std::string> body_names;  ///< "<entry name>-grain-<label>", index = local body id
};

/// True when the entry names a grain source (image or grains) rather than a shape.
bool is_grain_source(const Section& body);

/// The segmentation options of an `image = …` entry (pixel_size, input, crop, threshold, …),
/// reading the image at `image_path` (already resolved). Throws SceneError for a bad key. Also used
/// by `fragmpm pipeline` to draw the segmentation preview the scene's grains come from.
SegmentOptions read_segment_options(const Section& body, const std::string& image_path);

/// Reads, segments and samples one grain-source entry. `scene_path` locates relative image and
/// grain-file paths (relative to the scene file's directory). Throws SceneError for unknown keys, a
/// bad pixel size or option, a missing or unreadable image or grain file, grains outside the grid
/// domain, or no grain that holds a particle.
GrainEntry read_grain_entry(const Section& body, const std::string& scene_path, int material,
                            const mpm::MaterialSpec& spec, const mpm::GridSpec<2>& grid,
                            int particles_per_cell);

}  // namespace fragmpm::pipeline::scene_detail
