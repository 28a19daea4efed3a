#pragma once
// Particle figures (docs/design.md "Figures"): each CPDI particle domain — the parallelogram with
// corners x ± r1/2 ± r2/2 — filled with the colour of a scalar field (viridis, with a colour bar
// labelled with the field name and units) or of a body / fragment id (categorical palette, with a
// legend), plus title, time stamp and a scale bar of a round length. Equal scale in x and y. Plain
// arrays in, so the figure does not depend on the run-file format.
#include <Eigen/Core>
#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <string>
#include <vector>

namespace fragmpm::analysis {

struct ParticleFigure {
  std::vector<Eigen::Vector2d> x, r1, r2;  ///< centres and full CPDI edge vectors [m]
  /// Either a continuous field (one value per particle; NaN drawn grey) ...
  std::vector<double> values;
  /// ... or categorical ids (one per particle; negative = none, drawn grey). Exactly one is given.
  std::vector<std::int64_t> ids;
  std::string id_name = "id";      ///< legend prefix for ids ("body", "fragment")
  std::string none_name = "none";  ///< legend entry of the negative ids (grey)
  std::string title;
  std::string field_name;            ///< colour-bar label, e.g. "damage"
  std::string units;                 ///< e.g. "K", "MPa", "m/s"; empty or "1" for dimensionless
  std::optional<double> time;        ///< [s]; shown as "t = 12.5 µs" when set
  std::optional<double> vmin, vmax;  ///< colour range; default: range of the finite values
  int width = 1200, height = 900;
};

/// Where the particles fall in the image: pixel = (left + scale (x − x_min), bottom − scale (y −
/// y_min)).
struct ParticleFrame {
  double x_min = 0, y_min = 0;  ///< [m], lower-left corner of the drawn domain
  double scale = 1;             ///< pixels per metre
  double left = 0, bottom = 0;  ///< pixel position of (x_min, y_min)
  int bar_left = 0, bar_top = 0, bar_right = 0, bar_bottom = 0;  ///< colour bar [px]; 0 when ids
  double vmin = 0, vmax = 1;                                     ///< colour range used
  double scale_bar_length = 0;                                   ///< [m]
  Eigen::Vector2d to_pixel(const Eigen::Vector2d& p) const;
};

/// Checks the input and lays the figure out. Throws FigureError on mismatched array lengths, both
/// or neither of values/ids, no particles, non-finite geometry, all-degenerate domains, an empty or
/// reversed colour range, or a size outside [200, 16384] pixels.
ParticleFrame particle_frame(const ParticleFigure& figure);

/// The figure as an 8-bit BGR image (height × width).
cv::Mat render_particle_figure(const ParticleFigure& figure);

/// Renders and writes the figure as PNG (replacing an existing file).
void write_particle_figure(const ParticleFigure& figure, const std::string& png_path);

/// Round scale-bar length 1, 2 or 5 × 10^k [m] no longer than `max_length` [m] (> 0).
double scale_bar_length(double max_length);

}  // namespace fragmpm::analysis
