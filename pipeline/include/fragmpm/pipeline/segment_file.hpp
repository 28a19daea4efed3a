#pragma once
// Grain files (docs/design.md): one HDF5 file per segmented image, SI units.
//   /            attributes: format ("fragmpm grain file"), program_version, git_hash,
//                pixel_size [m], image_path, window (x,y,w,h in the image's pixels), image_size
//                (w,h), input_kind, options (the segmentation settings, one "key = value" a line)
//   /labels      rows × cols int32 label image of the window (0 = background, grain k = label k),
//                row 0 at the top of the image
//   /grains/     one dataset per column, one row per grain (row k − 1 = label k): label, pixels,
//                area, equivalent_diameter, roundness, aspect_ratio, centroid_x, centroid_y,
//                major_axis, minor_axis, orientation, perimeter, centroid_col, centroid_row,
//                mean_grey, phase, touches_border; each with a `units` attribute
//   /particles/  the datasets of a run frame (x, v, F, volume0, mass, r1, r2, stress, damage,
//                surface, body, material); attributes cell_size [m], particles_per_cell,
//                densities (kg/m3 per material, comma-separated)
// Positions (centroid_x/y, x) are in the image's physical frame: origin at the lower-left corner
// of the window, x right, y up.
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

#include "fragmpm/mpm/particles.hpp"
#include "fragmpm/pipeline/segment.hpp"
#include "fragmpm/pipeline/segment_particles.hpp"

namespace fragmpm::pipeline {

/// Everything written to a grain file besides the segmentation itself.
struct GrainFileExtras {
  ParticleSampling sampling;
  std::vector<double> density_of_material;  ///< [kg/m³]
  std::string options_text;                 ///< settings used, for the record
};

/// Writes `path`. Refuses to replace an existing file unless `overwrite` (mpm::RunFileError naming
/// the path, as every HDF5 failure).
void write_grain_file(const std::string& path, const Segmentation& segmentation,
                      const mpm::Particles<2>& particles, const GrainFileExtras& extras,
                      bool overwrite);

/// A grain file read back.
struct GrainFile {
  std::string path;
  std::string image_path;
  double pixel_size = 0.0;  ///< [m]
  cv::Rect window;
  cv::Mat labels;  ///< CV_32SC1
  std::vector<Grain> grains;
  mpm::Particles<2> particles;
  ParticleSampling sampling;
};

/// Reads a grain file; throws mpm::RunFileError naming the file and object when it is missing,
/// not HDF5, or lacks a dataset or attribute of the layout above.
GrainFile read_grain_file(const std::string& path);

}  // namespace fragmpm::pipeline
