// Reading a sweep directory for `fragmpm pool`: manifest → groups → members' fragment tables.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <regex>

#include "fragmpm/mpm/run_file_reader.hpp"
#include "fragmpm/pipeline/pool.hpp"
#include "fragmpm/pipeline/sweep_members.hpp"

namespace fragmpm::pipeline {

namespace fs = std::filesystem;

namespace {

/// A numeric CSV table by column name.
std::map<std::string, std::vector<double>> read_csv_columns(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw PoolError(path.string() + ": cannot open");
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = split_csv_line(line);
  std::map<std::string, std::vector<double>> columns;
  for (const std::string& h : header) columns[h];
  int number = 1;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty()) continue;
    const std::vector<std::string> f = split_csv_line(line);
    if (f.size() != header.size())
      throw PoolError(fmt::format("{}:{}: expected {} fields, got {}", path.string(), number,
                                  header.size(), f.size()));
    for (std::size_t k = 0; k < f.size(); ++k) {
      double v = std::numeric_limits<double>::quiet_NaN();
      try {
        v = std::stod(f[k]);
      } catch (const std::exception&) {
      }
      columns[header[k]].push_back(v);
    }
  }
  return columns;
}

const std::vector<double>& column(const std::map<std::string, std::vector<double>>& table,
                                  const std::string& name, const fs::path& path) {
  const auto it = table.find(name);
  if (it == table.end()) throw PoolError(path.string() + ": no column " + name);
  return it->second;
}

PoolMember read_member(const fs::path& dir, const std::string& name) {
  PoolMember member;
  member.name = name;
  const fs::path frag = dir / "fragments";
  const fs::path series_path = frag / "fragment_series.csv";
  const auto series = read_csv_columns(series_path);
  const auto& frames = column(series, "frame", series_path);
  const auto& times = column(series, "time_s", series_path);
  const auto platen = series.find("platen_displacement_m");
  std::vector<int> analysed;
  const std::regex pattern("fragments_([0-9]{6})\\.csv");
  for (const auto& e : fs::directory_iterator(frag)) {
    std::smatch m;
    const std::string file = e.path().filename().string();
    if (std::regex_match(file, m, pattern)) analysed.push_back(std::stoi(m[1].str()));
  }
  std::sort(analysed.begin(), analysed.end());
  if (analysed.empty()) throw PoolError(frag.string() + ": no fragments_NNNNNN.csv tables");

  const fs::path run = dir / "run.h5";
  std::vector<double> run_time, wall_work;
  try {
    const mpm::RunSeries s =
        mpm::RunFileReader::open(run.string()).read_series({"time", "wall_work"});
    run_time = s.column("time");
    wall_work = s.column("wall_work");
  } catch (const mpm::RunFileError& e) {
    throw PoolError(e.what());
  }
  for (int index : analysed) {
    PoolFrame f;
    f.frame = index;
    const auto row = std::find(frames.begin(), frames.end(), double(index));
    if (row == frames.end())
      throw PoolError(fmt::format("{}: no row for frame {}", series_path.string(), index));
    const std::size_t r = static_cast<std::size_t>(row - frames.begin());
    f.time = times[r];
    f.platen_displacement =
        platen != series.end() ? platen->second[r] : std::numeric_limits<double>::quiet_NaN();
    // The series row of the frame's step: frames are written at step ends, so the time matches
    // a /series time exactly; the nearest row is taken in case of rounding in the CSV.
    std::size_t best = 0;
    for (std::size_t k = 1; k < run_time.size(); ++k)
      if (std::abs(run_time[k] - f.time) < std::abs(run_time[best] - f.time)) best = k;
    f.wall_work = wall_work.empty() ? 0.0 : wall_work[best];
    const std::string n = fmt::format("{:06d}", index);
    const fs::path table_path = frag / ("fragments_" + n + ".csv");
    const fs::path fines_path = frag / ("fines_" + n + ".csv");
    const auto table = read_csv_columns(table_path);
    f.d = column(table, "equivalent_diameter_m", table_path);
    f.roundness = column(table, "roundness", table_path);
    f.mass = column(table, "mass_kg_per_m", table_path);
    f.all_d = f.d;
    f.all_mass = f.mass;
    std::vector<double> per_particle;
    const auto& area = column(table, "area_m2", table_path);
    const auto& particles = column(table, "particles", table_path);
    for (std::size_t i = 0; i < area.size(); ++i)
      if (particles[i] > 0) per_particle.push_back(area[i] / particles[i]);
    if (fs::exists(fines_path)) {
      const auto fines = read_csv_columns(fines_path);
      const auto& fd = column(fines, "equivalent_diameter_m", fines_path);
      const auto& fm = column(fines, "mass_kg_per_m", fines_path);
      f.all_d.insert(f.all_d.end(), fd.begin(), fd.end());
      f.all_mass.insert(f.all_mass.end(), fm.begin(), fm.end());
    }
    if (!per_particle.empty()) {
      std::nth_element(per_particle.begin(), per_particle.begin() + per_particle.size() / 2,
                       per_particle.end());
      f.particle_size = std::sqrt(4.0 * per_particle[per_particle.size() / 2] / M_PI);
    }
    member.frames.push_back(std::move(f));
  }
  return member;
}

}  // namespace

std::vector<PoolGroup> read_pool_groups(const std::string& dir, std::FILE* log) {
  std::vector<ManifestRow> rows;
  try {
    rows = read_manifest(dir);
  } catch (const std::runtime_error& e) {
    throw PoolError(e.what());
  }
  std::vector<PoolGroup> groups;
  std::size_t skipped = 0;
  for (const ManifestRow& row : rows) {
    if (row.status.status != "done") {
      ++skipped;
      continue;
    }
    std::vector<std::pair<std::string, std::string>> values;
    for (const auto& kv : row.values)
      if (kv.first != "seed") values.push_back(kv);
    auto it = std::find_if(groups.begin(), groups.end(),
                           [&](const PoolGroup& g) { return g.values == values; });
    if (it == groups.end()) {
      PoolGroup g;
      g.values = values;
      for (const auto& [k, v] : values) g.label += (g.label.empty() ? "" : ", ") + k + " = " + v;
      if (g.label.empty()) g.label = "all members";
      groups.push_back(std::move(g));
      it = groups.end() - 1;
    }
    it->members.push_back(read_member(fs::path(dir) / row.member, row.member));
  }
  if (log && skipped > 0)
    std::fprintf(log, "fragmpm pool: %zu member(s) not finished are left out\n", skipped);
  if (groups.empty()) throw PoolError(dir + ": no finished member to pool");
  return groups;
}

}  // namespace fragmpm::pipeline
