// Member folders, status files and the manifest of a sweep directory (sweep_members.hpp).
#include "fragmpm/pipeline/sweep_members.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

#include "fragmpm/pipeline/scene.hpp"

namespace fragmpm::pipeline {

namespace fs = std::filesystem;

namespace {

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Writes `text` to `path` through PATH.tmp and a rename (whole or absent after a crash).
void write_atomically(const fs::path& path, const std::string& text) {
  const fs::path tmp = path.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << text;
    out.flush();
    if (!out) throw std::runtime_error(tmp.string() + ": cannot write");
  }
  fs::rename(tmp, path);
}

}  // namespace

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        fields.back() += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        fields.back() += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      fields.emplace_back();
    } else if (c != '\r') {
      fields.back() += c;
    }
  }
  return fields;
}

std::optional<MemberStatus> read_member_status(const std::string& member_dir) {
  const fs::path p = fs::path(member_dir) / "status.txt";
  std::error_code ec;
  if (!fs::is_regular_file(p, ec)) return std::nullopt;
  std::istringstream in(slurp(p));
  std::map<std::string, std::string> kv;
  for (std::string line; std::getline(in, line);) {
    const std::size_t eq = line.find('=');
    if (eq != std::string::npos) kv[line.substr(0, eq)] = line.substr(eq + 1);
  }
  if (!kv.count("status")) return std::nullopt;
  MemberStatus s;
  s.status = kv["status"];
  try {
    s.exit_code = std::stoi(kv["exit_code"]);
    s.wall_seconds = std::stod(kv["wall_s"]);
    s.steps = std::stoll(kv["steps"]);
    s.balance_error = kv["balance_error"] == "nan" ? std::numeric_limits<double>::quiet_NaN()
                                                   : std::stod(kv["balance_error"]);
  } catch (const std::exception&) {
    return std::nullopt;  // a status file this program did not write: run the member again
  }
  s.stage = kv["stage"];
  return s;
}

bool member_finished(const std::string& member_dir) {
  const auto s = read_member_status(member_dir);
  std::error_code ec;
  const fs::path dir(member_dir);
  return s && s->status == "done" && fs::is_regular_file(dir / "run.h5", ec) &&
         fs::is_regular_file(dir / "fragments" / "fragment_series.csv", ec);
}

void write_member_status(const std::string& member_dir, const MemberStatus& s) {
  write_atomically(
      fs::path(member_dir) / "status.txt",
      fmt::format("status={}\nexit_code={}\nwall_s={:.3f}\nsteps={}\nbalance_error={}\n"
                  "stage={}\n",
                  s.status, s.exit_code, s.wall_seconds, s.steps,
                  std::isfinite(s.balance_error) ? fmt::format("{:.9g}", s.balance_error)
                                                 : std::string("nan"),
                  s.stage));
}

void write_manifest(const SweepSpec& spec, const std::string& dir) {
  std::string text = "member";
  for (const SweepAxis& a : spec.axes) {
    text += ',';
    text += csv_field(a.key);
  }
  text += ",status,exit_code,wall_s,steps,balance_error_J_per_m\n";
  for (const SweepMember& m : spec.members) {
    text += m.name;
    for (std::size_t a = 0; a < spec.axes.size(); ++a) {
      text += ',';
      text += csv_field(spec.axes[a].values[m.choice[a]]);
    }
    const auto s = read_member_status((fs::path(dir) / m.name).string());
    if (s)
      text +=
          fmt::format(",{},{},{:.3f},{},{}\n", s->status, s->exit_code, s->wall_seconds, s->steps,
                      std::isfinite(s->balance_error) ? fmt::format("{:.9g}", s->balance_error)
                                                      : std::string("nan"));
    else
      text += ",pending,,,,\n";
  }
  write_atomically(fs::path(dir) / "manifest.csv", text);
}

std::vector<ManifestRow> read_manifest(const std::string& dir) {
  const fs::path p = fs::path(dir) / "manifest.csv";
  std::ifstream in(p);
  if (!in) throw std::runtime_error(p.string() + ": cannot open (is this a sweep directory?)");
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = split_csv_line(line);
  const std::size_t fixed = 6;  // member + status, exit_code, wall_s, steps, balance_error
  if (header.size() < fixed || header[0] != "member")
    throw std::runtime_error(p.string() + ":1: not a sweep manifest header");
  std::vector<ManifestRow> rows;
  int number = 1;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty()) continue;
    const std::vector<std::string> f = split_csv_line(line);
    if (f.size() != header.size())
      throw std::runtime_error(fmt::format("{}:{}: expected {} fields, got {}", p.string(), number,
                                           header.size(), f.size()));
    ManifestRow row;
    row.member = f[0];
    const std::size_t n_values = header.size() - fixed;
    for (std::size_t k = 0; k < n_values; ++k) row.values.emplace_back(header[1 + k], f[1 + k]);
    row.status.status = f[1 + n_values];
    rows.push_back(std::move(row));
  }
  return rows;
}

void prepare_sweep_dir(const SweepSpec& spec, const std::string& dir) {
  fs::create_directories(dir);
  write_atomically(fs::path(dir) / "sweep.toml", spec.text);
  for (const SweepMember& m : spec.members) {
    const fs::path member = fs::path(dir) / m.name;
    const fs::path scene = member / "scene.toml";
    std::error_code ec;
    if (member_finished(member.string())) {
      if (fs::is_regular_file(scene, ec) && slurp(scene) != m.scene_text)
        throw SceneError(spec.path, 0, "",
                         "member " + m.name + " in " + dir +
                             " is finished with another scene than this sweep file gives it; "
                             "write this sweep to another directory");
      continue;
    }
    fs::create_directories(member);
    write_atomically(scene, m.scene_text);
  }
}

}  // namespace fragmpm::pipeline
