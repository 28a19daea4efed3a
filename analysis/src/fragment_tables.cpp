#include "fragmpm/analysis/fragment_tables.hpp"

#include <fmt/format.h>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace fragmpm::analysis {

const std::vector<FragmentColumn>& fragment_columns() {
  static const std::vector<FragmentColumn> columns{
      {"id", "1",
       "fragment id (particle_fragment refers to it); ids run by decreasing particle count", "id"},
      {"particles", "1", "number of particles", "particles"},
      {"area", "m^2 (per unit thickness)", "sum of current particle areas V0 det F", "area_m2"},
      {"equivalent_diameter", "m", "sqrt(4 area / pi)", "equivalent_diameter_m"},
      {"roundness", "1", "ImageJ roundness 4A/(pi a^2) = minor/major of the moment ellipse",
       "roundness"},
      {"aspect_ratio", "1", "major/minor axis of the moment ellipse (ImageJ AR)", "aspect_ratio"},
      {"major_axis", "m", "major axis of the moment ellipse rescaled to the area", "major_axis_m"},
      {"minor_axis", "m", "minor axis of the moment ellipse rescaled to the area", "minor_axis_m"},
      {"orientation", "rad", "major axis angle from +x towards +y, in (-pi/2, pi/2]",
       "orientation_rad"},
      {"solidity", "1", "area / convex hull area of the particle corners (capped at 1)",
       "solidity"},
      {"convex_area", "m^2 (per unit thickness)", "convex hull area of the particle corners",
       "convex_area_m2"},
      {"feret_max", "m", "maximum caliper (Feret) diameter of the convex hull", "feret_max_m"},
      {"feret_min", "m", "minimum caliper (Feret) diameter = minimum width of the convex hull",
       "feret_min_m"},
      {"perimeter", "m",
       "Crofton perimeter of the particle domains rasterised at spacing/5, smoothed at 0.4 spacing",
       "perimeter_m"},
      {"centroid_x", "m", "area centroid, x", "centroid_x_m"},
      {"centroid_y", "m", "area centroid, y", "centroid_y_m"},
      {"mass", "kg/m (per unit thickness)", "sum of particle masses", "mass_kg_per_m"},
      {"velocity_x", "m/s", "mass-weighted mean velocity, x", "velocity_x_m_per_s"},
      {"velocity_y", "m/s", "mass-weighted mean velocity, y", "velocity_y_m_per_s"},
      {"temperature", "K", "mass-weighted mean temperature", "temperature_K"},
  };
  return columns;
}

namespace {

double column_value(const FragmentStatistics& s, std::size_t k) {
  switch (k) {
    case 0:
      return s.id;
    case 1:
      return static_cast<double>(s.particles);
    case 2:
      return s.area;
    case 3:
      return s.equivalent_diameter;
    case 4:
      return s.roundness;
    case 5:
      return s.aspect_ratio;
    case 6:
      return s.major_axis;
    case 7:
      return s.minor_axis;
    case 8:
      return s.orientation;
    case 9:
      return s.solidity;
    case 10:
      return s.convex_area;
    case 11:
      return s.feret_max;
    case 12:
      return s.feret_min;
    case 13:
      return s.perimeter;
    case 14:
      return s.centroid_x;
    case 15:
      return s.centroid_y;
    case 16:
      return s.mass;
    case 17:
      return s.velocity_x;
    case 18:
      return s.velocity_y;
    default:
      return s.temperature;
  }
}

std::size_t column_count(bool temperature) {
  return fragment_columns().size() - (temperature ? 0 : 1);
}

std::ofstream open_csv(const std::string& path) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot be written");
  return out;
}

void close_csv(std::ofstream& out, const std::string& path) {
  out.close();
  if (!out) throw std::runtime_error(path + ": write failed");
}

/// The table's columns as run-file datasets, named PREFIX/<column>.
void add_table(std::vector<mpm::TableColumn>& out, const std::string& prefix,
               std::span<const FragmentStatistics> rows, bool temperature) {
  const std::size_t n = rows.size();
  for (std::size_t k = 0; k < column_count(temperature); ++k) {
    const FragmentColumn& c = fragment_columns()[k];
    mpm::TableColumn column{prefix + "/" + c.name, c.units, c.description, {}};
    if (k <= 1) {  // integer columns
      std::vector<std::int64_t> v(n);
      for (std::size_t r = 0; r < n; ++r)
        v[r] = static_cast<std::int64_t>(column_value(rows[r], k));
      column.values = std::move(v);
    } else {
      std::vector<double> v(n);
      for (std::size_t r = 0; r < n; ++r) v[r] = column_value(rows[r], k);
      column.values = std::move(v);
    }
    out.push_back(std::move(column));
  }
}

void add_cdf(std::vector<mpm::TableColumn>& out, const std::string& prefix, const EmpiricalCdf& cdf,
             const char* units, const char* what) {
  out.push_back({prefix + "/value", units,
                 fmt::format("{} of the resolved fragments, ascending", what), cdf.value});
  out.push_back({prefix + "/number_fraction", "1",
                 fmt::format("fraction of fragments with {} <= value", what), cdf.number_fraction});
  out.push_back({prefix + "/mass_fraction", "1",
                 fmt::format("fraction of fragment mass in fragments with {} <= value", what),
                 cdf.mass_fraction});
}

struct SeriesColumn {
  const char* name;
  const char* units;
  const char* description;
  const char* csv_header;
  bool integer;
  double (*value)(const FragmentSeriesPoint&);
};

const std::vector<SeriesColumn>& series_columns() {
  using P = FragmentSeriesPoint;
  static const std::vector<SeriesColumn> columns{
      {"frame", "1", "frame index (/frames/NNNNNN)", "frame", true,
       [](const P& p) { return double(p.frame); }},
      {"step", "1", "solver step of the frame", "step", true,
       [](const P& p) { return double(p.step); }},
      {"time", "s", "time of the frame", "time_s", false, [](const P& p) { return p.time; }},
      {"platen_displacement", "m", "magnitude of the platen displacement at the frame",
       "platen_displacement_m", false, [](const P& p) { return p.platen_displacement; }},
      {"fragments", "1", "resolved fragments", "fragments", true,
       [](const P& p) { return double(p.summary.fragments); }},
      {"fines", "1", "fine fragments (below the minimum particle count)", "fines", true,
       [](const P& p) { return double(p.summary.fines); }},
      {"fine_particles", "1", "particles in fines", "fine_particles", true,
       [](const P& p) { return double(p.summary.fine_particles); }},
      {"masked_particles", "1", "particles with d >= d_mask", "masked_particles", true,
       [](const P& p) { return double(p.summary.masked_particles); }},
      {"mean_equivalent_diameter", "m", "number mean equivalent diameter of the resolved fragments",
       "mean_equivalent_diameter_m", false,
       [](const P& p) { return p.summary.mean_equivalent_diameter; }},
      {"mass_mean_equivalent_diameter", "m",
       "mass-weighted mean equivalent diameter of the resolved fragments",
       "mass_mean_equivalent_diameter_m", false,
       [](const P& p) { return p.summary.mass_mean_equivalent_diameter; }},
      {"largest_equivalent_diameter", "m", "equivalent diameter of the largest fragment",
       "largest_equivalent_diameter_m", false,
       [](const P& p) { return p.summary.largest_equivalent_diameter; }},
      {"fragment_mass", "kg/m (per unit thickness)", "mass of the resolved fragments",
       "fragment_mass_kg_per_m", false, [](const P& p) { return p.summary.fragment_mass; }},
      {"fines_mass", "kg/m (per unit thickness)", "mass of the fines", "fines_mass_kg_per_m", false,
       [](const P& p) { return p.summary.fines_mass; }},
      {"departed_particles", "1",
       "particles that left the domain and were removed by this frame ([grid] outside = "
       "\"remove\")",
       "departed_particles", true, [](const P& p) { return double(p.summary.departed_particles); }},
      {"departed_mass", "kg/m (per unit thickness)",
       "mass of the particles that left the domain by this frame", "departed_mass_kg_per_m", false,
       [](const P& p) { return p.summary.departed_mass; }},
  };
  return columns;
}

}  // namespace

void write_fragment_series_csv(const std::string& path, std::span<const FragmentSeriesPoint> points,
                               bool platen) {
  std::ofstream out = open_csv(path);
  std::string header;
  for (const SeriesColumn& c : series_columns()) {
    if (!platen && std::string(c.name) == "platen_displacement") continue;
    if (!header.empty()) header += ',';
    header += c.csv_header;
  }
  out << header << '\n';
  for (const FragmentSeriesPoint& p : points) {
    bool first = true;
    for (const SeriesColumn& c : series_columns()) {
      if (!platen && std::string(c.name) == "platen_displacement") continue;
      if (!first) out << ',';
      first = false;
      if (c.integer)
        out << static_cast<long long>(c.value(p));
      else
        out << fmt::format("{:.10g}", c.value(p));
    }
    out << '\n';
  }
  close_csv(out, path);
}

std::vector<mpm::TableColumn> fragment_series_datasets(std::span<const FragmentSeriesPoint> points,
                                                       bool platen) {
  const std::size_t n = points.size();
  std::vector<mpm::TableColumn> out;
  for (const SeriesColumn& c : series_columns()) {
    if (!platen && std::string(c.name) == "platen_displacement") continue;
    mpm::TableColumn column{c.name, c.units, c.description, {}};
    if (c.integer) {
      std::vector<std::int64_t> v(n);
      for (std::size_t k = 0; k < n; ++k) v[k] = static_cast<std::int64_t>(c.value(points[k]));
      column.values = std::move(v);
    } else {
      std::vector<double> v(n);
      for (std::size_t k = 0; k < n; ++k) v[k] = c.value(points[k]);
      column.values = std::move(v);
    }
    out.push_back(std::move(column));
  }
  return out;
}

void write_fragment_csv(const std::string& path, std::span<const FragmentStatistics> rows,
                        bool temperature) {
  std::ofstream out = open_csv(path);
  const std::size_t columns = column_count(temperature);
  for (std::size_t k = 0; k < columns; ++k)
    out << (k ? "," : "") << fragment_columns()[k].csv_header;
  out << '\n';
  for (const FragmentStatistics& s : rows) {
    for (std::size_t k = 0; k < columns; ++k) {
      if (k) out << ',';
      if (k <= 1)
        out << static_cast<std::int64_t>(column_value(s, k));
      else
        out << fmt::format("{:.10g}", column_value(s, k));
    }
    out << '\n';
  }
  close_csv(out, path);
}

void write_cdf_csv(const std::string& path, const EmpiricalCdf& cdf,
                   const std::string& value_header) {
  std::ofstream out = open_csv(path);
  out << value_header << ",number_fraction,mass_fraction\n";
  for (std::size_t k = 0; k < cdf.value.size(); ++k)
    out << fmt::format("{:.10g},{:.10g},{:.10g}\n", cdf.value[k], cdf.number_fraction[k],
                       cdf.mass_fraction[k]);
  close_csv(out, path);
}

std::vector<mpm::TableColumn> fragment_frame_datasets(const FrameFragments& frame) {
  std::vector<mpm::TableColumn> out;
  add_table(out, "table", frame.fragments, frame.has_temperature);
  add_table(out, "fines", frame.fines, frame.has_temperature);
  out.push_back({"particle_fragment", "1",
                 "fragment id of each particle (table/id or fines/id), -1 = masked (d >= d_mask), "
                 "-2 = another body than the one analysed (analyze --body)",
                 frame.labels.fragment});
  add_cdf(out, "cdf/equivalent_diameter", frame.equivalent_diameter, "m", "equivalent diameter");
  add_cdf(out, "cdf/roundness", frame.roundness, "1", "roundness");
  return out;
}

}  // namespace fragmpm::analysis
