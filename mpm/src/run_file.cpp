// The run file of docs/design.md on top of hdf5_io; see run_file.hpp for the layout.
#include "fragmpm/mpm/run_file.hpp"

#include <algorithm>
#include <bit>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <set>

#include "fragmpm/mpm/build_info.hpp"
#include "fragmpm/mpm/hdf5_io.hpp"
#include "fragmpm/mpm/xdmf.hpp"
#include "run_file_fields.hpp"

namespace fragmpm::mpm {

const std::vector<std::string>& all_frame_fields() {
  static const std::vector<std::string> fields{
      "x",      "v",      "F",       "volume0", "mass",     "r1",          "r2",
      "stress", "damage", "surface", "body",    "material", "temperature", "id"};
  return fields;
}

namespace {

using namespace run_file_detail;

// ---- /meta

std::string module_lines(const std::vector<ModuleDecision>& modules) {
  std::string text;
  for (const ModuleDecision& m : modules) {
    std::string reason = m.reason;
    std::replace(reason.begin(), reason.end(), '\n', ' ');  // one line per module
    text += m.module + ": " + (m.active ? "on" : "off");
    if (!reason.empty()) text += kModuleSeparator + reason;
    text += '\n';
  }
  return text;
}

// ---- /series columns: name, units, how to read the value from a row

template <int D>
struct ScalarColumn {
  const char* name;
  const char* description;
  bool energy;  ///< units J (per unit thickness in 2D); otherwise `units`
  const char* units;
  std::function<double(const SeriesRow<D>&)> value;
  /// Added after run files existed without it: a restarted older file goes on without the column.
  bool optional = false;
};

template <int D>
const std::vector<ScalarColumn<D>>& scalar_columns() {
  using R = SeriesRow<D>;
  static const std::vector<ScalarColumn<D>> columns{
      {"time", "time at the end of the step", false, "s", [](const R& r) { return r.time; }},
      {"dt", "step length", false, "s", [](const R& r) { return r.dt; }},
      {"kinetic", "kinetic energy", true, "", [](const R& r) { return r.kinetic; }},
      {"strain", "stored strain energy", true, "", [](const R& r) { return r.strain; }},
      {"thermal", "thermal energy", true, "", [](const R& r) { return r.thermal; }},
      {"dissipated", "dissipated by damage (cumulative)", true, "",
       [](const R& r) { return r.totals.dissipated; }},
      {"flow_dissipation", "dissipated by the frictional flow of failed material (cumulative)",
       true, "", [](const R& r) { return r.totals.flow_dissipation; }, true},
      {"friction_work", "dissipated by friction (cumulative)", true, "",
       [](const R& r) { return r.totals.friction_work; }},
      {"contact_dissipation",
       "plastic collision loss of grid contact and walls, beyond friction (cumulative)", true, "",
       [](const R& r) { return r.totals.contact_dissipation; }},
      {"transfer_dissipation",
       "kinetic energy the grid-to-particle transfer removes (FLIP smoothing, PIC projection; "
       "cumulative)",
       true, "", [](const R& r) { return r.totals.transfer_dissipation; }, true},
      {"fracture_energy",
       "crack energy of the phase field, G_c times the regularised crack area ([KT19] eq. (3))",
       true, "", [](const R& r) { return r.totals.fracture_energy; }, true},
      {"history_excess",
       "phase field: energy the crack growth took from the history field beyond the tensile "
       "energy its degradation released, sum of V0 (g_old - g_new)(H - psi+) (cumulative; counted "
       "as put in)",
       true, "", [](const R& r) { return r.totals.history_excess; }, true},
      {"wall_work", "work of the walls on the material (cumulative)", true, "",
       [](const R& r) { return r.totals.wall_work; }},
      {"gravity_work", "work of gravity (cumulative)", true, "",
       [](const R& r) { return r.totals.gravity_work; }},
      {"load_work", "work of the traction loads (cumulative)", true, "",
       [](const R& r) { return r.totals.load_work; }},
      {"balance_error", "energy balance error, see series.hpp", true, "",
       [](const R& r) { return r.balance_error; }},
      {"lost_mass", "mass of the particles removed after leaving the domain (cumulative)", false,
       D == 2 ? "kg/m (per unit thickness)" : "kg", [](const R& r) { return r.totals.lost.mass; },
       true},
      {"lost_kinetic",
       "kinetic energy of the particles removed after leaving the domain, at removal (cumulative)",
       true, "", [](const R& r) { return r.totals.lost.kinetic; }, true},
      {"lost_strain",
       "stored strain energy of the particles removed after leaving the domain, at removal "
       "(cumulative)",
       true, "", [](const R& r) { return r.totals.lost.strain; }, true},
  };
  return columns;
}

const char* energy_units(int dimension) {
  return dimension == 2 ? "J/m (per unit thickness)" : "J";
}

std::string wall_force_name(const std::string& wall) {
  return "wall_" + wall + "_force";
}
std::string wall_displacement_name(const std::string& wall) {
  return "wall_" + wall + "_displacement";
}

}  // namespace

// ---------------------------------------------------------------- Impl

template <int D>
struct RunFile<D>::Impl {
  using Frame = FrameEntry;

  h5::File file;
  std::string path;
  std::string xmf_path;
  std::vector<std::string> wall_names;
  std::vector<Frame> frames;  ///< sorted by index
  /// /series datasets, kept open: reopening them for every append costs ~10x the append itself,
  /// because closing a chunked dataset writes its chunk cache back.
  std::map<std::string, h5::Dataset> series;

  explicit Impl(h5::File f, std::string p) : file(std::move(f)), path(std::move(p)) {
    xmf_path = std::filesystem::path(path).replace_extension(".xmf").string();
  }

  h5::Group root() const { return file.root(); }

  /// Opens every /series dataset and checks that the ones this run appends to exist.
  void open_series() {
    const h5::Group group = root().open_group("series");
    series.clear();
    for (const std::string& name : group.children()) series.emplace(name, group.open_dataset(name));
    std::vector<std::string> required{"step", "momentum"};
    for (const ScalarColumn<D>& c : scalar_columns<D>())
      if (!c.optional) required.push_back(c.name);
    for (const std::string& w : wall_names) {
      required.push_back(wall_force_name(w));
      required.push_back(wall_displacement_name(w));
    }
    for (const std::string& name : required)
      if (!series.count(name)) throw RunFileError(group.describe("missing dataset '" + name + "'"));
  }

  const h5::Dataset& series_dataset(const std::string& name) const { return series.at(name); }

  /// 2D runs: the group of the 3-component copies of frame `index`'s vectors and tensors that the
  /// XDMF file points at (see xdmf.hpp).
  static std::string padded_group(int index) { return "xdmf/frames/" + frame_name(index); }

  /// Writes the padded copies a 2D frame lacks (all of them for a new frame or a run file written
  /// before they existed); returns true when it wrote any.
  bool write_padded_copies(const Frame& frame) const {
    if (D != 2) return false;
    bool wrote = false;
    const h5::Group r = root();
    for (const std::string& name : frame.fields) {
      const FieldInfo info = field_info<D>(name);
      if (name == "x" || info.kind == XdmfField::Kind::scalar) continue;
      const std::string target = padded_group(frame.index);
      if (r.exists(target + "/" + name)) continue;
      write_padded_copy(r.open_group("frames/" + frame_name(frame.index)), r.require_group(target),
                        name, info.kind, name == "F" ? 1.0 : 0.0);
      wrote = true;
    }
    return wrote;
  }

  /// Removes frame `index` and its padded copies.
  void remove_frame(int index) const {
    const h5::Group r = root();
    if (r.exists("frames/" + frame_name(index))) r.remove("frames/" + frame_name(index));
    if (r.exists(padded_group(index))) r.remove(padded_group(index));
  }

  /// Writes /xdmf/point_ids = 0 … N−1 for the largest frame (connectivity for the XDMF Polyvertex
  /// topology; see xdmf.hpp) and the padded copies of 2D frames, then the .xmf file.
  void rewrite_xdmf() const {
    std::size_t largest = 0;
    bool wrote = false;
    for (const Frame& frame : frames) {
      largest = std::max(largest, frame.points);
      wrote = write_padded_copies(frame) || wrote;
    }
    const h5::Group r = root();
    std::size_t ids = r.is_dataset("xdmf/point_ids") ? r.open_dataset("xdmf/point_ids").rows() : 0;
    if (ids < largest) {
      std::vector<std::int32_t> values(largest);
      for (std::size_t p = 0; p < largest; ++p) values[p] = static_cast<std::int32_t>(p);
      r.write("xdmf/point_ids", values, {largest})
          .set_attribute("description",
                         "0 ... N-1: point connectivity for the XDMF file beside this one");
      ids = largest;
      wrote = true;
    }
    if (wrote) file.flush();  // the .xmf must never point at data that is not on disk yet
    std::vector<XdmfFrame> light;
    for (const Frame& frame : frames) {
      XdmfFrame f;
      f.group = std::string("/frames/") + frame_name(frame.index);
      f.time = frame.time;
      f.points = frame.points;
      for (const std::string& name : frame.fields) {
        if (name == "x") continue;  // the geometry
        const FieldInfo info = field_info<D>(name);
        const bool padded = D == 2 && info.kind != XdmfField::Kind::scalar;
        f.fields.push_back(
            {name, info.kind, info.number,
             padded ? std::string("/") + padded_group(frame.index) + "/" + name : ""});
      }
      light.push_back(std::move(f));
    }
    write_xdmf(xmf_path, std::filesystem::path(path).filename().string(), D, light,
               "/xdmf/point_ids", ids);
  }

  /// Rebuilds the frame list from the file (when opening an existing run).
  void scan_frames() { frames = run_file_detail::scan_frames(root().open_group("frames")); }
};

template <int D>
RunFile<D>::RunFile(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
template <int D>
RunFile<D>::RunFile(RunFile&&) noexcept = default;
template <int D>
RunFile<D>& RunFile<D>::operator=(RunFile&&) noexcept = default;
template <int D>
RunFile<D>::~RunFile() = default;

template <int D>
const std::string& RunFile<D>::path() const {
  return impl_->path;
}

template <int D>
RunFile<D> RunFile<D>::create(const std::string& path, const RunMeta& meta, bool overwrite) {
  // Wall names become dataset names (wall_<name>_force) and lines of /meta wall_names.
  for (std::size_t w = 0; w < meta.wall_names.size(); ++w) {
    const std::string& name = meta.wall_names[w];
    if (name.empty() || name.find_first_of("/\n") != std::string::npos ||
        std::find(meta.wall_names.begin(), meta.wall_names.begin() + static_cast<std::ptrdiff_t>(w),
                  name) != meta.wall_names.begin() + static_cast<std::ptrdiff_t>(w))
      throw RunFileError(path + ": wall name '" + name +
                         "' must be non-empty, unique and free of '/' and line breaks");
  }
  auto impl = std::make_unique<Impl>(h5::File::create(path, overwrite), path);
  impl->wall_names = meta.wall_names;
  const h5::Group root = impl->root();

  const h5::Group m = root.require_group("meta");
  m.set_attribute("program_version", program_version());
  m.set_attribute("git_hash", program_git_hash());
  m.set_attribute("scene_path", meta.scene_path);
  m.set_attribute("scene_text", meta.scene_text);
  m.set_attribute("unit_system", "SI; 2D quantities per unit thickness");
  m.set_attribute("dimension", static_cast<std::int64_t>(D));
  m.set_attribute("modules", module_lines(meta.modules));
  std::string walls;
  for (const std::string& w : meta.wall_names) walls += w + "\n";
  m.set_attribute("wall_names", walls);

  root.require_group("frames");
  const h5::Group series = root.require_group("series");
  for (const ScalarColumn<D>& c : scalar_columns<D>()) {
    const h5::Dataset ds = series.create_extendible<double>(c.name, {});
    ds.set_attribute("units", c.energy ? energy_units(D) : c.units);
    ds.set_attribute("description", c.description);
  }
  const h5::Dataset step = series.create_extendible<std::int64_t>("step", {});
  step.set_attribute("units", "1");
  step.set_attribute("description", "step number of the row");
  const h5::Dataset momentum = series.create_extendible<double>("momentum", {std::size_t{D}});
  momentum.set_attribute("units",
                         D == 2 ? "kg/s (momentum per unit thickness, kg m/s per m)" : "kg m/s");
  momentum.set_attribute("description", "total momentum, steps x D");
  const std::size_t axial_size = D == 2 ? 1 : 3;
  const h5::Dataset angular = series.create_extendible<double>("angular_momentum", {axial_size});
  angular.set_attribute("units", D == 2 ? "kg m/s (angular momentum per unit thickness, kg m²/s "
                                          "per m), about the origin"
                                        : "kg m²/s, about the origin");
  angular.set_attribute("description",
                        D == 2 ? "total angular momentum (out-of-plane component), steps x 1"
                               : "total angular momentum, steps x 3");
  const h5::Dataset lost = series.create_extendible<double>("lost_momentum", {std::size_t{D}});
  lost.set_attribute("units",
                     D == 2 ? "kg/s (momentum per unit thickness, kg m/s per m)" : "kg m/s");
  lost.set_attribute("description",
                     "momentum of the particles removed after leaving the domain, at removal "
                     "(cumulative), steps x D");
  for (const std::string& w : meta.wall_names) {
    const h5::Dataset force =
        series.create_extendible<double>(wall_force_name(w), {std::size_t{D}});
    force.set_attribute("units", D == 2 ? "N/m (per unit thickness)" : "N");
    force.set_attribute("description", "reaction exerted by the material on the wall, steps x D");
    const h5::Dataset disp =
        series.create_extendible<double>(wall_displacement_name(w), {std::size_t{D}});
    disp.set_attribute("units", "m");
    disp.set_attribute("description", "wall displacement since t = 0, steps x D");
  }
  impl->open_series();
  impl->file.flush();
  impl->rewrite_xdmf();
  return RunFile(std::move(impl));
}

template <int D>
RunFile<D> RunFile<D>::open_existing(const std::string& path) {
  auto impl = std::make_unique<Impl>(h5::File::open(path, true), path);
  const h5::Group root = impl->root();
  for (const char* group : {"meta", "frames", "series"})
    if (!root.is_group(group))
      throw RunFileError(path + ": /" + group + ": missing; not a FragMPM run file");
  const h5::Group meta = root.open_group("meta");
  const std::int64_t dimension = meta.attribute_int64("dimension");
  if (dimension != D)
    throw RunFileError(meta.describe("the run is " + std::to_string(dimension) + "D; expected " +
                                     std::to_string(D) + "D"));
  impl->wall_names = split_lines(meta.attribute_string("wall_names"));
  impl->open_series();
  impl->scan_frames();
  impl->rewrite_xdmf();
  return RunFile(std::move(impl));
}

template <int D>
RunMeta RunFile<D>::meta() const {
  return read_meta(impl_->root().open_group("meta"));
}

template <int D>
int RunFile<D>::write_frame(long long step, double time, const Particles<D>& particles,
                            const std::vector<std::string>& fields) {
  const auto& known = all_frame_fields();
  std::set<std::string> wanted(fields.begin(), fields.end());
  for (const std::string& f : wanted) {
    if (std::find(known.begin(), known.end(), f) == known.end()) {
      std::string list;
      for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
      throw RunFileError(impl_->path + ": unknown frame field '" + f + "' (expected one of " +
                         list + ")");
    }
  }
  const std::size_t n = particles.size();
  const int index = impl_->frames.empty() ? 0 : impl_->frames.back().index + 1;
  const std::string name = frame_name(index);
  const h5::Group frames = impl_->root().open_group("frames");
  impl_->remove_frame(index);
  const h5::Group g = frames.require_group(name);
  g.set_attribute("time", time);
  g.set_attribute("step", static_cast<std::int64_t>(step));

  typename Impl::Frame frame{index, step, time, n,
                             write_particle_datasets<D>(g, particles, fields)};
  impl_->frames.push_back(std::move(frame));
  impl_->file.flush();
  impl_->rewrite_xdmf();
  return index;
}

template <int D>
void RunFile<D>::append_series(const std::vector<SeriesRow<D>>& rows) {
  if (rows.empty()) return;
  const std::size_t walls = impl_->wall_names.size();
  for (const SeriesRow<D>& r : rows)
    if (r.wall_force.size() != walls || r.wall_displacement.size() != walls)
      throw RunFileError(impl_->path + ": /series: the row of step " + std::to_string(r.step) +
                         " has " + std::to_string(r.wall_force.size()) + " wall forces and " +
                         std::to_string(r.wall_displacement.size()) +
                         " displacements; the run has " + std::to_string(walls) + " walls");
  std::vector<double> column(rows.size());
  for (const ScalarColumn<D>& c : scalar_columns<D>()) {
    if (c.optional && !impl_->series.count(c.name)) continue;
    for (std::size_t k = 0; k < rows.size(); ++k) column[k] = c.value(rows[k]);
    impl_->series_dataset(c.name).append_rows(column);
  }
  std::vector<std::int64_t> steps(rows.size());
  for (std::size_t k = 0; k < rows.size(); ++k) steps[k] = rows[k].step;
  impl_->series_dataset("step").append_rows(steps);
  std::vector<Vec<D>> vectors(rows.size());
  for (std::size_t k = 0; k < rows.size(); ++k) vectors[k] = rows[k].momentum;
  impl_->series_dataset("momentum").append_rows(pack<D>(vectors));
  if (impl_->series.count("lost_momentum")) {
    for (std::size_t k = 0; k < rows.size(); ++k)
      for (int i = 0; i < D; ++i)
        vectors[k][i] = rows[k].totals.lost.momentum[static_cast<std::size_t>(i)];
    impl_->series_dataset("lost_momentum").append_rows(pack<D>(vectors));
  }
  // Run files from before the angular momentum series resume without it.
  if (impl_->series.count("angular_momentum")) {
    constexpr int A = Axial<D>::RowsAtCompileTime;
    std::vector<double> angular(rows.size() * A);
    for (std::size_t k = 0; k < rows.size(); ++k)
      for (int a = 0; a < A; ++a) angular[k * A + a] = rows[k].angular_momentum[a];
    impl_->series_dataset("angular_momentum").append_rows(angular);
  }
  for (std::size_t w = 0; w < walls; ++w) {
    for (std::size_t k = 0; k < rows.size(); ++k) vectors[k] = rows[k].wall_force[w];
    impl_->series_dataset(wall_force_name(impl_->wall_names[w])).append_rows(pack<D>(vectors));
    for (std::size_t k = 0; k < rows.size(); ++k) vectors[k] = rows[k].wall_displacement[w];
    impl_->series_dataset(wall_displacement_name(impl_->wall_names[w]))
        .append_rows(pack<D>(vectors));
  }
  impl_->file.flush();
}

namespace {
/// The checkpoint's datasets of the system the kept multigrid levels were built from.
constexpr const char* phase_field_levels_datasets[] = {
    "phase_field_levels_outer", "phase_field_levels_inner", "phase_field_levels_values"};

/// The length a dataset of `n` values is stored with: n rounded up to a sixteenth of the next
/// power of two (at most 6.25 % more).
std::size_t stored_capacity(std::size_t n) {
  if (n == 0) return 0;
  const std::size_t step = std::max<std::size_t>(1, std::bit_ceil(n) / 16);
  return (n + step - 1) / step * step;
}

/// Accumulators stored as /checkpoint attributes, so a restart resumes the energy balance exactly.
const std::vector<std::pair<const char*, double EnergyAccumulators::*>>& accumulator_fields() {
  static const std::vector<std::pair<const char*, double EnergyAccumulators::*>> fields{
      {"wall_work", &EnergyAccumulators::wall_work},
      {"gravity_work", &EnergyAccumulators::gravity_work},
      {"load_work", &EnergyAccumulators::load_work},
      {"friction_work", &EnergyAccumulators::friction_work},
      {"dissipated", &EnergyAccumulators::dissipated},
      {"flow_dissipation", &EnergyAccumulators::flow_dissipation},
      {"contact_dissipation", &EnergyAccumulators::contact_dissipation},
      {"transfer_dissipation", &EnergyAccumulators::transfer_dissipation},
      {"initial_energy", &EnergyAccumulators::initial_energy},
      {"fracture_energy", &EnergyAccumulators::fracture_energy},
      {"history_excess", &EnergyAccumulators::history_excess},
  };
  return fields;
}

/// What the removed particles carried out of the domain, as /checkpoint attributes (with
/// lost_particles, the count, and lost_momentum_x, _y, _z).
const std::vector<std::pair<const char*, double LostParticles::*>>& lost_fields() {
  static const std::vector<std::pair<const char*, double LostParticles::*>> fields{
      {"lost_mass", &LostParticles::mass},
      {"lost_kinetic", &LostParticles::kinetic},
      {"lost_strain", &LostParticles::strain},
  };
  return fields;
}

std::string lost_momentum_name(int component) {
  return std::string("lost_momentum_") + "xyz"[component];
}
}  // namespace

template <int D>
void RunFile<D>::write_checkpoint(const Checkpoint<D>& checkpoint) {
  const Particles<D>& p = checkpoint.particles;
  const std::size_t n = p.size(), d = D;
  const h5::Group g = impl_->root().require_group("checkpoint");
  // Marked incomplete while the datasets are overwritten, so a run killed mid-write is detected.
  g.set_attribute("complete", std::int64_t{0});
  g.write("x", pack<D>(p.x), {n, d});
  g.write("v", pack<D>(p.v), {n, d});
  g.write("affine", pack<D>(p.affine), {n, d, d});
  g.write("F", pack<D>(p.F), {n, d, d});
  g.write("volume0", p.volume0, {n});
  g.write("mass", p.mass, {n});
  g.write("domain", pack<D>(p.domain), {n, d, d});
  g.write("stress", pack<D>(p.stress), {n, d, d});
  g.write("damage", p.damage, {n});
  g.write("damage_history", p.damage_history, {n});
  g.write("surface", p.surface, {n});
  g.write("body", p.body, {n});
  g.write("material", p.material, {n});
  g.write("strength", p.strength, {n});
  g.write("id", particle_ids(p), {n});
  if (!p.plastic_inverse.empty())
    g.write("plastic_inverse", pack<D>(p.plastic_inverse), {n, d, d});
  else if (g.exists("plastic_inverse"))
    g.remove("plastic_inverse");
  if (!p.temperature.empty())
    g.write("temperature", p.temperature, {n});
  else if (g.exists("temperature"))
    g.remove("temperature");
  // The phase-field warm start: the last nodal solution by global node and field.
  const PhaseFieldWarmStart<D>& pf = checkpoint.phase_field;
  if (!pf.empty()) {
    const std::size_t m = pf.solution.size();
    std::vector<std::int64_t> nodes(m * d);
    for (std::size_t r = 0; r < m; ++r)
      for (std::size_t k = 0; k < d; ++k) nodes[r * d + k] = pf.node[r][static_cast<int>(k)];
    g.write("phase_field_node", nodes, {m, d});
    g.write("phase_field_field", pf.field, {m});
    g.write("phase_field_solution", pf.solution, {m});
    if (pf.previous.size() == m)
      g.write("phase_field_previous", pf.previous, {m});
    else if (g.exists("phase_field_previous"))
      g.remove("phase_field_previous");
    g.set_attribute("phase_field_direct_solves_left", std::int64_t{pf.direct_solves_left});
    g.set_attribute("phase_field_direct_run", std::int64_t{pf.direct_run});
    g.set_attribute("phase_field_multigrid", std::int64_t{pf.multigrid});
    g.set_attribute("phase_field_average_iterations", pf.average_iterations);
    // The system the kept multigrid levels come from (the restarted run builds the same).
    // Stored padded to a capacity, with the lengths as attributes: a later checkpoint whose
    // system has a few more or fewer entries then overwrites the datasets in place instead of
    // leaving their old space behind (tens of MB on the plate at h = 0.125 mm).
    if (!pf.levels_values.empty()) {
      const auto padded = [](auto values) {
        values.resize(stored_capacity(values.size()), 0);
        return values;
      };
      const std::size_t rows = stored_capacity(pf.levels_outer.size());
      const std::size_t entries = stored_capacity(pf.levels_values.size());
      g.write("phase_field_levels_outer", padded(pf.levels_outer), {rows});
      g.write("phase_field_levels_inner", padded(pf.levels_inner), {entries});
      g.write("phase_field_levels_values", padded(pf.levels_values), {entries});
      g.set_attribute("phase_field_levels_rows", static_cast<std::int64_t>(pf.levels_outer.size()));
      g.set_attribute("phase_field_levels_entries",
                      static_cast<std::int64_t>(pf.levels_values.size()));
    } else {
      for (const char* name : phase_field_levels_datasets)
        if (g.exists(name)) g.remove(name);
    }
    g.set_attribute("phase_field_levels_age", std::int64_t{pf.levels_age});
    g.set_attribute("phase_field_levels_cycles", std::int64_t{pf.levels_cycles});
    g.set_attribute("phase_field_last_cycles", std::int64_t{pf.last_cycles});
  } else {
    for (const char* name :
         {"phase_field_node", "phase_field_field", "phase_field_solution", "phase_field_previous"})
      if (g.exists(name)) g.remove(name);
    for (const char* name : phase_field_levels_datasets)
      if (g.exists(name)) g.remove(name);
  }
  g.set_attribute("time", checkpoint.time);
  g.set_attribute("step", static_cast<std::int64_t>(checkpoint.step));
  for (const auto& [name, member] : accumulator_fields())
    g.set_attribute(name, checkpoint.totals.*member);
  const LostParticles& lost = checkpoint.totals.lost;
  g.set_attribute("lost_particles", static_cast<std::int64_t>(lost.count));
  for (const auto& [name, member] : lost_fields()) g.set_attribute(name, lost.*member);
  for (int k = 0; k < D; ++k)
    g.set_attribute(lost_momentum_name(k), lost.momentum[static_cast<std::size_t>(k)]);
  g.set_attribute("complete", std::int64_t{1});
  impl_->file.flush();
}

template <int D>
std::optional<Checkpoint<D>> RunFile<D>::read_checkpoint() const {
  const h5::Group root = impl_->root();
  if (!root.exists("checkpoint")) return std::nullopt;
  const h5::Group g = root.open_group("checkpoint");
  if (!g.has_attribute("complete") || g.attribute_int64("complete") != 1)
    throw RunFileError(g.describe("incomplete checkpoint (the run stopped while writing it)"));
  Checkpoint<D> c;
  c.time = g.attribute_double("time");
  c.step = g.attribute_int64("step");
  for (const auto& [name, member] : accumulator_fields())
    if (g.has_attribute(name)) c.totals.*member = g.attribute_double(name);
  // Checkpoints from before particles could be removed have none of these: nothing was lost.
  LostParticles& lost = c.totals.lost;
  if (g.has_attribute("lost_particles")) lost.count = g.attribute_int64("lost_particles");
  for (const auto& [name, member] : lost_fields())
    if (g.has_attribute(name)) lost.*member = g.attribute_double(name);
  for (int k = 0; k < D; ++k)
    if (g.has_attribute(lost_momentum_name(k)))
      lost.momentum[static_cast<std::size_t>(k)] = g.attribute_double(lost_momentum_name(k));
  const std::size_t n = g.open_dataset("x").rows(), d = D;
  Particles<D>& p = c.particles;
  p.resize(n, g.exists("temperature"));
  unpack<D>(read_shaped<double>(g, "x", {n, d}), p.x);
  unpack<D>(read_shaped<double>(g, "v", {n, d}), p.v);
  // Run files from before APIC have no affine matrices: zero, as a FLIP run carries.
  if (g.exists("affine")) unpack<D>(read_shaped<double>(g, "affine", {n, d, d}), p.affine);
  unpack<D>(read_shaped<double>(g, "F", {n, d, d}), p.F);
  p.volume0 = read_shaped<double>(g, "volume0", {n});
  p.mass = read_shaped<double>(g, "mass", {n});
  unpack<D>(read_shaped<double>(g, "domain", {n, d, d}), p.domain);
  unpack<D>(read_shaped<double>(g, "stress", {n, d, d}), p.stress);
  p.damage = read_shaped<double>(g, "damage", {n});
  p.damage_history = read_shaped<double>(g, "damage_history", {n});
  p.surface = read_shaped<std::uint8_t>(g, "surface", {n});
  p.body = read_shaped<std::int32_t>(g, "body", {n});
  p.material = read_shaped<std::int32_t>(g, "material", {n});
  p.strength = read_shaped<double>(g, "strength", {n});
  if (!p.temperature.empty()) p.temperature = read_shaped<double>(g, "temperature", {n});
  if (g.exists("plastic_inverse")) {
    p.plastic_inverse.resize(n);
    unpack<D>(read_shaped<double>(g, "plastic_inverse", {n, d, d}), p.plastic_inverse);
  }
  if (g.exists("id")) p.id = read_shaped<std::int32_t>(g, "id", {n});
  // Checkpoints from before the warm start have none: the next solve starts from the particles.
  if (g.exists("phase_field_solution")) {
    PhaseFieldWarmStart<D>& pf = c.phase_field;
    const std::size_t m = g.open_dataset("phase_field_solution").rows();
    pf.solution = read_shaped<double>(g, "phase_field_solution", {m});
    pf.field = read_shaped<std::int32_t>(g, "phase_field_field", {m});
    if (g.exists("phase_field_previous"))
      pf.previous = read_shaped<double>(g, "phase_field_previous", {m});
    const std::vector<std::int64_t> nodes =
        read_shaped<std::int64_t>(g, "phase_field_node", {m, d});
    pf.node.resize(m);
    for (std::size_t r = 0; r < m; ++r)
      for (std::size_t k = 0; k < d; ++k) pf.node[r][static_cast<int>(k)] = nodes[r * d + k];
    if (g.has_attribute("phase_field_direct_solves_left")) {
      pf.direct_solves_left =
          static_cast<std::int32_t>(g.attribute_int64("phase_field_direct_solves_left"));
      pf.direct_run = static_cast<std::int32_t>(g.attribute_int64("phase_field_direct_run"));
    } else if (g.has_attribute("phase_field_direct") &&
               g.attribute_int64("phase_field_direct") != 0) {
      // Checkpoints from when a direct solve stayed direct for good: a first run of them.
      pf.direct_solves_left = pf.direct_run = first_direct_run;
    }
    // Checkpoints from before the multigrid preconditioner: the next solves use the crack block
    // until one needs more than multigrid_switch_iterations.
    if (g.has_attribute("phase_field_multigrid"))
      pf.multigrid = static_cast<std::int32_t>(g.attribute_int64("phase_field_multigrid"));
    if (g.has_attribute("phase_field_average_iterations"))
      pf.average_iterations = g.attribute_double("phase_field_average_iterations");
    // Checkpoints from before the levels were kept: the next multigrid solve builds them.
    if (g.exists("phase_field_levels_values")) {
      const std::size_t rows =
          static_cast<std::size_t>(g.attribute_int64("phase_field_levels_rows"));
      const std::size_t entries =
          static_cast<std::size_t>(g.attribute_int64("phase_field_levels_entries"));
      if (rows != m + 1)
        throw RunFileError(g.describe("phase_field_levels_outer has " + std::to_string(rows) +
                                      " rows; expected one more than the " + std::to_string(m) +
                                      " phase-field unknowns"));
      pf.levels_outer =
          read_shaped<std::int32_t>(g, "phase_field_levels_outer", {stored_capacity(rows)});
      pf.levels_inner =
          read_shaped<std::int32_t>(g, "phase_field_levels_inner", {stored_capacity(entries)});
      pf.levels_values =
          read_shaped<double>(g, "phase_field_levels_values", {stored_capacity(entries)});
      pf.levels_outer.resize(rows);
      pf.levels_inner.resize(entries);
      pf.levels_values.resize(entries);
      if (pf.levels_outer.front() != 0 ||
          pf.levels_outer.back() != static_cast<std::int32_t>(entries) ||
          !std::is_sorted(pf.levels_outer.begin(), pf.levels_outer.end()) ||
          std::any_of(pf.levels_inner.begin(), pf.levels_inner.end(),
                      [&](std::int32_t j) { return j < 0 || static_cast<std::size_t>(j) >= m; }))
        throw RunFileError(
            g.describe("phase_field_levels_outer / _inner do not describe compressed rows over "
                       "the phase-field unknowns"));
      pf.levels_age = static_cast<std::int32_t>(g.attribute_int64("phase_field_levels_age"));
      pf.levels_cycles = static_cast<std::int32_t>(g.attribute_int64("phase_field_levels_cycles"));
      pf.last_cycles = static_cast<std::int32_t>(g.attribute_int64("phase_field_last_cycles"));
    }
  }
  return c;
}

template <int D>
void RunFile<D>::truncate_after(long long step) {
  auto& list = impl_->frames;
  for (const auto& f : list)
    if (f.step > step) impl_->remove_frame(f.index);
  list.erase(std::remove_if(list.begin(), list.end(), [&](const auto& f) { return f.step > step; }),
             list.end());

  // Rows are in step order: keep the leading rows with step ≤ `step`.
  const std::vector<std::int64_t> steps =
      impl_->series_dataset("step").template read<std::int64_t>().values;
  const std::size_t keep = static_cast<std::size_t>(
      std::find_if(steps.begin(), steps.end(), [&](std::int64_t s) { return s > step; }) -
      steps.begin());
  for (const auto& [name, dataset] : impl_->series) dataset.set_rows(keep);
  impl_->file.flush();
  impl_->rewrite_xdmf();
}

template <int D>
void RunFile<D>::write_failure(const std::string& diagnostic) {
  impl_->root().open_group("meta").set_attribute("failure", diagnostic);
  impl_->file.flush();
}

template <int D>
void RunFile<D>::flush() {
  impl_->file.flush();
}

template <int D>
int RunFile<D>::frame_count() const {
  return static_cast<int>(impl_->frames.size());
}

template <int D>
Particles<D> RunFile<D>::read_frame(int index, double* time, long long* step) const {
  return read_frame_group<D>(impl_->root(), impl_->path, index, impl_->frames.size(), time, step);
}

template class RunFile<2>;
template class RunFile<3>;

}  // namespace fragmpm::mpm
