// Read-only run files (run_file_reader.hpp) and the layout code RunFile shares with them.
#include "fragmpm/mpm/run_file_reader.hpp"

#include <algorithm>
#include <cstdio>

#include "fragmpm/mpm/run_file.hpp"
#include "run_file_fields.hpp"

namespace fragmpm::mpm {

namespace run_file_detail {

std::string frame_name(int index) {
  char buffer[16];
  std::snprintf(buffer, sizeof buffer, "%06d", index);
  return buffer;
}

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t end = text.find('\n', start);
    lines.push_back(text.substr(start, end - start));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return lines;
}

namespace {

std::vector<ModuleDecision> parse_modules(const h5::Group& meta) {
  std::vector<ModuleDecision> modules;
  for (const std::string& line : split_lines(meta.attribute_string("modules"))) {
    const std::size_t colon = line.find(": ");
    ModuleDecision m;
    m.module = line.substr(0, colon);
    std::string rest = colon == std::string::npos ? "" : line.substr(colon + 2);
    const std::size_t separator = rest.find(kModuleSeparator);
    const std::string state = rest.substr(0, separator);
    if (colon == std::string::npos || (state != "on" && state != "off"))
      throw RunFileError(
          meta.describe("attribute 'modules': line '" + line + "' is not 'name: on|off — reason'"));
    m.active = state == "on";
    if (separator != std::string::npos)
      m.reason = rest.substr(separator + std::string(kModuleSeparator).size());
    modules.push_back(std::move(m));
  }
  return modules;
}

bool digits_only(const std::string& name) {
  return !name.empty() &&
         std::all_of(name.begin(), name.end(), [](char c) { return c >= '0' && c <= '9'; });
}

}  // namespace

RunMeta read_meta(const h5::Group& m) {
  RunMeta meta;
  meta.scene_path = m.attribute_string("scene_path");
  meta.scene_text = m.attribute_string("scene_text");
  meta.modules = parse_modules(m);
  meta.wall_names = split_lines(m.attribute_string("wall_names"));
  return meta;
}

std::vector<FrameEntry> scan_frames(const h5::Group& group) {
  std::vector<FrameEntry> frames;
  for (const std::string& name : group.children()) {
    if (!digits_only(name)) continue;
    const h5::Group g = group.open_group(name);
    FrameEntry frame;
    frame.index = std::stoi(name);
    frame.step = g.attribute_int64("step");
    frame.time = g.attribute_double("time");
    frame.points = g.open_dataset("x").rows();
    for (const std::string& field : all_frame_fields())
      if (g.exists(field)) frame.fields.push_back(field);
    frames.push_back(std::move(frame));
  }
  std::sort(frames.begin(), frames.end(),
            [](const FrameEntry& a, const FrameEntry& b) { return a.index < b.index; });
  return frames;
}

template <int D>
Particles<D> read_frame_group(const h5::Group& root, const std::string& path, int index,
                              std::size_t frame_count, double* time, long long* step) {
  const h5::Group frames = root.open_group("frames");
  const std::string name = frame_name(index);
  if (index < 0 || !frames.is_group(name))
    throw RunFileError(path + ": /frames/" + name + ": no such frame (the file has " +
                       std::to_string(frame_count) + " frames)");
  const h5::Group g = frames.open_group(name);
  if (time) *time = g.attribute_double("time");
  if (step) *step = g.attribute_int64("step");
  return read_particle_datasets<D>(g);
}

template Particles<2> read_frame_group<2>(const h5::Group&, const std::string&, int, std::size_t,
                                          double*, long long*);
template Particles<3> read_frame_group<3>(const h5::Group&, const std::string&, int, std::size_t,
                                          double*, long long*);

}  // namespace run_file_detail

using namespace run_file_detail;

bool FrameEntry::has(const std::string& field) const {
  return std::find(fields.begin(), fields.end(), field) != fields.end();
}

const std::vector<double>& RunSeries::column(const std::string& name) const {
  const auto it = columns.find(name);
  if (it == columns.end()) throw RunFileError(source + ": /series/" + name + ": no such series");
  return it->second;
}

RunFileReader::RunFileReader(h5::File file, std::string path)
    : file_(std::move(file)), path_(std::move(path)) {}

RunFileReader RunFileReader::open(const std::string& path) {
  RunFileReader reader(h5::File::open(path, false), path);
  const h5::Group root = reader.file_.root();
  for (const char* group : {"meta", "frames", "series"})
    if (!root.is_group(group))
      throw NotARunFile(path + ": not a FragMPM run file (no /" + group + " group)");
  const h5::Group meta = root.open_group("meta");
  if (!meta.has_attribute("dimension"))
    throw NotARunFile(path + ": not a FragMPM run file (/meta has no 'dimension' attribute)");
  reader.dimension_ = static_cast<int>(meta.attribute_int64("dimension"));
  if (meta.has_attribute("wall_names"))
    reader.walls_ = split_lines(meta.attribute_string("wall_names"));
  reader.frames_ = scan_frames(root.open_group("frames"));
  return reader;
}

RunMeta RunFileReader::meta() const {
  return read_meta(file_.root().open_group("meta"));
}

const FrameEntry* RunFileReader::find_frame(int index) const {
  const auto it = std::find_if(frames_.begin(), frames_.end(),
                               [&](const FrameEntry& f) { return f.index == index; });
  return it == frames_.end() ? nullptr : &*it;
}

template <int D>
Particles<D> RunFileReader::read_frame(int index, double* time, long long* step) const {
  const h5::Group root = file_.root();
  if (dimension_ != D)
    throw RunFileError(root.open_group("meta").describe("the run is " + std::to_string(dimension_) +
                                                        "D; expected " + std::to_string(D) + "D"));
  return read_frame_group<D>(root, path_, index, frames_.size(), time, step);
}

template Particles<2> RunFileReader::read_frame<2>(int, double*, long long*) const;
template Particles<3> RunFileReader::read_frame<3>(int, double*, long long*) const;

RunSeries RunFileReader::read_series(const std::vector<std::string>& only) const {
  RunSeries series;
  series.source = path_;
  series.dimension = dimension_;
  const h5::Group group = file_.root().open_group("series");
  for (const std::string& name : group.children()) {
    if (!only.empty() && std::find(only.begin(), only.end(), name) == only.end()) continue;
    if (!group.is_dataset(name)) continue;
    series.columns.emplace(name, group.read<double>(name).values);
  }
  return series;
}

RunFileReader::GroupState RunFileReader::fragment_group(const std::string& name) const {
  const h5::Group root = file_.root();
  const std::string path = "fragments/" + name;
  GroupState state;
  state.exists = root.exists(path);
  state.is_group = state.exists && root.is_group(path);
  if (state.is_group) {
    const h5::Group g = root.open_group(path);
    if (g.has_attribute("written_by")) state.written_by = g.attribute_string("written_by");
  }
  return state;
}

std::vector<double> read_series(const std::string& path, const std::string& name) {
  const h5::File file = h5::File::open(path, false);
  const h5::Group root = file.root();
  if (!root.is_dataset("series/" + name))
    throw RunFileError(path + ": /series/" + name + ": no such series");
  return root.read<double>("series/" + name).values;
}

}  // namespace fragmpm::mpm
