// `fragmpm pool`: pooled CDFs with member-bootstrap bands, grading curves, size fits and breakage
// per group and analysed frame, written as CSV, DIR/pool.h5 and figures (pool.hpp).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <regex>

#include "fragmpm/analysis/bootstrap_cdf.hpp"
#include "fragmpm/analysis/figure_error.hpp"
#include "fragmpm/analysis/grading.hpp"
#include "fragmpm/analysis/plot.hpp"
#include "fragmpm/analysis/si_format.hpp"
#include "fragmpm/analysis/size_fits.hpp"
#include "fragmpm/mpm/hdf5_io.hpp"
#include "fragmpm/pipeline/pool.hpp"
#include "fragmpm/pipeline/report_html.hpp"
#include "fragmpm/pipeline/sweep_members.hpp"

namespace fragmpm::pipeline {

namespace fs = std::filesystem;
namespace an = fragmpm::analysis;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// One row of pool_fits.csv: a group at one analysed frame.
struct FitRow {
  std::size_t group = 0;
  std::size_t ordinal = 0;
  double time = 0.0, platen = kNaN, wall_work = 0.0;
  std::size_t members = 0, fragments = 0;
  an::GradingSummary grading;
  an::RosinRammlerFit rr;
  bool rr_ok = false;
  an::PowerLawFit pl;
  bool pl_ok = false;
  double br_mean = kNaN, b10_mean = kNaN;
};

struct BreakageRow {
  std::size_t group = 0, ordinal = 0;
  std::string member;
  double time = 0.0, wall_work = 0.0, br = kNaN, b10 = kNaN;
};

std::string num(double v) {
  return std::isfinite(v) ? fmt::format("{:.9g}", v) : std::string("nan");
}

/// The last number written in a value ("0.1 mm" → 0.1, "[0, -20 m/s]" → −20), for plotting fit
/// parameters against the varied value; NaN when there is none.
double last_number(const std::string& text) {
  static const std::regex number(R"([-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?)");
  double v = kNaN;
  for (std::sregex_iterator it(text.begin(), text.end(), number), end; it != end; ++it)
    v = std::stod(it->str());
  return v;
}

void write_text(const fs::path& path, const std::string& text, std::vector<std::string>& files) {
  std::ofstream out(path, std::ios::trunc);
  out << text;
  if (!out) throw PoolError(path.string() + ": cannot write");
  files.push_back(path.string());
}

/// Plots a figure, or says why it was skipped (a figure never stops the tables).
void plot(const an::PlotSpec& spec, const fs::path& path, std::vector<std::string>& files,
          std::FILE* log) {
  try {
    an::write_line_plot(spec, path.string());
    files.push_back(path.string());
  } catch (const an::FigureError& e) {
    if (log) std::fprintf(log, "  figure %s skipped: %s\n", path.string().c_str(), e.what());
  }
}

/// Caption of a pool figure from its file name.
std::string pool_caption(const std::string& name) {
  static const std::vector<std::pair<std::regex, std::string>> known{
      {std::regex(R"(^cdf_equivalent_diameter_number_frame(\d+)\.png$)"),
       "Pooled number CDF of equivalent diameter at analysed frame $1, one colour per group, "
       "dashed: the 95 % band from resampling members."},
      {std::regex(R"(^cdf_equivalent_diameter_mass_frame(\d+)\.png$)"),
       "Pooled mass CDF of equivalent diameter at analysed frame $1, with the 95 % member "
       "bootstrap band dashed."},
      {std::regex(R"(^cdf_roundness_number_frame(\d+)\.png$)"),
       "Pooled number CDF of roundness at analysed frame $1, with the 95 % band dashed."},
      {std::regex(R"(^cdf_roundness_mass_frame(\d+)\.png$)"),
       "Pooled mass CDF of roundness at analysed frame $1, with the 95 % band dashed."},
      {std::regex(R"(^grading_frame(\d+)\.png$)"),
       "Grading curve (percent passing by mass, fragments and fines) at analysed frame $1."},
      {std::regex(R"(^breakage_vs_work\.png$)"),
       "Hardin's relative breakage B_r of every member and frame against the work the walls did."},
      {std::regex(R"(^fit_(.*)\.png$)"),
       "A fit parameter with its 95 % interval against the varied value, per analysed frame."},
  };
  for (const auto& [pattern, caption] : known)
    if (std::regex_search(name, pattern)) return std::regex_replace(name, pattern, caption);
  return name;
}

/// DIR/report.html: the groups, the fit table and every figure with a caption.
std::string write_pool_report(const PoolOptions& o, const std::vector<PoolGroup>& groups,
                              const std::vector<FitRow>& fits, const fs::path& dir,
                              const std::vector<std::string>& files) {
  Report report;
  report.title = "FragMPM pool: " + dir.filename().string();
  report.summary_title = "The study: groups of members and fits per analysed frame";
  report.subtitle = fmt::format("{} group(s); CDF bands from {} member resamplings (seed {})",
                                groups.size(), o.replicates, o.seed);
  for (std::size_t gi = 0; gi < groups.size(); ++gi)
    report.summary.push_back(
        {fmt::format("group {}", gi + 1),
         fmt::format("{}: {} members", groups[gi].label, groups[gi].members.size())});
  for (const FitRow& r : fits) {
    std::string value =
        fmt::format("t = {}, {} fragments", an::format_si(r.time, "s", 3), r.fragments);
    if (r.rr_ok)
      value += fmt::format("; Rosin-Rammler d\u2080 = {} [{}, {}], n = {:.3g} [{:.3g}, {:.3g}]",
                           an::format_si(r.rr.d0, "m", 3), an::format_si(r.rr.d0_ci.low, "m", 3),
                           an::format_si(r.rr.d0_ci.high, "m", 3), r.rr.n, r.rr.n_ci.low,
                           r.rr.n_ci.high);
    if (r.pl_ok)
      value += fmt::format("; power law D = {:.3g} [{:.3g}, {:.3g}] above {}", r.pl.exponent,
                           r.pl.exponent_ci.low, r.pl.exponent_ci.high,
                           an::format_si(r.pl.d_min, "m", 3));
    if (std::isfinite(r.br_mean)) value += fmt::format("; B_r = {:.3g}", r.br_mean);
    report.summary.push_back(
        {fmt::format("group {}, frame {}", r.group + 1, r.ordinal), value, false});
  }
  ReportSection cdfs{"Pooled distributions", {}}, grading{"Grading and breakage", {}},
      fit_figures{"Fit parameters", {}};
  for (const std::string& file : files) {
    const fs::path relative = fs::path(file).lexically_relative(dir);
    if (relative.extension() != ".png") continue;
    const std::string name = relative.filename().string();
    ReportSection& section = name.rfind("cdf_", 0) == 0   ? cdfs
                             : name.rfind("fit_", 0) == 0 ? fit_figures
                                                          : grading;
    section.figures.push_back({relative.generic_string(), pool_caption(name)});
  }
  report.sections = {cdfs, grading, fit_figures};
  const std::string path = (dir / "report.html").string();
  write_report(report, path);
  return path;
}

}  // namespace

std::vector<std::string> pool_sweep(const PoolOptions& o, std::FILE* log) {
  const std::vector<PoolGroup> groups = read_pool_groups(o.dir, log);
  const fs::path dir(o.dir);
  const fs::path figures = dir / "pool_figures";
  if (o.figures) fs::create_directories(figures);
  std::vector<std::string> files;
  std::vector<FitRow> fits;
  std::vector<BreakageRow> breakage;
  std::string cdf_csv =
      "group,frame_ordinal,time_s,quantity,x,number,number_low,number_high,mass,mass_low,"
      "mass_high\n";
  std::string grading_csv = "group,frame_ordinal,time_s,d_m,percent_passing\n";

  mpm::h5::File h5 = mpm::h5::File::create((dir / "pool.h5").string(), true);
  const mpm::h5::Group root = h5.root();
  root.set_attribute("written_by", "fragmpm pool");
  root.set_attribute("bootstrap_replicates", static_cast<std::int64_t>(o.replicates));
  root.set_attribute("bootstrap_seed", static_cast<std::int64_t>(o.seed));
  root.set_attribute("units", "sizes in m, masses in kg/m, work in J/m, fractions 0-1");

  // Frames per group: the smallest number of analysed frames among its members.
  std::size_t max_frames = 0;
  for (const PoolGroup& g : groups) {
    std::size_t n = std::numeric_limits<std::size_t>::max();
    for (const PoolMember& m : g.members) n = std::min(n, m.frames.size());
    max_frames = std::max(max_frames, n);
  }
  // Figures gather one curve set per frame ordinal over the groups.
  std::vector<std::map<std::string, an::PlotSpec>> frame_plots(max_frames);

  for (std::size_t gi = 0; gi < groups.size(); ++gi) {
    const PoolGroup& g = groups[gi];
    std::size_t frames = std::numeric_limits<std::size_t>::max();
    for (const PoolMember& m : g.members) frames = std::min(frames, m.frames.size());
    if (log)
      std::fprintf(log, "fragmpm pool: group %zu (%s): %zu members, %zu analysed frames\n", gi + 1,
                   g.label.c_str(), g.members.size(), frames);
    const mpm::h5::Group hg = root.require_group(fmt::format("groups/{:02d}", gi + 1));
    hg.set_attribute("label", g.label);
    hg.set_attribute("members", static_cast<std::int64_t>(g.members.size()));
    std::string names;
    for (const PoolMember& m : g.members) names += (names.empty() ? "" : ",") + m.name;
    hg.set_attribute("member_names", names);

    for (std::size_t k = 0; k < frames; ++k) {
      FitRow row;
      row.group = gi;
      row.ordinal = k;
      row.members = g.members.size();
      std::vector<an::MemberSample> deq, round;
      std::vector<double> pooled_d, pooled_all_d, pooled_all_mass;
      double time = 0, platen = 0, work = 0;
      for (const PoolMember& m : g.members) {
        const PoolFrame& f = m.frames[k];
        deq.push_back({f.d, f.mass});
        round.push_back({f.roundness, f.mass});
        pooled_d.insert(pooled_d.end(), f.d.begin(), f.d.end());
        pooled_all_d.insert(pooled_all_d.end(), f.all_d.begin(), f.all_d.end());
        pooled_all_mass.insert(pooled_all_mass.end(), f.all_mass.begin(), f.all_mass.end());
        time += f.time;
        platen += f.platen_displacement;
        work += f.wall_work;
      }
      const double M = double(g.members.size());
      row.time = time / M;
      row.platen = platen / M;
      row.wall_work = work / M;
      row.fragments = pooled_d.size();
      const mpm::h5::Group hf = hg.require_group(fmt::format("frames/{:02d}", k));
      hf.set_attribute("mean_time", row.time);
      hf.set_attribute("mean_platen_displacement", row.platen);
      hf.set_attribute("mean_wall_work", row.wall_work);
      const std::string frame_label = std::isfinite(row.platen)
                                          ? fmt::format("u = {:.3g} um", row.platen * 1e6)
                                          : fmt::format("t = {:.3g} us", row.time * 1e6);

      // Pooled CDFs with bands; the seed differs per group, frame and quantity (documented).
      if (pooled_d.empty()) continue;
      const auto [dmin, dmax] = std::minmax_element(pooled_d.begin(), pooled_d.end());
      struct Quantity {
        const char* name;
        const std::vector<an::MemberSample>* samples;
        std::vector<double> x;
        bool log;
      };
      Quantity quantities[] = {
          {"equivalent_diameter", &deq,
           *dmin < *dmax ? an::spaced_points(*dmin, *dmax, o.points, true)
                         : std::vector<double>{*dmin, *dmin * 1.0001},
           true},
          {"roundness", &round, an::spaced_points(0.0, 1.0, o.points, false), false}};
      for (std::size_t q = 0; q < 2; ++q) {
        const Quantity& Q = quantities[q];
        const std::uint64_t seed = o.seed + 1000003ull * gi + 1009ull * k + q;
        const an::CdfBand band = an::bootstrap_cdf_band(*Q.samples, Q.x, o.replicates, seed);
        for (std::size_t i = 0; i < band.x.size(); ++i)
          cdf_csv += fmt::format("{},{},{},{},{},{},{},{},{},{},{}\n", gi + 1, k, num(row.time),
                                 Q.name, num(band.x[i]), num(band.number[i]),
                                 num(band.number_low[i]), num(band.number_high[i]),
                                 num(band.mass[i]), num(band.mass_low[i]), num(band.mass_high[i]));
        const mpm::h5::Group hc = hf.require_group(std::string("cdf/") + Q.name);
        hc.set_attribute("seed", static_cast<std::int64_t>(seed));
        const mpm::h5::Dims dims{band.x.size()};
        hc.write("x", band.x, dims);
        hc.write("number", band.number, dims);
        hc.write("number_low", band.number_low, dims);
        hc.write("number_high", band.number_high, dims);
        hc.write("mass", band.mass, dims);
        hc.write("mass_low", band.mass_low, dims);
        hc.write("mass_high", band.mass_high, dims);
        if (!o.figures) continue;
        const double scale = Q.log ? 1e6 : 1.0;
        for (const bool by_mass : {false, true}) {
          const std::string key = fmt::format("cdf_{}_{}", Q.name, by_mass ? "mass" : "number");
          an::PlotSpec& spec = frame_plots[k][key];
          if (spec.title.empty()) {
            spec.title = fmt::format("{} by {}, frame {} ({}), dashed: 95 % band",
                                     Q.name == std::string("roundness") ? "roundness" : "size",
                                     by_mass ? "mass" : "number", k, frame_label);
            spec.x_label = Q.log ? "equivalent diameter [\u00b5m]" : "roundness";
            spec.y_label = by_mass ? "mass fraction" : "number fraction";
            spec.log_x = Q.log;
          }
          std::vector<double> xs(band.x.size());
          for (std::size_t i = 0; i < xs.size(); ++i) xs[i] = band.x[i] * scale;
          const auto& mid = by_mass ? band.mass : band.number;
          const auto& lo = by_mass ? band.mass_low : band.number_low;
          const auto& hi = by_mass ? band.mass_high : band.number_high;
          // The band's edges dashed, in the group's colour.
          const int colour = static_cast<int>(gi);
          spec.series.push_back({g.label, xs, mid, false, true, false, colour});
          spec.series.push_back({"", xs, lo, false, true, true, colour});
          spec.series.push_back({"", xs, hi, false, true, true, colour});
        }
      }

      // Grading curve of all pieces (fragments and fines) of the group's members.
      const an::GradingCurve curve = an::grading_curve(pooled_all_d, pooled_all_mass);
      row.grading = an::summarise(curve);
      for (std::size_t i = 0; i < curve.d.size(); ++i)
        grading_csv += fmt::format("{},{},{},{},{}\n", gi + 1, k, num(row.time), num(curve.d[i]),
                                   num(100.0 * curve.passing[i]));
      {
        const mpm::h5::Group hgr = hf.require_group("grading");
        hgr.write("d", curve.d, {curve.d.size()});
        hgr.write("passing", curve.passing, {curve.passing.size()});
        hgr.set_attribute("D10", row.grading.d10);
        hgr.set_attribute("D50", row.grading.d50);
        hgr.set_attribute("D90", row.grading.d90);
        hgr.set_attribute("uniformity_coefficient", row.grading.uniformity);
      }
      if (o.figures) {
        an::PlotSpec& spec = frame_plots[k]["grading"];
        if (spec.title.empty()) {
          spec.title = fmt::format("grading curves, frame {} ({})", k, frame_label);
          spec.x_label = "equivalent diameter [\u00b5m]";
          spec.y_label = "percent passing by mass";
          spec.log_x = true;
        }
        std::vector<double> xs, ys;
        for (std::size_t i = 0; i < curve.d.size(); ++i) {
          xs.push_back(curve.d[i] * 1e6);
          ys.push_back(100.0 * curve.passing[i]);
        }
        spec.series.push_back({g.label, xs, ys, false});
      }

      // Fits to the pooled fragment sizes (number distribution).
      try {
        row.rr = an::fit_rosin_rammler(pooled_d);
        row.rr_ok = true;
      } catch (const std::invalid_argument& e) {
        if (log)
          std::fprintf(log, "  group %zu frame %zu: no Rosin-Rammler fit: %s\n", gi + 1, k,
                       e.what());
      }
      try {
        row.pl = an::fit_power_law_csn(pooled_d, o.min_tail);
        row.pl_ok = true;
      } catch (const std::invalid_argument& e) {
        if (log)
          std::fprintf(log, "  group %zu frame %zu: no power-law fit: %s\n", gi + 1, k, e.what());
      }

      // Breakage of each member against its own first frame (the initial grains).
      double br_sum = 0, b10_sum = 0;
      int br_count = 0;
      for (const PoolMember& m : g.members) {
        const PoolFrame& f0 = m.frames.front();
        const PoolFrame& f = m.frames[k];
        if (f0.all_d.empty() || f.all_d.empty()) continue;
        const an::GradingCurve c0 = an::grading_curve(f0.all_d, f0.all_mass);
        const an::GradingCurve c = an::grading_curve(f.all_d, f.all_mass);
        const double lower = o.breakage_lower > 0 ? o.breakage_lower : f0.particle_size;
        BreakageRow b{gi, k, m.name, f.time, f.wall_work, kNaN, kNaN};
        if (lower > 0 && lower < c0.d.back()) b.br = an::hardin_relative_breakage(c0, c, lower);
        b.b10 = an::lade_b10(c0, c);
        if (std::isfinite(b.br)) {
          br_sum += b.br;
          b10_sum += b.b10;
          ++br_count;
        }
        breakage.push_back(b);
      }
      if (br_count > 0) {
        row.br_mean = br_sum / br_count;
        row.b10_mean = b10_sum / br_count;
      }
      fits.push_back(row);
    }
  }

  // Tables.
  std::vector<std::string> keys;
  for (const auto& kv : groups.front().values) keys.push_back(kv.first);
  std::string fit_csv = "group";
  for (const std::string& k : keys) fit_csv += "," + csv_field(k);
  fit_csv +=
      ",frame_ordinal,mean_time_s,mean_platen_displacement_m,mean_wall_work_J_per_m,members,"
      "fragments,D10_m,D30_m,D50_m,D60_m,D90_m,uniformity_coefficient,rr_d0_m,rr_d0_low_m,"
      "rr_d0_high_m,rr_n,rr_n_low,rr_n_high,rr_range_low_m,rr_range_high_m,rr_ks,pl_D,pl_D_low,"
      "pl_D_high,pl_d_min_m,pl_d_high_m,pl_tail,pl_ks,hardin_Br_mean,lade_B10_mean\n";
  for (const FitRow& r : fits) {
    fit_csv += std::to_string(r.group + 1);
    for (const auto& kv : groups[r.group].values) fit_csv += "," + csv_field(kv.second);
    const an::GradingSummary& s = r.grading;
    fit_csv += fmt::format(",{},{},{},{},{},{},{},{},{},{},{},{}", r.ordinal, num(r.time),
                           num(r.platen), num(r.wall_work), r.members, r.fragments, num(s.d10),
                           num(s.d30), num(s.d50), num(s.d60), num(s.d90), num(s.uniformity));
    if (r.rr_ok)
      fit_csv += fmt::format(",{},{},{},{},{},{},{},{},{}", num(r.rr.d0), num(r.rr.d0_ci.low),
                             num(r.rr.d0_ci.high), num(r.rr.n), num(r.rr.n_ci.low),
                             num(r.rr.n_ci.high), num(r.rr.d_low), num(r.rr.d_high), num(r.rr.ks));
    else
      fit_csv += ",nan,nan,nan,nan,nan,nan,nan,nan,nan";
    if (r.pl_ok)
      fit_csv += fmt::format(",{},{},{},{},{},{},{}", num(r.pl.exponent), num(r.pl.exponent_ci.low),
                             num(r.pl.exponent_ci.high), num(r.pl.d_min), num(r.pl.d_high),
                             r.pl.tail, num(r.pl.ks));
    else
      fit_csv += ",nan,nan,nan,nan,nan,0,nan";
    fit_csv += fmt::format(",{},{}\n", num(r.br_mean), num(r.b10_mean));
  }
  std::string breakage_csv =
      "group,member,frame_ordinal,time_s,wall_work_J_per_m,hardin_Br,lade_B10\n";
  for (const BreakageRow& b : breakage)
    breakage_csv += fmt::format("{},{},{},{},{},{},{}\n", b.group + 1, b.member, b.ordinal,
                                num(b.time), num(b.wall_work), num(b.br), num(b.b10));
  write_text(dir / "pool_fits.csv", fit_csv, files);
  write_text(dir / "pool_breakage.csv", breakage_csv, files);
  write_text(dir / "pool_cdf.csv", cdf_csv, files);
  write_text(dir / "pool_grading.csv", grading_csv, files);

  // The same tables in pool.h5, one dataset per numeric column.
  {
    const mpm::h5::Group t = root.require_group("fits");
    auto col = [&](const char* name, auto get) {
      std::vector<double> v;
      for (const FitRow& r : fits) v.push_back(get(r));
      t.write(name, v, {v.size()});
    };
    col("group", [](const FitRow& r) { return double(r.group + 1); });
    col("frame_ordinal", [](const FitRow& r) { return double(r.ordinal); });
    col("mean_time", [](const FitRow& r) { return r.time; });
    col("mean_wall_work", [](const FitRow& r) { return r.wall_work; });
    col("fragments", [](const FitRow& r) { return double(r.fragments); });
    col("D10", [](const FitRow& r) { return r.grading.d10; });
    col("D50", [](const FitRow& r) { return r.grading.d50; });
    col("D90", [](const FitRow& r) { return r.grading.d90; });
    col("uniformity_coefficient", [](const FitRow& r) { return r.grading.uniformity; });
    col("rr_d0", [](const FitRow& r) { return r.rr_ok ? r.rr.d0 : kNaN; });
    col("rr_d0_low", [](const FitRow& r) { return r.rr_ok ? r.rr.d0_ci.low : kNaN; });
    col("rr_d0_high", [](const FitRow& r) { return r.rr_ok ? r.rr.d0_ci.high : kNaN; });
    col("rr_n", [](const FitRow& r) { return r.rr_ok ? r.rr.n : kNaN; });
    col("rr_n_low", [](const FitRow& r) { return r.rr_ok ? r.rr.n_ci.low : kNaN; });
    col("rr_n_high", [](const FitRow& r) { return r.rr_ok ? r.rr.n_ci.high : kNaN; });
    col("rr_range_low", [](const FitRow& r) { return r.rr_ok ? r.rr.d_low : kNaN; });
    col("rr_range_high", [](const FitRow& r) { return r.rr_ok ? r.rr.d_high : kNaN; });
    col("pl_D", [](const FitRow& r) { return r.pl_ok ? r.pl.exponent : kNaN; });
    col("pl_D_low", [](const FitRow& r) { return r.pl_ok ? r.pl.exponent_ci.low : kNaN; });
    col("pl_D_high", [](const FitRow& r) { return r.pl_ok ? r.pl.exponent_ci.high : kNaN; });
    col("pl_d_min", [](const FitRow& r) { return r.pl_ok ? r.pl.d_min : kNaN; });
    col("pl_d_high", [](const FitRow& r) { return r.pl_ok ? r.pl.d_high : kNaN; });
    col("pl_tail", [](const FitRow& r) { return r.pl_ok ? double(r.pl.tail) : 0.0; });
    col("hardin_Br_mean", [](const FitRow& r) { return r.br_mean; });
    col("lade_B10_mean", [](const FitRow& r) { return r.b10_mean; });
    const mpm::h5::Group b = root.require_group("breakage");
    auto bcol = [&](const char* name, auto get) {
      std::vector<double> v;
      for (const BreakageRow& r : breakage) v.push_back(get(r));
      b.write(name, v, {v.size()});
    };
    bcol("group", [](const BreakageRow& r) { return double(r.group + 1); });
    bcol("member", [](const BreakageRow& r) { return std::stod(r.member); });
    bcol("frame_ordinal", [](const BreakageRow& r) { return double(r.ordinal); });
    bcol("time", [](const BreakageRow& r) { return r.time; });
    bcol("wall_work", [](const BreakageRow& r) { return r.wall_work; });
    bcol("hardin_Br", [](const BreakageRow& r) { return r.br; });
    bcol("lade_B10", [](const BreakageRow& r) { return r.b10; });
  }
  h5.flush();
  files.push_back((dir / "pool.h5").string());

  if (!o.figures) return files;
  for (std::size_t k = 0; k < frame_plots.size(); ++k)
    for (auto& [name, spec] : frame_plots[k])
      if (!spec.series.empty())
        plot(spec, figures / fmt::format("{}_frame{:02d}.png", name, k), files, log);
  {
    an::PlotSpec spec;
    spec.title = "Hardin's B_r against wall work, every member and frame";
    spec.x_label = "wall work [J/m]";
    spec.y_label = "B_r";
    for (std::size_t gi = 0; gi < groups.size(); ++gi) {
      an::LineSeries s{groups[gi].label, {}, {}, true, false};
      for (const BreakageRow& b : breakage)
        if (b.group == gi && std::isfinite(b.br)) {
          s.x.push_back(b.wall_work);
          s.y.push_back(b.br);
        }
      if (!s.x.empty()) spec.series.push_back(std::move(s));
    }
    if (!spec.series.empty()) plot(spec, figures / "breakage_vs_work.png", files, log);
  }
  // Fit parameters of the last pooled frame against the varied value (the last number written in
  // the first varied key's value; the group number when there is none).
  std::size_t last = 0;
  for (const FitRow& r : fits) last = std::max(last, r.ordinal);
  struct Param {
    const char* file;
    const char* label;
    double (*value)(const FitRow&);
    double (*low)(const FitRow&);
    double (*high)(const FitRow&);
  };
  const Param params[] = {
      {"fit_rr_n.png", "Rosin-Rammler n", [](const FitRow& r) { return r.rr.n; },
       [](const FitRow& r) { return r.rr.n_ci.low; },
       [](const FitRow& r) { return r.rr.n_ci.high; }},
      {"fit_rr_d0.png", "Rosin-Rammler d\u2080 [\u00b5m]",
       [](const FitRow& r) { return r.rr.d0 * 1e6; },
       [](const FitRow& r) { return r.rr.d0_ci.low * 1e6; },
       [](const FitRow& r) { return r.rr.d0_ci.high * 1e6; }},
      {"fit_power_law_D.png", "power-law exponent D", [](const FitRow& r) { return r.pl.exponent; },
       [](const FitRow& r) { return r.pl.exponent_ci.low; },
       [](const FitRow& r) { return r.pl.exponent_ci.high; }},
  };
  const bool numeric =
      !keys.empty() && std::all_of(groups.begin(), groups.end(), [](const PoolGroup& g) {
        return std::isfinite(last_number(g.values.front().second));
      });
  for (const Param& p : params) {
    an::PlotSpec spec;
    spec.title = fmt::format("{}, last frame, with 95 % interval", p.label);
    spec.x_label = numeric ? keys.front() + " (last number of the value)" : "group";
    spec.y_label = p.label;
    an::LineSeries mid{"estimate", {}, {}, true, true, false, 0},
        lo{"95 % interval", {}, {}, true, true, true, 1}, hi{"", {}, {}, true, true, true, 1};
    // In order of the varied value, so that the lines join neighbours.
    std::vector<const FitRow*> order;
    for (const FitRow& r : fits)
      if (r.ordinal == last) order.push_back(&r);
    auto x_of = [&](const FitRow& r) {
      return numeric ? last_number(groups[r.group].values.front().second) : double(r.group + 1);
    };
    std::stable_sort(order.begin(), order.end(),
                     [&](const FitRow* a, const FitRow* b) { return x_of(*a) < x_of(*b); });
    for (const FitRow* rp : order) {
      const FitRow& r = *rp;
      const bool ok = std::string(p.file).find("power") != std::string::npos ? r.pl_ok : r.rr_ok;
      if (!ok) continue;
      const double x = x_of(r);
      mid.x.push_back(x);
      mid.y.push_back(p.value(r));
      lo.x.push_back(x);
      lo.y.push_back(p.low(r));
      hi.x.push_back(x);
      hi.y.push_back(p.high(r));
    }
    if (mid.x.empty()) continue;
    spec.series = {mid, lo, hi};
    plot(spec, figures / p.file, files, log);
  }
  files.push_back(write_pool_report(o, groups, fits, dir, files));
  return files;
}

}  // namespace fragmpm::pipeline
