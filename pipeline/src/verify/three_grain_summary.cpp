// The top grain's fragment measures of one frame and the summary table of the three-grain case
// (verify_three_grain.hpp).
#include <cmath>
#include <fstream>
#include <stdexcept>

#include "fragmpm/pipeline/verify_three_grain.hpp"

namespace fragmpm::pipeline {

void summarize_top_grain(const analysis::FrameFragments& frame, ThreeGrainSample& sample) {
  sample.fragments = static_cast<long long>(frame.fragments.size());
  sample.fines = static_cast<long long>(frame.fines.size());
  sample.mean_diameter = sample.largest_diameter = sample.diameter_deviation = 0.0;
  sample.mean_roundness = 0.0;
  if (frame.fragments.empty()) return;
  const double n = static_cast<double>(frame.fragments.size());
  for (const auto& f : frame.fragments) {
    sample.mean_diameter += f.equivalent_diameter / n;
    sample.mean_roundness += f.roundness / n;
    sample.largest_diameter = std::max(sample.largest_diameter, f.equivalent_diameter);
  }
  if (frame.fragments.size() < 2) return;
  double squares = 0.0;
  for (const auto& f : frame.fragments)
    squares += (f.equivalent_diameter - sample.mean_diameter) *
               (f.equivalent_diameter - sample.mean_diameter);
  sample.diameter_deviation = std::sqrt(squares / (n - 1.0));
}

void write_three_grain_summary(const std::string& path, const std::vector<ThreeGrainSample>& rows) {
  std::ofstream csv(path);
  if (!csv) throw std::runtime_error("cannot write " + path);
  csv << "variant,platen_speed_m_s,displacement_m,time_s,fragments,fines,mean_d_eq_m,"
         "largest_d_eq_m,d_eq_std_m,mean_roundness,peak_platen_force_N_per_m,"
         "largest_temperature_rise_K\n";
  csv.precision(8);
  for (const auto& r : rows)
    csv << r.variant << ',' << r.platen_speed << ',' << r.displacement << ',' << r.time << ','
        << r.fragments << ',' << r.fines << ',' << r.mean_diameter << ',' << r.largest_diameter
        << ',' << r.diameter_deviation << ',' << r.mean_roundness << ',' << r.peak_force << ','
        << r.largest_temperature_rise << '\n';
}

}  // namespace fragmpm::pipeline
