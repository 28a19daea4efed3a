// Scene keys of fracture and contact (scenes/README.md): damage laws and strengths per
// material, friction laws for [contact] and [[walls]], and the [contact] table.
#include "scene_fracture.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>

#include "fragmpm/mpm/damage_law.hpp"
#include "fragmpm/mpm/problem.hpp"

namespace fragmpm::pipeline::scene_detail {
namespace {

using QK = QuantityKind;

/// E = 9 K G / (3 K + G) [Pa], for the brittleness H̄ = σ_f² / (2 E G_f) ([XLS21] eq. (21)).
double youngs_modulus(const mpm::MaterialSpec& m) {
  return 9.0 * m.bulk_modulus * m.shear_modulus / (3.0 * m.bulk_modulus + m.shear_modulus);
}

/// The weibull table; σ̄_f is its reference_strength or, when that is left out, the material's
/// strength.
mpm::WeibullStrength read_weibull(const Section& w, std::optional<double> thickness,
                                  const Section& material, std::optional<double> strength) {
  w.allow_only({"reference_strength", "reference_volume", "modulus", "seed"});
  mpm::WeibullStrength out;
  if (!strength || w.has("reference_strength")) {
    out.reference_strength = w.quantity("reference_strength", QK::pressure);
    if (!(out.reference_strength > 0.0))
      w.expected("reference_strength", "a positive strength σ̄_f");
    if (strength && out.reference_strength != *strength)
      w.fail("reference_strength", "expected the material's strength = " + si(*strength, "Pa") +
                                       " (both give σ̄_f of [HH17] eq. (25); leave one out), got " +
                                       si(out.reference_strength, "Pa"));
  } else {
    out.reference_strength = *strength;
  }
  out.reference_volume = w.quantity("reference_volume", QK::volume);
  if (!(out.reference_volume > 0.0)) w.expected("reference_volume", "a positive volume V̄");
  out.modulus = w.number("modulus");
  if (!(out.modulus > 0.0)) w.expected("modulus", "a positive Weibull modulus m");
  const long long seed = w.optional_integer("seed").value_or(0);
  if (seed < 0) w.expected("seed", "an integer seed >= 0");
  out.seed = static_cast<unsigned long long>(seed);
  if (!thickness)
    material.fail(
        "weibull",
        "missing [physics] thickness: expected the out-of-plane thickness (a length) that "
        "turns particle areas into the volumes of [HH17] eq. (25) in a 2D scene");
  out.thickness = *thickness;
  return out;
}

std::string plain(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

/// The snap-back check of [XLS21] eq. (20)-(21) for one strength: H̄ l_ch < 1 with l_ch the
/// solver's characteristic length (mpm::characteristic_length: the material's
/// characteristic_length, or the calibrated band width of rankine_band_cells cells).
void check_softening(const Section& m, const mpm::MaterialSpec& spec,
                     const mpm::RankineSoftening& law, double strength,
                     const std::string& which_strength, const mpm::GridSpec<2>& grid, double l_ch) {
  if (std::isfinite(mpm::rankine_softening_modulus(strength, law, l_ch))) return;
  const double hbar_l =
      strength * strength * l_ch / (2.0 * law.youngs_modulus * law.fracture_energy);
  // The default l_ch is proportional to the cell size, so the cell may grow by l_max / l_ch (a
  // given l_ch has to be reduced itself).
  const double h_max =
      mpm::rankine_largest_characteristic_length(strength, law) * grid.cell_size / l_ch;
  if (spec.characteristic_length > 0.0)
    m.fail(
        "characteristic_length",
        "expected a characteristic length below " +
            si(mpm::rankine_largest_characteristic_length(strength, law), "m") + " for material '" +
            spec.name + "' (snap-back: H̄ l_ch = " +
            plain(strength * strength * l_ch / (2.0 * law.youngs_modulus * law.fracture_energy)) +
            " >= 1, [XLS21] eq. (20)-(21)), got " + si(l_ch, "m"));
  const double gf_min = strength * strength * l_ch / (2.0 * law.youngs_modulus);
  m.fail("fracture_energy",
         "expected a cell fine enough for the softening of material '" + spec.name +
             "': cell too coarse for this material (snap-back), H̄ l_ch = σ_f² l_ch / (2 E G_f) = " +
             plain(hbar_l) + " >= 1 with σ_f = " + si(strength, "Pa") + " (" + which_strength +
             "), E = " + si(law.youngs_modulus, "Pa") +
             ", G_f = " + si(law.fracture_energy, "J/m2") + " and l_ch = " + si(l_ch, "m") +
             " (grid.cell_size = " + si(grid.cell_size, "m") +
             "); the largest admissible cell size is " + si(h_max, "m") +
             " (strictly below), or a fracture energy above " + si(gf_min, "J/m2") +
             " at this cell size ([XLS21] eq. (20)-(21))");
}

}  // namespace

const std::vector<std::string_view>& damage_keys() {
  static const std::vector<std::string_view> keys = {"damage",
                                                     "strength",
                                                     "fracture_energy",
                                                     "crack_speed",
                                                     "degradation",
                                                     "weibull",
                                                     "characteristic_length",
                                                     "averaging",
                                                     "length_scale",
                                                     "residual_stiffness",
                                                     "anisotropy",
                                                     "crushed_friction_angle"};
  return keys;
}

namespace {

/// The keys of damage = "phase-field" ([KT19] §2.1): l₀, G_c and k_f. The other laws' keys are
/// refused, since nothing would read them.
mpm::PhaseField read_phase_field(const Section& m, const mpm::GridSpec<2>& grid) {
  for (std::string_view k : {"strength", "weibull", "crack_speed", "characteristic_length",
                             "averaging", "degradation", "crushed_friction_angle"})
    if (m.has(k))
      m.fail(k, "expected " + std::string(k) +
                    " only with damage = \"rankine\" or \"time-to-failure\", got it with "
                    "\"phase-field\" (the phase field needs length_scale, fracture_energy and "
                    "optionally residual_stiffness)");
  mpm::PhaseField pf;
  if (!m.has("length_scale"))
    m.fail("length_scale",
           "missing required key: expected length_scale (the phase-field length l0 of [KT19] eq. "
           "(4), a length such as \"0.5 mm\", at least the cell size " +
               si(grid.cell_size, "m") + ") for damage = \"phase-field\"");
  pf.length_scale = m.quantity("length_scale", QK::length);
  if (!(pf.length_scale > 0.0)) m.expected("length_scale", "a positive length l0");
  // The crack profile exp(−|x|/(2 l₀)) must be resolved by the grid: below one cell the nodal
  // field cannot carry it and the crack energy grows with h / l₀ (phase_field.hpp).
  if (pf.length_scale < grid.cell_size)
    m.fail("length_scale",
           "expected a phase-field length l0 no smaller than the cell size: the smallest "
           "admissible length_scale is " +
               si(grid.cell_size, "m") + " (grid.cell_size), got " + si(pf.length_scale, "m"));
  if (!m.has("fracture_energy"))
    m.fail("fracture_energy",
           "missing required key: expected fracture_energy (the critical energy release rate "
           "G_c, an energy per area such as \"2.7 J/m2\") for damage = \"phase-field\"");
  pf.fracture_energy = m.quantity("fracture_energy", QK::energy_per_area);
  if (!(pf.fracture_energy > 0.0))
    m.expected("fracture_energy", "a positive critical energy release rate G_c");
  pf.residual_stiffness = m.optional_number("residual_stiffness").value_or(0.0);
  if (!(pf.residual_stiffness >= 0.0 && pf.residual_stiffness < 1.0))
    m.expected("residual_stiffness",
               "a residual stiffness 0 <= k_f < 1 (g = (1 - k_f)(1 - d)^2 + k_f, [KT19] eq. (15))");
  if (m.has("anisotropy")) {
    // [KT19] §2.2, eq. (4)-(6): the fourth-order density G_c l0³ χᵀ Γ χ in the material axes.
    if (grid.shape_function != mpm::ShapeFunctionKind::bspline2)
      m.fail("anisotropy",
             "expected the anisotropic phase field only with [grid] shape_function = "
             "\"bspline2\" (its fourth-order term needs the second derivatives of a C1 basis)");
    const Section a = m.table("anisotropy");
    a.allow_only({"gamma_1111", "gamma_2222", "gamma_1122", "gamma_1212", "orientation"});
    mpm::PhaseFieldAnisotropy& g = pf.anisotropy;
    g.gamma_1111 = a.number("gamma_1111");
    g.gamma_2222 = a.number("gamma_2222");
    g.gamma_1212 = a.number("gamma_1212");
    g.gamma_1122 = a.optional_number("gamma_1122").value_or(0.0);
    g.orientation = a.optional_quantity("orientation", QK::angle).value_or(0.0);
    for (std::string_view k : {"gamma_1111", "gamma_2222", "gamma_1212"})
      if (!(a.number(k) >= 0.0)) a.expected(k, "a non-negative component of the tensor γ");
    // The density must not be negative for any curvature: Γ positive semi-definite.
    if (!(g.gamma_1122 * g.gamma_1122 <= g.gamma_1111 * g.gamma_2222))
      a.expected("gamma_1122",
                 "|gamma_1122| <= sqrt(gamma_1111 gamma_2222) (the fourth-order density must not "
                 "be negative)");
    if (!(g.gamma_1111 + g.gamma_2222 + g.gamma_1212 > 0.0))
      a.fail_table(
          "expected some positive component of γ (all zero is the second-order model: "
          "leave anisotropy out)");
    pf.anisotropic = true;
  }
  return pf;
}

}  // namespace

void read_damage(const Section& m, mpm::MaterialSpec& spec, std::optional<double> thickness,
                 const mpm::GridSpec<2>& grid, double particle_spacing) {
  const std::string law = m.optional_string("damage").value_or("none");
  if (law == "none") {
    for (std::string_view k : damage_keys())
      if (k != "damage" && m.has(k))
        m.fail(k, "expected " + std::string(k) +
                      " only with a damage law (damage = \"rankine\", \"time-to-failure\" or "
                      "\"phase-field\"), got it with damage = \"none\"");
    spec.damage = mpm::NoDamage{};
    return;
  }
  if (law == "phase-field") {
    spec.damage = read_phase_field(m, grid);
    return;
  }
  if (law != "rankine" && law != "time-to-failure")
    m.expected("damage", "one of \"none\", \"rankine\", \"time-to-failure\", \"phase-field\"");
  for (std::string_view k : {"length_scale", "residual_stiffness", "anisotropy"})
    if (m.has(k))
      m.fail(k, "expected " + std::string(k) +
                    " only with damage = \"phase-field\", got it with \"" + law + "\"");

  // Strength: uniform σ_f, or a Weibull field ([HH17] eq. (25)) whose σ̄_f may come from `strength`.
  if (!m.has("strength") && !m.has("weibull"))
    m.fail(
        "strength",
        "missing required key: expected strength (a pressure, e.g. \"50 MPa\") or a weibull table "
        "for damage = \"" +
            law + "\"");
  std::optional<double> strength;
  if (m.has("strength")) {
    strength = m.quantity("strength", QK::pressure);
    if (!(*strength > 0.0)) m.expected("strength", "a positive tensile strength σ_f");
    spec.strength = *strength;
  }
  if (m.has("weibull")) {
    spec.weibull = true;
    spec.weibull_strength = read_weibull(m.table("weibull"), thickness, m, strength);
    spec.strength = spec.weibull_strength.reference_strength;
  }

  if (m.has("characteristic_length")) {
    spec.characteristic_length = m.quantity("characteristic_length", QK::length);
    if (!(spec.characteristic_length > 0.0))
      m.expected("characteristic_length",
                 "a positive length l_ch (default: 1.13 h for rankine, the cell diagonal for "
                 "time-to-failure)");
  }
  const std::string degradation = m.optional_string("degradation").value_or("tensile");
  if (degradation == "tensile")
    spec.degradation = mpm::Degradation::tensile_spectral;
  else if (degradation == "isotropic")
    spec.degradation = mpm::Degradation::isotropic;
  else if (degradation == "volumetric-deviatoric")
    spec.degradation = mpm::Degradation::volumetric_deviatoric;
  else if (degradation == "hencky-spectral")
    spec.degradation = mpm::Degradation::hencky_spectral;
  else
    m.expected("degradation",
               "one of \"tensile\" (spectral, [HH17] eq. (26)-(27)), \"isotropic\" ([XLS21] eq. "
               "(7)), \"volumetric-deviatoric\" ([AMM09]), \"hencky-spectral\" ([KT19] eq. (14))");
  if (m.has("crushed_friction_angle")) {
    if (spec.degradation != mpm::Degradation::hencky_spectral)
      m.fail("crushed_friction_angle",
             "expected crushed_friction_angle only with degradation = \"hencky-spectral\" (the "
             "flow of failed material is returned in its principal logarithmic strains), got "
             "degradation = \"" +
                 degradation + "\"");
    spec.crushed_friction_angle = m.quantity("crushed_friction_angle", QK::angle);
    if (!(spec.crushed_friction_angle > 0.0 && spec.crushed_friction_angle < 0.5 * M_PI))
      m.expected("crushed_friction_angle",
                 "a friction angle between 0 and 90 deg (e.g. \"30 deg\"), the Mohr-Coulomb "
                 "angle of the failed material");
  }

  if (law == "rankine") {
    if (m.has("crack_speed"))
      m.fail(
          "crack_speed",
          "expected crack_speed only with damage = \"time-to-failure\", got it with \"rankine\"");
    mpm::RankineSoftening r;
    r.fracture_energy = m.quantity("fracture_energy", QK::energy_per_area);
    if (!(r.fracture_energy > 0.0)) m.expected("fracture_energy", "a positive fracture energy G_f");
    r.youngs_modulus = youngs_modulus(spec);
    const std::string averaging = m.optional_string("averaging").value_or("local");
    if (averaging == "nonlocal")
      r.nonlocal = true;
    else if (averaging != "local")
      m.expected("averaging",
                 "one of \"local\" (the particle's own largest principal stress drives the law) "
                 "or \"nonlocal\" (its kernel average over the cell diagonal)");
    spec.damage = r;
    // l_ch of a lattice particle (volume s² per unit thickness), as the solver computes it: known
    // only once the law is set (before, the default for no damage law would be taken).
    const double band_width =
        mpm::characteristic_length<2>(spec, particle_spacing * particle_spacing, grid.cell_size);
    // With Weibull strengths the nominal strength checked is the median at the particles' volume;
    // stronger draws that snap back are capped at the snap-back limit by the damage update
    // (warned in assign_strengths).
    if (spec.weibull)
      check_softening(m, spec, r,
                      mpm::weibull_median_strength(particle_spacing * particle_spacing,
                                                   spec.weibull_strength, 2),
                      "the Weibull median at the particle volume", grid, band_width);
    else
      check_softening(m, spec, r, spec.strength, "strength", grid, band_width);
  } else {
    if (m.has("fracture_energy"))
      m.fail("fracture_energy",
             "expected fracture_energy only with damage = \"rankine\", got it with "
             "\"time-to-failure\"");
    if (m.has("averaging"))
      m.fail("averaging",
             "expected averaging only with damage = \"rankine\", got it with \"time-to-failure\"");
    mpm::TimeToFailure t;
    t.crack_speed = m.quantity("crack_speed", QK::velocity);
    if (!(t.crack_speed > 0.0))
      m.expected("crack_speed", "a positive crack speed c_f ([HH17] eq. (24))");
    spec.damage = t;
  }
}

void assign_strengths(mpm::Problem<2>& problem, const std::vector<Section>& sections) {
  mpm::Particles<2>& P = problem.particles;
  for (std::size_t m = 0; m < problem.materials.size(); ++m) {
    const mpm::MaterialSpec& spec = problem.materials[m];
    std::vector<std::size_t> mine;
    for (std::size_t p = 0; p < P.size(); ++p)
      if (static_cast<std::size_t>(P.material[p]) == m) mine.push_back(p);
    // Strength drives only the damage laws of damage_law.hpp; the phase field never reads it.
    if (!spec.damages() || std::holds_alternative<mpm::PhaseField>(spec.damage)) {
      for (std::size_t p : mine) P.strength[p] = std::numeric_limits<double>::infinity();
      continue;
    }
    if (!spec.weibull) {
      for (std::size_t p : mine) P.strength[p] = spec.strength;
      continue;
    }
    std::vector<double> volumes;
    volumes.reserve(mine.size());
    for (std::size_t p : mine) volumes.push_back(P.volume0[p]);
    const std::vector<double> s = mpm::weibull_strengths(volumes, spec.weibull_strength, 2);
    std::size_t snapping = 0;
    const auto* rankine = std::get_if<mpm::RankineSoftening>(&spec.damage);
    for (std::size_t k = 0; k < mine.size(); ++k) {
      P.strength[mine[k]] = s[k];
      // The solver's l_ch of this particle: the damage update caps a draw that snaps back here.
      if (rankine &&
          !std::isfinite(mpm::rankine_softening_modulus(
              s[k], *rankine,
              mpm::characteristic_length<2>(spec, P.volume0[mine[k]], problem.grid.cell_size))))
        ++snapping;
    }
    if (snapping > 0)
      std::cerr << sections[m].file() << ":" << sections[m].line_of("weibull")
                << ": warning: material '" << spec.name << "': " << snapping << " of "
                << mine.size()
                << " particles drew a Weibull strength for which the cell is too coarse "
                   "(snap-back, H̄ l_ch >= 1); "
                   "their strength is capped at sqrt(2 E G_f / l_ch), at which they fail at once\n";
  }
}

mpm::FrictionLaw read_friction(const Section& s, std::string_view k) {
  const toml::node* n = s.find(k);
  if (n && n->is_number()) {
    const double mu = s.number(k);
    if (!(mu >= 0.0)) s.expected(k, "a Coulomb friction coefficient >= 0");
    return mpm::CoulombFriction{mu};
  }
  if (!n || !n->is_table())
    s.expected(k,
               "a Coulomb friction coefficient (a number >= 0) or a friction-law table { law = "
               "\"coulomb\" | "
               "\"velocity-dependent\" | \"adhesion\" | \"static-dynamic\" | "
               "\"thermal-softening\", ... }");
  const Section f = s.table(k);
  const std::string law = f.optional_string("law").value_or("coulomb");
  auto coefficient = [&](std::string_view key) {
    const double mu = f.number(key);
    if (!(mu >= 0.0)) f.expected(key, "a friction coefficient >= 0");
    return mu;
  };
  if (law == "coulomb") {
    f.allow_only({"law", "mu"});
    return mpm::CoulombFriction{coefficient("mu")};
  }
  if (law == "velocity-dependent") {  // [NBS18] eq. (23): μ = μ₀ + k |Δv′|
    f.allow_only({"law", "mu", "slope"});
    mpm::VelocityDependentFriction v;
    v.coefficient = coefficient("mu");
    v.slope = f.quantity("slope", QK::inverse_velocity);  // k < 0 (velocity weakening) is allowed
    return v;
  }
  if (law == "adhesion") {  // [NBS18] eq. (24)-(25)
    f.allow_only({"law", "mu", "shear_strength", "tensile_strength"});
    mpm::AdhesiveFriction a;
    a.coefficient = coefficient("mu");
    a.shear_strength = f.quantity("shear_strength", QK::pressure);
    if (!(a.shear_strength >= 0.0))
      f.expected("shear_strength", "an adhesive shear strength S_a >= 0");
    a.tensile_strength = f.optional_quantity("tensile_strength", QK::pressure).value_or(0.0);
    if (!(a.tensile_strength >= 0.0))
      f.expected("tensile_strength", "an adhesive tensile strength N_a >= 0");
    return a;
  }
  if (law == "static-dynamic") {  // [NBS18] eq. (42)-(43)
    f.allow_only({"law", "mu_static", "mu_dynamic", "half_velocity"});
    mpm::SmoothStaticDynamicFriction sd;
    sd.static_coefficient = coefficient("mu_static");
    sd.dynamic_coefficient = coefficient("mu_dynamic");
    sd.half_velocity = f.quantity("half_velocity", QK::velocity);
    if (!(sd.half_velocity >= 0.0))
      f.expected(
          "half_velocity",
          "a slip speed v½ >= 0 at which μ is halfway between μ_s and μ_d (0 = a sharp step)");
    return sd;
  }
  if (law == "thermal-softening") {  // [XLS21] eq. (15)
    f.allow_only({"law", "mu", "theta_ref", "theta_dam"});
    mpm::ThermalSofteningFriction t;
    t.coefficient = coefficient("mu");
    t.reference_temperature = f.quantity("theta_ref", QK::temperature);
    if (!(t.reference_temperature >= 0.0))
      f.expected("theta_ref", "an absolute temperature >= 0 K");
    t.damage_temperature = f.quantity("theta_dam", QK::temperature);
    if (!(t.damage_temperature > t.reference_temperature))
      f.expected("theta_dam",
                 "a temperature above theta_ref = " + si(t.reference_temperature, "K"));
    return t;
  }
  f.expected("law",
             "one of \"coulomb\", \"velocity-dependent\", \"adhesion\", \"static-dynamic\", "
             "\"thermal-softening\"");
}

mpm::ContactSpec<2> read_contact(const Section& c) {
  c.allow_only({"partitioning", "friction", "critical_damage", "minimum_damage", "rebuild_fraction",
                "gap_test", "conductance", "conductance_pressure", "conductance_exponent", "normal",
                "nodal_gradient", "friction_heating"});
  mpm::ContactSpec<2> spec;
  const std::string partitioning = c.optional_string("partitioning").value_or("auto");
  if (partitioning == "auto")
    spec.partitioning = mpm::Partitioning::automatic;
  else if (partitioning == "off")
    spec.partitioning = mpm::Partitioning::off;
  else if (partitioning == "bodies")
    spec.partitioning = mpm::Partitioning::bodies;
  else
    c.expected("partitioning", "one of \"auto\", \"off\", \"bodies\"");
  const std::string nodal = c.optional_string("nodal_gradient").value_or("principal");
  if (nodal == "principal")
    spec.nodal_gradient = mpm::NodalGradientRule::principal;
  else if (nodal == "largest")
    spec.nodal_gradient = mpm::NodalGradientRule::largest;
  else
    c.expected("nodal_gradient",
               "one of \"principal\" (structure tensor), \"largest\" ([HH17] Alg. 1)");
  if (c.has("friction")) spec.friction = read_friction(c, "friction");
  const std::string heating = c.optional_string("friction_heating").value_or("lumped-slip");
  if (heating == "lumped-slip")
    spec.friction_work_order = mpm::FrictionWorkOrder::lumped_slip;
  else if (heating == "second-order")
    spec.friction_work_order = mpm::FrictionWorkOrder::second;
  else if (heating == "first-order")
    spec.friction_work_order = mpm::FrictionWorkOrder::first;
  else
    c.expected("friction_heating",
               "one of \"lumped-slip\" (the default), \"second-order\" ([NBS18] eq. (34)-(36)), "
               "\"first-order\" ([NBS18] eq. (27))");
  if (auto d = c.optional_number("critical_damage")) {
    if (!(*d > 0.0 && *d <= 1.0)) c.expected("critical_damage", "a damage level 0 < D_cr <= 1");
    spec.critical_damage = *d;
  }
  if (auto d = c.optional_number("minimum_damage")) {
    if (!(*d >= 0.0 && *d < 1.0))
      c.expected("minimum_damage", "a damage level 0 <= D_min < 1 ([HH17] eq. (21))");
    spec.minimum_damage = *d;
  }
  if (auto f = c.optional_number("rebuild_fraction")) {
    if (!(*f >= 0.0 && *f <= 1.0))
      c.expected("rebuild_fraction",
                 "a fraction of the kernel radius 0 <= rebuild_fraction <= 1 (0 = every step)");
    spec.rebuild_fraction = *f;
  }
  spec.position_gap_test = c.optional_bool("gap_test").value_or(false);
  if (auto n = c.optional_vector("normal", std::nullopt)) {
    if (!(n->norm() > 0.0))
      c.expected("normal", "a non-zero normal vector (the contact normal of field 0)");
    spec.normal = *n / n->norm();
  }
  return spec;
}

}  // namespace fragmpm::pipeline::scene_detail
