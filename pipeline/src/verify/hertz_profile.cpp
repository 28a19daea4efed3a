// The pressure profile of the Hertz case: CSV of the nodal pressures of every level and a figure
// of them over the analytic ellipse ([XLS21] eq. (89); verify_hertz.hpp).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "fragmpm/analysis/plot.hpp"
#include "fragmpm/pipeline/verify_hertz.hpp"

namespace fragmpm::pipeline {

void write_hertz_profile(const std::string& directory, const std::vector<HertzLevel>& levels,
                         const HertzOracle& oracle) {
  std::filesystem::create_directories(directory);
  const std::filesystem::path csv_path = std::filesystem::path(directory) / "hertz-profile.csv";
  std::ofstream csv(csv_path);
  csv << "level,cell_size_m,x_m,pressure_Pa,analytic_Pa,analytic_nodal_Pa\n";
  csv.precision(10);
  analysis::PlotSpec spec;
  spec.title = "Hertz line contact: contact pressure on the flat";
  spec.x_label = "position on the flat x [mm]";
  spec.y_label = "contact pressure p [MPa]";
  double reach = 1.25 * oracle.half_width();
  for (std::size_t k = 0; k < levels.size(); ++k) {
    analysis::LineSeries nodes;
    char label[64];
    std::snprintf(label, sizeof label, "MPM, h = %.3g mm", levels[k].cell_size * 1e3);
    nodes.label = label;
    nodes.markers = true;
    for (const HertzProfilePoint& point : levels[k].profile) {
      csv << k << ',' << levels[k].cell_size << ',' << point.x << ',' << point.pressure << ','
          << point.analytic << ',' << point.analytic_nodal << '\n';
      nodes.x.push_back(point.x * 1e3);
      nodes.y.push_back(point.pressure * 1e-6);
      reach = std::max(reach, std::abs(point.x));
    }
    spec.series.push_back(std::move(nodes));
  }
  analysis::LineSeries analytic;
  analytic.label = "Hertz, [XLS21] eq. (89)";
  constexpr int samples = 400;
  for (int j = 0; j <= samples; ++j) {
    const double x = reach * (2.0 * j / samples - 1.0);
    analytic.x.push_back(x * 1e3);
    analytic.y.push_back(oracle.pressure(x) * 1e-6);
  }
  spec.series.insert(spec.series.begin(), std::move(analytic));
  if (!levels.empty()) {  // what the finest level's nodes should read (HertzOracle::nodal_pressure)
    analysis::LineSeries nodal;
    char label[80];
    std::snprintf(label, sizeof label, "eq. (89) read at the nodes, h = %.3g mm",
                  levels.back().cell_size * 1e3);
    nodal.label = label;
    for (const HertzProfilePoint& point : levels.back().profile) {
      nodal.x.push_back(point.x * 1e3);
      nodal.y.push_back(point.analytic_nodal * 1e-6);
    }
    spec.series.insert(spec.series.begin() + 1, std::move(nodal));
  }
  csv.close();
  std::printf("written %s\n", csv_path.string().c_str());
  const std::filesystem::path png_path = std::filesystem::path(directory) / "hertz-profile.png";
  analysis::write_line_plot(spec, png_path.string());
  std::printf("written %s (pressure profile)\n", png_path.string().c_str());
}

}  // namespace fragmpm::pipeline
