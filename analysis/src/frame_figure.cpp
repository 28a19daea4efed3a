// Run-frame particle figures (see frame_figure.hpp).
#include "fragmpm/analysis/frame_figure.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "fragmpm/analysis/figure_error.hpp"

namespace fragmpm::analysis {

namespace {

ParticleFigure geometry(const mpm::Particles<2>& p, std::optional<double> time,
                        const std::string& title) {
  ParticleFigure f;
  const std::size_t n = p.size();
  if (p.domain.size() != n)
    throw FigureError(fmt::format("frame figure: {} particles but {} domains", n, p.domain.size()));
  f.x.assign(p.x.begin(), p.x.end());
  f.r1.reserve(n);
  f.r2.reserve(n);
  for (const auto& d : p.domain) {
    f.r1.push_back(d.col(0));
    f.r2.push_back(d.col(1));
  }
  f.time = time;
  f.title = title;
  return f;
}

/// Names the colour-bar field (moved-in strings sidestep a GCC 12 -Wrestrict false positive on
/// assignments of literals).
void name_field(ParticleFigure& f, std::string name, std::string units) {
  f.field_name = std::move(name);
  f.units = std::move(units);
}

template <class T>
void require_size(const std::vector<T>& v, std::size_t n, const char* what) {
  if (v.size() != n)
    throw FigureError(fmt::format("frame figure: the frame has {} {} values for {} particles{}",
                                  v.size(), what, n,
                                  v.empty() ? " (not stored in this frame)" : ""));
}

/// Colour range of a field dominated by a few extreme particles (stress concentrations at contacts
/// and crack tips reach 10 x the bulk value): the 1st and 99th percentiles of the finite values, so
/// the bulk is not all one colour; the values beyond take the end colours. Returns false (range
/// left to the default) when there are too few values for percentiles to mean anything, or they
/// coincide.
bool clip_to_percentiles(ParticleFigure& f) {
  std::vector<double> v;
  for (double x : f.values)
    if (std::isfinite(x)) v.push_back(x);
  if (v.size() < 200) return false;
  auto at = [&v](double q) {
    const auto k = static_cast<std::ptrdiff_t>(std::llround(q * static_cast<double>(v.size() - 1)));
    std::nth_element(v.begin(), v.begin() + k, v.end());
    return v[static_cast<std::size_t>(k)];
  };
  const double lo = at(0.01), hi = at(0.99);
  if (!(hi > lo)) return false;
  f.vmin = lo;
  f.vmax = hi;
  return true;
}

}  // namespace

const std::vector<std::string>& frame_field_names() {
  static const std::vector<std::string> names{"damage", "temperature", "speed", "stress", "body"};
  return names;
}

FrameField parse_frame_field(const std::string& name) {
  const auto& names = frame_field_names();
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return static_cast<FrameField>(i);
  throw FigureError(
      fmt::format("unknown field '{}'; expected one of {}", name, fmt::join(names, ", ")));
}

double max_principal_stress(const Eigen::Matrix2d& s) {
  const double sxy = 0.5 * (s(0, 1) + s(1, 0));
  const double mean = 0.5 * (s(0, 0) + s(1, 1)), half_diff = 0.5 * (s(0, 0) - s(1, 1));
  return mean + std::sqrt(half_diff * half_diff + sxy * sxy);
}

ParticleFigure frame_figure(const mpm::Particles<2>& p, FrameField field,
                            std::optional<double> time, const std::string& title) {
  ParticleFigure f = geometry(p, time, title);
  const std::size_t n = p.size();
  switch (field) {
    case FrameField::damage:
      require_size(p.damage, n, "damage");
      f.values = p.damage;
      name_field(f, "damage", "");
      f.vmin = 0.0;  // d in [0, 1] ([XLS21] §2): a fixed range makes frames comparable
      f.vmax = 1.0;
      break;
    case FrameField::temperature:
      if (p.temperature.empty())
        throw FigureError(
            "frame figure: the frame has no temperature (the thermal module was off in this run)");
      require_size(p.temperature, n, "temperature");
      f.values = p.temperature;
      name_field(f, "temperature", "K");
      break;
    case FrameField::speed:
      require_size(p.v, n, "velocity");
      f.values.reserve(n);
      for (const auto& v : p.v) f.values.push_back(v.norm());
      name_field(f, "speed |v|", "m/s");
      f.vmin = 0.0;
      break;
    case FrameField::stress:
      require_size(p.stress, n, "stress");
      f.values.reserve(n);
      for (const auto& s : p.stress) f.values.push_back(1e-6 * max_principal_stress(s));
      name_field(
          f, clip_to_percentiles(f) ? "max principal stress, 1-99 % range" : "max principal stress",
          "MPa");
      break;
    case FrameField::body:
      require_size(p.body, n, "body");
      f.ids.assign(p.body.begin(), p.body.end());
      f.id_name = std::string("body");
      name_field(f, "body", "");
      break;
  }
  return f;
}

std::vector<std::int64_t> resolved_fragment_ids(const FragmentLabels& labels) {
  std::vector<std::int64_t> ids(labels.fragment.size(), -1);
  for (std::size_t p = 0; p < ids.size(); ++p) {
    const std::int32_t f = labels.fragment[p];
    if (f >= 0 && !labels.fine[static_cast<std::size_t>(f)]) ids[p] = f;
  }
  return ids;
}

ParticleFigure fragment_figure(const mpm::Particles<2>& p,
                               const std::vector<std::int64_t>& fragment_ids,
                               std::optional<double> time, const std::string& title) {
  ParticleFigure f = geometry(p, time, title);
  require_size(fragment_ids, p.size(), "fragment id");
  f.ids = fragment_ids;
  f.id_name = std::string("fragment");
  f.none_name = std::string("masked or fines");
  name_field(f, "fragment", "");
  return f;
}

}  // namespace fragmpm::analysis
