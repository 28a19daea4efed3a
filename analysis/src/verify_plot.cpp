// Verification figure (see verify_plot.hpp).
#include "fragmpm/analysis/verify_plot.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <vector>

#include "fragmpm/analysis/figure_error.hpp"
#include "fragmpm/analysis/plot.hpp"

namespace fragmpm::analysis {

namespace {

const std::vector<std::string> expected_header{"case",      "variant", "level",     "cell_size_m",
                                               "particles", "dt_s",    "steps",     "wall_s",
                                               "metric",    "value",   "reference", "error"};

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream in(line);
  std::string cell;
  while (std::getline(in, cell, ',')) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

double number(const std::string& text, const std::string& path, int line,
              const std::string& column) {
  const char* begin = text.c_str();
  char* end = nullptr;
  const double v = std::strtod(begin, &end);
  if (end == begin || *end != '\0')
    throw FigureError(
        fmt::format("{}:{}: column {}: '{}' is not a number", path, line, column, text));
  return v;
}

struct Point {
  int level;
  double wall, error;
};

}  // namespace

void write_verify_plot(const std::string& csv_path, const std::string& png_path) {
  std::ifstream in(csv_path);
  if (!in) throw FigureError(fmt::format("{}: cannot open the verify CSV", csv_path));
  std::string line;
  if (!std::getline(in, line))
    throw FigureError(fmt::format("{}: empty file; expected a verify CSV", csv_path));
  if (!line.empty() && line.back() == '\r') line.pop_back();
  if (split(line) != expected_header)
    throw FigureError(fmt::format("{}:1: header '{}'; expected '{}'", csv_path, line,
                                  fmt::join(expected_header, ",")));
  std::map<std::pair<std::string, std::string>, std::vector<Point>> groups;
  std::set<std::string> cases;
  int line_no = 1, dropped = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    const std::vector<std::string> c = split(line);
    if (c.size() != expected_header.size())
      throw FigureError(fmt::format("{}:{}: {} columns; expected {}", csv_path, line_no, c.size(),
                                    expected_header.size()));
    const double level = number(c[2], csv_path, line_no, "level");
    const double wall = number(c[7], csv_path, line_no, "wall_s");
    const double error = number(c[11], csv_path, line_no, "error");
    cases.insert(c[0]);
    if (!(wall > 0.0) || !(error > 0.0) || !std::isfinite(wall) || !std::isfinite(error)) {
      ++dropped;
      continue;
    }
    groups[{c[1], c[8]}].push_back(Point{static_cast<int>(level), wall, error});
  }
  if (groups.empty())
    throw FigureError(fmt::format(
        "{}: no row with a positive error and wall time to draw on log axes", csv_path));
  PlotSpec spec;
  spec.title = fmt::format("Verification {}: error vs run time", fmt::join(cases, ", "));
  if (dropped > 0)
    spec.title += fmt::format(" ({} rows with zero error or time not shown)", dropped);
  spec.x_label = "wall time [s]";
  spec.y_label = "error";
  spec.log_x = spec.log_y = true;
  for (auto& [key, points] : groups) {
    std::stable_sort(points.begin(), points.end(),
                     [](const Point& a, const Point& b) { return a.level < b.level; });
    LineSeries s;
    s.label = key.first.empty() ? key.second : fmt::format("{}: {}", key.first, key.second);
    s.markers = true;
    for (const Point& p : points) {
      s.x.push_back(p.wall);
      s.y.push_back(p.error);
    }
    spec.series.push_back(std::move(s));
  }
  write_line_plot(spec, png_path);
}

}  // namespace fragmpm::analysis
