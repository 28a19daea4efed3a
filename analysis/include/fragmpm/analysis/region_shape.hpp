#pragma once
// Shape measures of a planar region made of weighted cells: grains (pixels of a label image) and
// fragments (particle domains) both go through the one implementation here (docs/design.md), so the
// grain table and the fragment statistics use the same definitions, those of ImageJ:
//   area A, equivalent diameter √(4A/π), centroid, the moment-equivalent ellipse (major, minor
//   axis, orientation) rescaled to the region's area, roundness 4A/(π a²) = minor/major, aspect
//   ratio major/minor.
// ImageJ adds 1/12 to each pixel's second moment for the pixel's own extent; here every cell
// carries its own second central moments (a pixel or a CPDI parallelogram domain), which is the
// same correction generalised.
#include <cstdint>
#include <limits>
#include <opencv2/core/mat.hpp>
#include <span>
#include <vector>

namespace fragmpm::analysis {

/// One piece of a region: centroid (x, y), area, and its own second central moments per unit
/// area (cxx = ∫(x−x̄)² dA / area, …). Lengths in any consistent unit u; area in u².
struct ShapeCell {
  double x = 0.0;
  double y = 0.0;
  double area = 0.0;
  double cxx = 0.0;
  double cyy = 0.0;
  double cxy = 0.0;
};

/// A square pixel of side `side` centred at (x, y): own moments side²/12 (ImageJ's 1/12).
ShapeCell pixel_cell(double x, double y, double side);

/// A parallelogram (CPDI particle domain) centred at (x, y) with full edge vectors r1, r2:
/// area |r1 × r2| and own covariance (r1 r1ᵀ + r2 r2ᵀ)/12 (uniform density over the domain).
ShapeCell parallelogram_cell(double x, double y, double r1x, double r1y, double r2x, double r2y);

/// Running sums of area and first/second moments. Sums are taken about the first cell's position
/// so that regions far from the origin keep their digits.
struct RegionMoments {
  double area = 0.0;
  double sx = 0.0, sy = 0.0;               ///< Σ a (x − x0), Σ a (y − y0)
  double sxx = 0.0, syy = 0.0, sxy = 0.0;  ///< Σ a (x − x0)² + a cxx, …
  double x0 = 0.0, y0 = 0.0;
  std::int64_t cells = 0;

  void add(const ShapeCell& c);
};

/// Shape measures of one region, in the unit of the cells (u, u², radians).
struct RegionShape {
  double area = 0.0;                 ///< A [u²]
  double equivalent_diameter = 0.0;  ///< √(4A/π) [u]
  double centroid_x = 0.0;           ///< [u]
  double centroid_y = 0.0;           ///< [u]
  double major_axis = 0.0;           ///< full length a of the moment ellipse rescaled to area A [u]
  double minor_axis = 0.0;           ///< full length b, with π a b / 4 = A [u]
  double orientation = 0.0;   ///< angle of the major axis from +x towards +y, in (−π/2, π/2]
  double roundness = 0.0;     ///< 4A/(π a²) = b/a ∈ (0, 1] (ImageJ "Round")
  double aspect_ratio = 0.0;  ///< a/b ≥ 1 (ImageJ "AR"); +inf for a region with no width
  /// Boundary length [u]; NaN when the caller has no boundary (e.g. cells without an outline).
  double perimeter = std::numeric_limits<double>::quiet_NaN();
};

/// Shape of the region whose moments were accumulated. `perimeter` is passed through (it is not a
/// moment: pixel regions get it from label_region_shapes, fragments from their outline).
/// A region of zero area gives an all-zero shape.
RegionShape region_shape(const RegionMoments& moments,
                         double perimeter = std::numeric_limits<double>::quiet_NaN());
RegionShape region_shape(std::span<const ShapeCell> cells,
                         double perimeter = std::numeric_limits<double>::quiet_NaN());

/// Perimeter by the Cauchy–Crofton formula discretised on 4 directions (0°, 45°, 90°, 135°):
/// P = (π/8) [n₀ + n₉₀ + (n₄₅ + n₁₃₅)/√2] · side, with n_θ the number of times the lines through
/// pixel centres in direction θ enter or leave the region. Unbiased for isotropic shapes (a disk of
/// radius r gives 2πr); unlike ImageJ's traced polygon it does not depend on the pixel-edge
/// staircase.
double crofton_perimeter(std::int64_t n0, std::int64_t n90, std::int64_t n45, std::int64_t n135,
                         double side);

/// One labelled region of a label image.
struct LabelRegion {
  std::int32_t label = 0;
  std::int64_t pixels = 0;
  RegionShape shape;          ///< in the physical frame described at label_region_shapes
  cv::Rect bbox;              ///< in pixels (column, row)
  double centroid_col = 0.0;  ///< pixel coordinates of the centroid, pixel centres at integer + 0.5
  double centroid_row = 0.0;
  bool touches_border = false;  ///< has a pixel in the first/last row or column
};

/// OpenCV adapter: shape of every label > 0 of a CV_32S label image (0 = background), in the
/// physical frame of the image: origin at the lower-left corner of the image, x to the right, y up,
/// pixel (col, row) centred at ((col + ½) s, (rows − row − ½) s) with s = pixel_size. Returned in
/// increasing label order; labels that do not occur are skipped. Pixels outside the image count as
/// background for the perimeter (a grain cut by the border includes the cut in its perimeter).
std::vector<LabelRegion> label_region_shapes(const cv::Mat& labels, double pixel_size);

}  // namespace fragmpm::analysis
