// Quantity strings → SI numbers (docs/design.md). A small hand-written reader: units are products
// of prefixed symbols with integer powers, tracked as exponents of the base dimensions so that any
// spelling of a unit of the right kind is accepted ("kg/m3", "g/cm3", "g cm^-3").
#include "fragmpm/pipeline/units.hpp"

#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>
#include <utility>

namespace fragmpm::pipeline {
namespace {

// Exponents of length, mass, time, temperature, angle. The radian is kept as its own dimension so
// that "rad/s" (angular velocity) and "Hz" (frequency) cannot be confused: they differ by 2π.
using Dims = std::array<int, 5>;
constexpr int L = 0, M = 1, T = 2, TH = 3, A = 4;

Dims dims(int l, int m, int t, int th = 0, int a = 0) {
  return {l, m, t, th, a};
}

struct Unit {
  double scale = 1.0;  ///< SI value of one of this unit
  Dims d{};
};

Unit operator*(const Unit& a, const Unit& b) {
  Unit r{a.scale * b.scale, {}};
  for (int i = 0; i < 5; ++i) r.d[i] = a.d[i] + b.d[i];
  return r;
}

Unit power(const Unit& u, int n) {
  Unit r{std::pow(u.scale, n), {}};
  for (int i = 0; i < 5; ++i) r.d[i] = u.d[i] * n;
  return r;
}

struct Symbol {
  std::string_view name;
  Unit unit;
};

// Base and derived symbols that scene files may use. Kept short on purpose: every symbol here must
// be unambiguous next to the prefixes below.
const std::array<Symbol, 11>& symbols() {
  static const std::array<Symbol, 11> table = {{
      {"m", {1.0, dims(1, 0, 0)}},
      {"g", {1e-3, dims(0, 1, 0)}},
      {"s", {1.0, dims(0, 0, 1)}},
      {"K", {1.0, dims(0, 0, 0, 1)}},
      {"Pa", {1.0, dims(-1, 1, -2)}},
      {"bar", {1e5, dims(-1, 1, -2)}},
      {"N", {1.0, dims(1, 1, -2)}},
      {"J", {1.0, dims(2, 1, -2)}},
      {"W", {1.0, dims(2, 1, -3)}},
      {"Hz", {1.0, dims(0, 0, -1)}},
      {"rad", {1.0, dims(0, 0, 0, 0, 1)}},
  }};
  return table;
}

std::optional<Unit> find_symbol(std::string_view name) {
  if (name == "deg") return Unit{std::numbers::pi / 180.0, dims(0, 0, 0, 0, 1)};
  for (const auto& s : symbols())
    if (s.name == name) return s.unit;
  return std::nullopt;
}

std::optional<double> prefix_scale(std::string_view p) {
  if (p == "p") return 1e-12;
  if (p == "n") return 1e-9;
  if (p == "u" || p == "\xC2\xB5" || p == "\xCE\xBC") return 1e-6;  // u, micro sign, Greek mu
  if (p == "m") return 1e-3;
  if (p == "c") return 1e-2;
  if (p == "d") return 1e-1;
  if (p == "k") return 1e3;
  if (p == "M") return 1e6;
  if (p == "G") return 1e9;
  if (p == "T") return 1e12;
  return std::nullopt;
}

Dims kind_dims(QuantityKind k) {
  switch (k) {
    case QuantityKind::length:
      return dims(1, 0, 0);
    case QuantityKind::time:
      return dims(0, 0, 1);
    case QuantityKind::mass:
      return dims(0, 1, 0);
    case QuantityKind::density:
      return dims(-3, 1, 0);
    case QuantityKind::pressure:
      return dims(-1, 1, -2);
    case QuantityKind::velocity:
      return dims(1, 0, -1);
    case QuantityKind::acceleration:
      return dims(1, 0, -2);
    case QuantityKind::frequency:
      return dims(0, 0, -1);
    case QuantityKind::angle:
      return dims(0, 0, 0, 0, 1);
    case QuantityKind::angular_velocity:
      return dims(0, 0, -1, 0, 1);
    case QuantityKind::temperature:
      return dims(0, 0, 0, 1);
    case QuantityKind::energy_per_area:
      return dims(0, 1, -2);
    case QuantityKind::specific_heat:
      return dims(2, 0, -2, -1);
    case QuantityKind::conductivity:
      return dims(1, 1, -3, -1);
    case QuantityKind::expansion:
      return dims(0, 0, 0, -1);
    case QuantityKind::area:
      return dims(2, 0, 0);
    case QuantityKind::volume:
      return dims(3, 0, 0);
    case QuantityKind::inverse_velocity:
      return dims(-1, 0, 1);
    case QuantityKind::heat_flux:
      return dims(0, 1, -3);
    case QuantityKind::film_coefficient:
      return dims(0, 1, -3, -1);
    case QuantityKind::stiffness:
      return dims(-2, 1, -2);
  }
  return {};
}

constexpr std::array<QuantityKind, 21> kAllKinds = {
    QuantityKind::length,        QuantityKind::time,
    QuantityKind::mass,          QuantityKind::density,
    QuantityKind::pressure,      QuantityKind::velocity,
    QuantityKind::acceleration,  QuantityKind::frequency,
    QuantityKind::angle,         QuantityKind::angular_velocity,
    QuantityKind::temperature,   QuantityKind::energy_per_area,
    QuantityKind::specific_heat, QuantityKind::conductivity,
    QuantityKind::expansion,     QuantityKind::area,
    QuantityKind::volume,        QuantityKind::inverse_velocity,
    QuantityKind::heat_flux,     QuantityKind::film_coefficient,
    QuantityKind::stiffness};

/// "a length" / "kg m^-1 s^-2" — how a found unit is described in an error.
std::string describe_dims(const Dims& d) {
  for (QuantityKind k : kAllKinds)
    if (kind_dims(k) == d) {
      const std::string_view n = kind_name(k);
      const bool vowel = n.find_first_of("aeiou") == 0;
      return std::string(vowel ? "an " : "a ") + std::string(n);
    }
  static const std::array<const char*, 5> base = {"m", "kg", "s", "K", "rad"};
  std::string out;
  for (int i = 0; i < 5; ++i) {
    if (d[i] == 0) continue;
    if (!out.empty()) out += ' ';
    out += base[i];
    if (d[i] != 1) {
      out += '^';
      out += std::to_string(d[i]);
    }
  }
  return out.empty() ? "dimensionless" : "a quantity in " + out;
}

std::string_view example(QuantityKind kind) {
  switch (kind) {
    case QuantityKind::length:
      return "0.5 mm";
    case QuantityKind::time:
      return "250 us";
    case QuantityKind::mass:
      return "2 g";
    case QuantityKind::density:
      return "2.3 g/cm3";
    case QuantityKind::pressure:
      return "50 GPa";
    case QuantityKind::velocity:
      return "10 m/s";
    case QuantityKind::acceleration:
      return "9.81 m/s2";
    case QuantityKind::frequency:
      return "1 kHz";
    case QuantityKind::angle:
      return "90 deg";
    case QuantityKind::angular_velocity:
      return "10 rad/s";
    case QuantityKind::temperature:
      return "800 C";
    case QuantityKind::energy_per_area:
      return "20 J/m2";
    case QuantityKind::specific_heat:
      return "800 J/(kg K)";
    case QuantityKind::conductivity:
      return "1.5 W/(m K)";
    case QuantityKind::expansion:
      return "8e-6 1/K";
    case QuantityKind::area:
      return "94 mm2";
    case QuantityKind::volume:
      return "1 mm3";
    case QuantityKind::inverse_velocity:
      return "0.1 s/m";
    case QuantityKind::heat_flux:
      return "1 MW/m2";
    case QuantityKind::film_coefficient:
      return "10 W/(m2 K)";
    case QuantityKind::stiffness:
      return "100 GPa/mm";
  }
  return "";
}

std::string expected_text(QuantityKind kind) {
  return "expected " + describe_dims(kind_dims(kind)) + " (SI unit " + std::string(si_unit(kind)) +
         ", e.g. \"" + std::string(example(kind)) + "\")";
}

/// Reads a unit expression into its SI scale and dimensions; throws UnitError.
class UnitReader {
 public:
  /// `context` starts every error message ("expected a length ..., got \"5 furlongs\"").
  UnitReader(std::string_view unit, std::string context) : s_(unit), context_(std::move(context)) {}

  Unit read() {
    Unit u = product();
    skip_space();
    if (pos_ < s_.size()) fail("unexpected '" + std::string(s_.substr(pos_, 1)) + "'");
    return u;
  }

 private:
  std::string_view s_;
  std::string context_;
  std::size_t pos_ = 0;

  [[noreturn]] void fail(const std::string& why) const { throw UnitError(context_ + ": " + why); }

  bool skip_space() {
    const std::size_t start = pos_;
    while (pos_ < s_.size() && s_[pos_] == ' ') ++pos_;
    return pos_ > start;
  }
  bool at(std::string_view t) const { return s_.substr(pos_, t.size()) == t; }

  // product := operand { ('*' | '·' | ' ') operand | '/' operand }
  Unit product() {
    skip_space();
    Unit result = operand(true);
    bool after_division = false;
    for (;;) {
      const bool spaced = skip_space();
      if (pos_ >= s_.size() || s_[pos_] == ')') return result;
      if (s_[pos_] == '/') {
        ++pos_;
        skip_space();
        result = result * power(operand(false), -1);
        after_division = true;
        continue;
      }
      if (s_[pos_] == '*') {
        ++pos_;
      } else if (at("\xC2\xB7")) {  // middle dot
        pos_ += 2;
      } else if (!spaced) {
        fail("unexpected '" + std::string(s_.substr(pos_, 1)) + "'");
      }
      // "J/kg K" could mean J/(kg K) or (J/kg) K; make the user say which.
      if (after_division) fail("ambiguous product after '/': use parentheses, e.g. J/(kg K)");
      skip_space();
      result = result * operand(false);
    }
  }

  // operand := '(' product ')' | '1' (only first, as in "1/s") | factor
  Unit operand(bool first) {
    if (pos_ < s_.size() && s_[pos_] == '(') {
      ++pos_;
      Unit u = product();
      if (pos_ >= s_.size() || s_[pos_] != ')') fail("missing ')'");
      ++pos_;
      return u;
    }
    if (first && pos_ < s_.size() && s_[pos_] == '1') {
      ++pos_;
      return Unit{};
    }
    return factor();
  }

  // factor := [prefix] symbol [exponent]
  Unit factor() {
    const std::size_t start = pos_;
    // Non-ASCII leading characters that belong to the symbol: micro sign, Greek mu, degree sign.
    for (std::string_view lead : {"\xC2\xB5", "\xCE\xBC", "\xC2\xB0"})
      if (at(lead)) {
        pos_ += lead.size();
        break;
      }
    while (pos_ < s_.size() && std::isalpha(static_cast<unsigned char>(s_[pos_]))) ++pos_;
    const std::string_view name = s_.substr(start, pos_ - start);
    if (name.empty()) fail("expected a unit symbol at '" + std::string(s_.substr(start)) + "'");
    if (name == "C" ||
        name ==
            "\xC2\xB0"
            "C" ||
        name == "degC")
      fail("degrees Celsius are an offset scale and cannot be combined with other units; write K");
    Unit u = resolve(name);
    return power(u, exponent());
  }

  Unit resolve(std::string_view name) const {
    if (auto u = find_symbol(name)) return *u;
    // Longest prefix first only matters for the two-byte micro signs.
    for (std::size_t plen : {std::size_t{2}, std::size_t{1}}) {
      if (name.size() <= plen) continue;
      auto p = prefix_scale(name.substr(0, plen));
      auto u = find_symbol(name.substr(plen));
      if (p && u) return Unit{*p * u->scale, u->d};
    }
    fail("unknown unit '" + std::string(name) +
         "' (known: m, g, s, K, C, Pa, bar, N, J, W, Hz, rad, deg with prefixes p n u m c d k M G "
         "T)");
  }

  int exponent() {
    if (at("\xC2\xB2")) {
      pos_ += 2;
      return 2;
    }
    if (at("\xC2\xB3")) {
      pos_ += 2;
      return 3;
    }
    if (at("\xE2\x81\xBB")) {  // superscript minus followed by ¹ ² ³
      pos_ += 3;
      if (at("\xC2\xB9")) {
        pos_ += 2;
        return -1;
      }
      if (at("\xC2\xB2")) {
        pos_ += 2;
        return -2;
      }
      if (at("\xC2\xB3")) {
        pos_ += 2;
        return -3;
      }
      fail("expected a superscript digit after '⁻'");
    }
    std::size_t p = pos_;
    if (p < s_.size() && s_[p] == '^') ++p;
    int sign = 1;
    if (p < s_.size() && (s_[p] == '-' || s_[p] == '+')) {
      sign = s_[p] == '-' ? -1 : 1;
      ++p;
    }
    const std::size_t digits = p;
    while (p < s_.size() && std::isdigit(static_cast<unsigned char>(s_[p]))) ++p;
    if (p == digits) {
      if (p != pos_) fail("expected an integer exponent");
      return 1;
    }
    int n = 0;
    std::from_chars(s_.data() + digits, s_.data() + p, n);
    pos_ = p;
    return sign * n;
  }
};

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

}  // namespace

std::string_view kind_name(QuantityKind kind) {
  switch (kind) {
    case QuantityKind::length:
      return "length";
    case QuantityKind::time:
      return "time";
    case QuantityKind::mass:
      return "mass";
    case QuantityKind::density:
      return "density";
    case QuantityKind::pressure:
      return "pressure";
    case QuantityKind::velocity:
      return "velocity";
    case QuantityKind::acceleration:
      return "acceleration";
    case QuantityKind::frequency:
      return "frequency";
    case QuantityKind::angle:
      return "angle";
    case QuantityKind::angular_velocity:
      return "angular velocity";
    case QuantityKind::temperature:
      return "temperature";
    case QuantityKind::energy_per_area:
      return "energy per area";
    case QuantityKind::specific_heat:
      return "specific heat";
    case QuantityKind::conductivity:
      return "thermal conductivity";
    case QuantityKind::expansion:
      return "thermal expansion coefficient";
    case QuantityKind::area:
      return "area";
    case QuantityKind::volume:
      return "volume";
    case QuantityKind::inverse_velocity:
      return "inverse velocity";
    case QuantityKind::heat_flux:
      return "heat flux";
    case QuantityKind::film_coefficient:
      return "heat transfer coefficient";
    case QuantityKind::stiffness:
      return "contact stiffness";
  }
  return "quantity";
}

std::string_view si_unit(QuantityKind kind) {
  switch (kind) {
    case QuantityKind::length:
      return "m";
    case QuantityKind::time:
      return "s";
    case QuantityKind::mass:
      return "kg";
    case QuantityKind::density:
      return "kg/m3";
    case QuantityKind::pressure:
      return "Pa";
    case QuantityKind::velocity:
      return "m/s";
    case QuantityKind::acceleration:
      return "m/s2";
    case QuantityKind::frequency:
      return "Hz";
    case QuantityKind::angle:
      return "rad";
    case QuantityKind::angular_velocity:
      return "rad/s";
    case QuantityKind::temperature:
      return "K";
    case QuantityKind::energy_per_area:
      return "J/m2";
    case QuantityKind::specific_heat:
      return "J/(kg K)";
    case QuantityKind::conductivity:
      return "W/(m K)";
    case QuantityKind::expansion:
      return "1/K";
    case QuantityKind::area:
      return "m2";
    case QuantityKind::volume:
      return "m3";
    case QuantityKind::inverse_velocity:
      return "s/m";
    case QuantityKind::heat_flux:
      return "W/m2";
    case QuantityKind::film_coefficient:
      return "W/(m2 K)";
    case QuantityKind::stiffness:
      return "Pa/m";
  }
  return "";
}

double parse_quantity(std::string_view text, QuantityKind kind) {
  const std::string_view s = trim(text);
  std::string_view rest = s;
  if (!rest.empty() && rest.front() == '+') rest.remove_prefix(1);
  double value = 0.0;
  const auto [end, ec] = std::from_chars(rest.data(), rest.data() + rest.size(), value);
  if (ec != std::errc() || end == rest.data())
    throw UnitError(expected_text(kind) + ", got \"" + std::string(text) +
                    "\", which does not start with a number");
  if (!std::isfinite(value))
    throw UnitError(expected_text(kind) + ", got \"" + std::string(text) +
                    "\", which is not a finite number");
  const std::string_view unit_text = trim(rest.substr(static_cast<std::size_t>(end - rest.data())));
  if (unit_text.empty()) return value;  // bare number: SI

  // Celsius is affine, so it is only accepted on its own: θ[K] = θ[°C] + 273.15.
  if (unit_text == "C" ||
      unit_text ==
          "\xC2\xB0"
          "C" ||
      unit_text == "degC") {
    if (kind != QuantityKind::temperature)
      throw UnitError(expected_text(kind) + ", got \"" + std::string(text) +
                      "\", which is a temperature");
    return value + 273.15;
  }
  const Unit u =
      UnitReader(unit_text, expected_text(kind) + ", got \"" + std::string(text) + "\"").read();
  if (u.d != kind_dims(kind))
    throw UnitError(expected_text(kind) + ", got \"" + std::string(text) + "\", which is " +
                    describe_dims(u.d));
  return value * u.scale;
}

}  // namespace fragmpm::pipeline
