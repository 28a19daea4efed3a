#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "fragmpm/analysis/figure_error.hpp"
#include "fragmpm/analysis/verify_plot.hpp"
#include "fragmpm/pipeline/verify.hpp"

namespace fragmpm::pipeline {

double observed_order(const VerifyRow& coarse, const VerifyRow& fine) {
  if (!(coarse.error > 0.0) || !(fine.error > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  // A study in the time step alone (the oscillating block) keeps the cell and refines Δt.
  const bool in_time = coarse.cell_size == fine.cell_size;
  const double coarse_size = in_time ? coarse.dt : coarse.cell_size;
  const double fine_size = in_time ? fine.dt : fine.cell_size;
  if (!(coarse_size > 0.0) || !(fine_size > 0.0) || coarse_size == fine_size)
    return std::numeric_limits<double>::quiet_NaN();
  return std::log(coarse.error / fine.error) / std::log(coarse_size / fine_size);
}

bool report_case(const std::string& directory, const std::string& case_name,
                 const std::vector<VerifyRow>& rows, const std::string& selection) {
  if (rows.empty()) {
    // Only a run kept in a run file and stopped short of its end (--max-steps) reports nothing;
    // the CSV of an earlier, finished invocation stays as it was.
    std::printf(
        "\n%s: no run finished, nothing to report yet (the same command continues a run "
        "stopped by --max-steps)\n",
        case_name.c_str());
    return true;
  }
  std::filesystem::create_directories(directory);
  const std::string stem = selection.empty() ? case_name : case_name + "-" + selection;
  const std::string path = (std::filesystem::path(directory) / (stem + ".csv")).string();
  std::ofstream csv(path);
  csv << "case,variant,level,cell_size_m,particles,dt_s,steps,wall_s,metric,value,reference,"
         "error\n";
  csv.precision(10);
  // The files are read back by splitting at commas (the error-versus-time figure), so a comma in
  // a name would shift every later column: it is written as a semicolon.
  const auto field = [](std::string text) {
    std::replace(text.begin(), text.end(), ',', ';');
    return text;
  };
  for (const auto& r : rows)
    csv << field(r.case_name) << ',' << field(r.variant) << ',' << r.level << ',' << r.cell_size
        << ',' << r.particles << ',' << r.dt << ',' << r.steps << ',' << r.wall_seconds << ','
        << field(r.metric) << ',' << r.value << ',' << r.reference << ',' << r.error << '\n';
  std::printf("\n%s\n%-8s %-5s %11s %9s %10s %7s %8s  %-28s %12s %12s %10s %6s  %s\n",
              case_name.c_str(), "variant", "level", "h [m]", "particles", "dt [s]", "steps",
              "wall [s]", "metric", "value", "reference", "error", "order", "target");
  bool all_passed = true;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const VerifyRow& r = rows[i];
    double order = std::numeric_limits<double>::quiet_NaN();
    for (std::size_t j = i; j-- > 0;)
      if (rows[j].variant == r.variant && rows[j].metric == r.metric) {
        order = observed_order(rows[j], r);
        break;
      }
    char order_text[16] = "";
    if (std::isfinite(order)) std::snprintf(order_text, sizeof order_text, "%6.2f", order);
    char target_text[80] = "";
    if (r.has_target()) {
      std::snprintf(target_text, sizeof target_text, "[%.5g, %.5g] %s", r.target_low, r.target_high,
                    r.passed() ? "PASS" : "FAIL");
      all_passed = all_passed && r.passed();
    }
    std::printf("%-8s %-5d %11.4e %9lld %10.3e %7lld %8.2f  %-28s %12.5e %12.5e %10.3e %6s  %s\n",
                r.variant.c_str(), r.level, r.cell_size, r.particles, r.dt, r.steps, r.wall_seconds,
                r.metric.c_str(), r.value, r.reference, r.error, order_text, target_text);
  }
  csv.close();
  std::printf("written %s\n", path.c_str());
  const std::string png = (std::filesystem::path(directory) / (case_name + ".png")).string();
  try {
    analysis::write_verify_plot(path, png);
    std::printf("written %s (error versus wall time)\n", png.c_str());
  } catch (const std::exception& e) {
    std::printf("no error-versus-time figure for %s: %s\n", case_name.c_str(), e.what());
  }
  return all_passed;
}

}  // namespace fragmpm::pipeline
