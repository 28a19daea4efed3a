// Node-level contact ([NBS18] §2.6-2.10): each friction law against its closed form at a single
// two-field node in the stick and slide branches; momentum conservation; removal of approach;
// separating fields; rigid walls; tensile adhesion (eq. (25)); friction work against the kinetic
// energy removed, and the lumped-slip work against the slip of the lumped velocities.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "fragmpm/mpm/contact_exchange.hpp"

using namespace fragmpm::mpm;

namespace {

constexpr double dt = 1e-6;
constexpr double inf = std::numeric_limits<double>::infinity();

// Field a (m = 2 kg) below, b (m = 3 kg) above, n = +y; b approaches at 1 m/s and slides at
// `slide` m/s in +x relative to a. m_red = 1.2 kg, d_n = −1.2 N s, d_t = 1.2 slide N s.
ContactNode<2> two_field_node(double slide) {
  ContactNode<2> node;
  node.mass_a = 2.0;
  node.mass_b = 3.0;
  node.velocity_a = Vec<2>(0.5, 0.25);
  node.velocity_b = Vec<2>(0.5 + slide, -0.75);
  node.normal = Vec<2>(0.0, 1.0);
  return node;
}
constexpr double m_red = 1.2;
constexpr double normal_star = 1.2;  // N A_c Δt = −d_n

template <int D>
Vec<D> velocity_after_a(const ContactNode<D>& node, const ContactExchange<D>& ex) {
  return node.velocity_a + ex.momentum_change_a / node.mass_a;
}
template <int D>
Vec<D> velocity_after_b(const ContactNode<D>& node, const ContactExchange<D>& ex) {
  if (std::isinf(node.mass_b)) return node.velocity_b;
  return node.velocity_b - ex.momentum_change_a / node.mass_b;
}

ContactExchange<2> run(const ContactNode<2>& node, const FrictionLaw& law,
                       FrictionWorkOrder order = FrictionWorkOrder::first) {
  return exchange_momentum<2>(node, law, dt, order);
}

}  // namespace

TEST(ContactExchange, CoulombSlideIsEq20AndStickIsCentreOfMass) {
  const CoulombFriction law{0.3};
  // Slide: d_t = 1.2·2 = 2.4 > μ N* = 0.36 → Δp′ = d_n (n − μ t̂) with t̂ = +x ([NBS18] eq. (20)).
  const auto node = two_field_node(2.0);
  const auto ex = run(node, law);
  ASSERT_TRUE(ex.in_contact);
  ASSERT_TRUE(ex.sliding);
  EXPECT_NEAR(ex.momentum_change_a.x(), 0.3 * normal_star, 1e-14);
  EXPECT_NEAR(ex.momentum_change_a.y(), -normal_star, 1e-14);
  EXPECT_NEAR(ex.normal_impulse, normal_star, 1e-14);
  EXPECT_NEAR(ex.slip_speed, 2.0 - 0.3 * normal_star / m_red, 1e-14);

  // Stick: d_t = 1.2·0.25 = 0.3 < 0.36 → both fields take the centre-of-mass velocity ([NBS18] eq.
  // (12)-(13)).
  const auto stuck_node = two_field_node(0.25);
  const auto stuck = run(stuck_node, law);
  ASSERT_TRUE(stuck.in_contact);
  EXPECT_FALSE(stuck.sliding);
  const Vec<2> v_cm = (2.0 * stuck_node.velocity_a + 3.0 * stuck_node.velocity_b) / 5.0;
  EXPECT_NEAR((velocity_after_a(stuck_node, stuck) - v_cm).norm(), 0.0, 1e-14);
  EXPECT_NEAR((velocity_after_b(stuck_node, stuck) - v_cm).norm(), 0.0, 1e-14);
  EXPECT_EQ(stuck.friction_work, 0.0);
  EXPECT_EQ(stuck.slip_speed, 0.0);
}

TEST(ContactExchange, VelocityDependentSlipSpeedSatisfiesEq22) {
  const VelocityDependentFriction law{0.2, 0.05};  // μ = 0.2 + 0.05 s/m · |Δv′|
  const auto node = two_field_node(4.0);           // d_t = 4.8 N s
  const auto ex = run(node, law);
  ASSERT_TRUE(ex.sliding);
  const double s = ex.momentum_change_a.x();
  // Closed form s = (m_red μ₀ + k d_t) N* / (m_red + k N*) (eq. (23) with N* = −d_n).
  const double d_t = m_red * 4.0;
  EXPECT_NEAR(s, (m_red * 0.2 + 0.05 * d_t) * normal_star / (m_red + 0.05 * normal_star), 1e-14);
  // Consistency with eq. (22): the sliding traction is μ at the final slip speed times N.
  const Vec<2> slip = velocity_after_b(node, ex) - velocity_after_a(node, ex);
  EXPECT_NEAR(slip.y(), 0.0, 1e-14);
  EXPECT_NEAR(slip.x(), ex.slip_speed, 1e-13);
  EXPECT_NEAR(s, friction_coefficient(law, slip.norm()) * normal_star, 1e-14);

  // Stick exactly when d_t ≤ μ₀ N* = 0.24 N s: slide speed 0.19 m/s → d_t = 0.228.
  const auto stuck = run(two_field_node(0.19), law);
  EXPECT_TRUE(stuck.in_contact);
  EXPECT_FALSE(stuck.sliding);
  EXPECT_TRUE(run(two_field_node(0.21), law).sliding);
}

TEST(ContactExchange, AdhesiveSlideIsEq24) {
  const AdhesiveFriction law{0.2, 4.0e5, 0.0};  // μ, S_a = 0.4 MPa, no tensile adhesion
  auto node = two_field_node(3.0);              // d_t = 3.6 N s
  node.area = 2.0;                              // A_c Δt = 2e-6 m² s → S_a A_c Δt = 0.8 N s
  const auto ex = run(node, law);
  ASSERT_TRUE(ex.sliding);
  EXPECT_NEAR(ex.momentum_change_a.x(), 0.8 + 0.2 * normal_star, 1e-13);
  EXPECT_NEAR(ex.momentum_change_a.y(), -normal_star, 1e-14);
  // S_stick below S_a + μN sticks, though it exceeds μN alone.
  node.velocity_b.x() = node.velocity_a.x() + 0.8;  // d_t = 0.96 < 1.04
  const auto stuck = run(node, law);
  EXPECT_TRUE(stuck.in_contact);
  EXPECT_FALSE(stuck.sliding);
  EXPECT_NEAR((velocity_after_b(node, stuck) - velocity_after_a(node, stuck)).norm(), 0.0, 1e-14);
  // Without tensile adhesion separating surfaces are free.
  node.velocity_b.y() = node.velocity_a.y() + 0.1;
  EXPECT_FALSE(run(node, law).in_contact);
}

TEST(ContactExchange, TensileAdhesionFollowsEllipseEq25) {
  // S_a A_c Δt = 1.0 N s and N_a A_c Δt = 0.5 N s.
  const AdhesiveFriction law{0.2, 1.0e6, 0.5e6};
  ContactNode<2> node = two_field_node(0.0);
  node.area = 1.0;
  // Separating: b moves away at w_n, slides at w_t; d_n = 1.2 w_n, d_t = 1.2 w_t.
  auto separating = [&](double d_t, double d_n) {
    ContactNode<2> n = node;
    n.velocity_b = n.velocity_a + Vec<2>(d_t / m_red, d_n / m_red);
    return n;
  };
  // Inside the ellipse: (0.6/1)² + (0.3/0.5)² = 0.72 ≤ 1 → stuck, moving with the centre of mass.
  const auto inside = separating(0.6, 0.3);
  const auto held = run(inside, law);
  EXPECT_TRUE(held.in_contact);
  EXPECT_FALSE(held.sliding);
  EXPECT_NEAR((velocity_after_b(inside, held) - velocity_after_a(inside, held)).norm(), 0.0, 1e-14);
  EXPECT_NEAR(held.normal_impulse, -0.3, 1e-14);  // tensile
  // Outside: (0.8)² + (0.4/0.5)² = 1.28 > 1 → the bond breaks and both fields keep their
  // velocities.
  const auto outside = separating(0.8, 0.4);
  const auto broken = run(outside, law);
  EXPECT_FALSE(broken.in_contact);
  EXPECT_EQ(broken.momentum_change_a, Vec<2>::Zero());
  // Pure tension just inside / outside N_a.
  EXPECT_TRUE(run(separating(0.0, 0.49), law).in_contact);
  EXPECT_FALSE(run(separating(0.0, 0.51), law).in_contact);
  // An open gap counts as separated too: held by adhesion while inside the ellipse.
  ContactNode<2> apart = separating(0.6, -0.3);
  apart.gap_closed = false;
  EXPECT_TRUE(run(apart, law).in_contact);
}

TEST(ContactExchange, SmoothStaticDynamicMatchesEq42AndEq43) {
  const SmoothStaticDynamicFriction law{0.4, 0.2, 0.05};
  const auto node = two_field_node(0.7);  // d_t = 0.84 > μ_s N* = 0.48
  const auto ex = run(node, law);
  ASSERT_TRUE(ex.sliding);
  const double s = ex.momentum_change_a.x();
  const Vec<2> slip = velocity_after_b(node, ex) - velocity_after_a(node, ex);
  EXPECT_NEAR(slip.norm(), ex.slip_speed, 1e-13);
  // Eq. 42 at the final slip velocity.
  EXPECT_NEAR(s, friction_coefficient(law, slip.norm()) * normal_star, 1e-13);
  // Eq. 43 as printed: S/N = (D*/N* + μ_d)/2 − √(((D*/N* − μ_d)/2)² − (μ_s − μ_d) k*/N*).
  const double k_star = 0.05 * m_red, d_star = m_red * 0.7 + k_star;
  const double ratio = d_star / normal_star;
  const double eq43 = 0.5 * (ratio + 0.2) -
                      std::sqrt(std::pow(0.5 * (ratio - 0.2), 2) - 0.2 * k_star / normal_star);
  EXPECT_NEAR(s / normal_star, eq43, 1e-12);
  // Static branch: d_t ≤ μ_s N* sticks.
  EXPECT_FALSE(run(two_field_node(0.39), law).sliding);
  // Limits: v½ → 0 slides at μ_d, v½ → ∞ at μ_s.
  const auto sharp = run(node, SmoothStaticDynamicFriction{0.4, 0.2, 0.0});
  EXPECT_NEAR(sharp.momentum_change_a.x(), 0.2 * normal_star, 1e-14);
  const auto flat = run(node, SmoothStaticDynamicFriction{0.4, 0.2, 1e12});
  EXPECT_NEAR(flat.momentum_change_a.x(), 0.4 * normal_star, 1e-9);
}

TEST(ContactExchange, ThermalSofteningIsEq15) {
  const ThermalSofteningFriction law{0.5, 300.0, 900.0};
  EXPECT_DOUBLE_EQ(friction_coefficient(law, 300.0), 0.5);
  EXPECT_DOUBLE_EQ(friction_coefficient(law, 600.0), 0.125);  // μ₀ (300/600)²
  EXPECT_EQ(friction_coefficient(law, 900.0), 0.0);
  EXPECT_EQ(friction_coefficient(law, 1500.0), 0.0);  // Macaulay bracket
  auto node = two_field_node(1.0);
  node.temperature = 600.0;
  const auto warm = run(node, law);
  ASSERT_TRUE(warm.sliding);
  EXPECT_NEAR(warm.momentum_change_a.x(), 0.125 * normal_star, 1e-14);
  // At θ_dam the interface is frictionless: only the normal exchange, no friction work.
  node.temperature = 900.0;
  const auto hot = run(node, law, FrictionWorkOrder::second);
  EXPECT_TRUE(hot.in_contact);
  EXPECT_EQ(hot.momentum_change_a.x(), 0.0);
  EXPECT_NEAR(hot.momentum_change_a.y(), -normal_star, 1e-14);
  EXPECT_EQ(hot.friction_work, 0.0);
  EXPECT_NEAR(hot.slip_speed, 1.0, 1e-14);
}

TEST(ContactExchange, ConservesMomentumAndRemovesApproachForEveryLaw) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const FrictionLaw laws[] = {
      CoulombFriction{0.3}, VelocityDependentFriction{0.2, 0.1}, AdhesiveFriction{0.2, 1e5, 1e5},
      SmoothStaticDynamicFriction{0.4, 0.2, 0.05}, ThermalSofteningFriction{0.4, 300.0, 800.0}};
  int contacts = 0, slides = 0;
  for (const auto& law : laws)
    for (int trial = 0; trial < 400; ++trial) {
      ContactNode<3> node;
      node.mass_a = 1e-3 * (1.1 + u(rng));
      node.mass_b = 1e-3 * (1.1 + u(rng));
      node.velocity_a = 10.0 * Vec<3>(u(rng), u(rng), u(rng));
      node.velocity_b = 10.0 * Vec<3>(u(rng), u(rng), u(rng));
      node.normal = Vec<3>(u(rng), u(rng), u(rng)).normalized();
      node.force_a = Vec<3>(u(rng), u(rng), u(rng));
      node.force_b = Vec<3>(u(rng), u(rng), u(rng));
      node.area = 1e-4;
      node.temperature = 500.0;
      const auto ex = exchange_momentum<3>(node, law, dt, FrictionWorkOrder::second);
      const Vec<3> va = velocity_after_a(node, ex), vb = velocity_after_b(node, ex);
      const Vec<3> p0 = node.mass_a * node.velocity_a + node.mass_b * node.velocity_b;
      const Vec<3> p1 = node.mass_a * va + node.mass_b * vb;
      const double scale =
          node.mass_a * node.velocity_a.norm() + node.mass_b * node.velocity_b.norm();
      EXPECT_LE((p1 - p0).norm(), 4.0 * std::numeric_limits<double>::epsilon() * scale);
      const double approach = (node.velocity_b - node.velocity_a).dot(node.normal);
      if (approach < 0.0) {
        ++contacts;
        ASSERT_TRUE(ex.in_contact);
        EXPECT_NEAR((vb - va).dot(node.normal), 0.0, 1e-13);  // approach removed
        EXPECT_GT(ex.normal_impulse, 0.0);
        EXPECT_GE(ex.friction_work, 0.0);
        if (ex.sliding) {
          ++slides;
          EXPECT_NEAR((vb - va).norm(), ex.slip_speed, 1e-12);
        } else {
          EXPECT_NEAR((vb - va).norm(), 0.0, 1e-12);
        }
      } else if (!std::holds_alternative<AdhesiveFriction>(law)) {
        EXPECT_FALSE(ex.in_contact);  // separating fields are left alone
        EXPECT_EQ(ex.momentum_change_a, Vec<3>::Zero());
      }
    }
  EXPECT_GT(contacts, 800);
  EXPECT_GT(slides, 400);
}

TEST(ContactExchange, SeparatingOrGappedFieldsAreUntouched) {
  auto node = two_field_node(1.0);
  node.velocity_b.y() = node.velocity_a.y() + 0.5;  // b moves away from a
  const auto apart = run(node, CoulombFriction{0.5});
  EXPECT_FALSE(apart.in_contact);
  EXPECT_EQ(apart.momentum_change_a, Vec<2>::Zero());
  EXPECT_EQ(apart.friction_work, 0.0);
  // Approaching but the position test says the surfaces are apart ([NBS18] eq. (8)).
  auto gapped = two_field_node(1.0);
  gapped.gap_closed = false;
  EXPECT_FALSE(run(gapped, CoulombFriction{0.5}).in_contact);
  // Grazing (Δv·n = 0) is not contact.
  auto grazing = two_field_node(1.0);
  grazing.velocity_b.y() = grazing.velocity_a.y();
  EXPECT_FALSE(run(grazing, CoulombFriction{0.5}).in_contact);
}

TEST(ContactExchange, RigidWallTakesTheFieldToTheWallVelocity) {
  ContactNode<2> node;
  node.mass_a = 0.5;
  node.mass_b = inf;
  node.velocity_a = Vec<2>(3.0, -2.0);  // into a floor moving up at 0.5 m/s and right at 1 m/s
  node.velocity_b = Vec<2>(1.0, 0.5);
  node.normal = Vec<2>(0.0, -1.0);  // from the field (above) towards the wall (below)
  node.force_a = Vec<2>(0.1, 0.2);
  node.force_b = Vec<2>(5.0, 5.0);  // ignored for a rigid wall
  for (auto order : {FrictionWorkOrder::first, FrictionWorkOrder::second}) {
    const auto ex = exchange_momentum<2>(node, CoulombFriction{0.2}, dt, order);
    ASSERT_TRUE(ex.in_contact);
    ASSERT_TRUE(ex.sliding);  // d_t = 0.5·2 = 1 > 0.2·1.25
    EXPECT_TRUE(ex.momentum_change_a.allFinite());
    EXPECT_TRUE(std::isfinite(ex.friction_work));
    const Vec<2> va = velocity_after_a(node, ex);
    EXPECT_NEAR(va.y(), 0.5, 1e-14);              // normal velocity = the wall's
    EXPECT_NEAR(va.x(), 3.0 - 0.2 * 2.5, 1e-14);  // Δv_t = μ Δv_n
    EXPECT_NEAR(ex.normal_impulse, 0.5 * 2.5, 1e-14);
    EXPECT_NEAR(ex.slip_speed, 1.5, 1e-14);
  }
  // Sticking to the wall: the field moves with it.
  const auto stuck =
      exchange_momentum<2>(node, CoulombFriction{2.0}, dt, FrictionWorkOrder::second);
  EXPECT_FALSE(stuck.sliding);
  EXPECT_NEAR((velocity_after_a(node, stuck) - node.velocity_b).norm(), 0.0, 1e-14);
}

TEST(ContactExchange, SecondOrderWorkIsTheTangentialKineticEnergyRemovedWithoutForces) {
  // With no nodal forces the trial velocities are the start-of-step velocities; friction removes
  // ½ m_red (v_t² − v′_t²) from the relative tangential motion in one step, which eq. (34) recovers
  // exactly for any step size. First order (eq. (27)) misses s²/(2 m_red) and converges as s → 0.
  const CoulombFriction law{0.25};
  for (double approach : {1.0, 1e-2, 1e-4}) {
    ContactNode<2> node = two_field_node(2.0);
    node.velocity_a =
        Vec<2>::Zero();  // a at rest so that the velocity differences carry no round-off
    node.velocity_b = Vec<2>(2.0, -approach);  // the normal impulse shrinks like the step
    const double n_star = m_red * approach, s = 0.25 * n_star, d_t = m_red * 2.0;
    // ½ m_red (v_t² − v′_t²) with v_t = d_t/m_red, v′_t = (d_t − s)/m_red, factored to avoid
    // cancellation.
    const double ke_loss = s * (2.0 * d_t - s) / (2.0 * m_red);
    const auto second = run(node, law, FrictionWorkOrder::second);
    const auto first = run(node, law, FrictionWorkOrder::first);
    ASSERT_TRUE(second.sliding);
    EXPECT_NEAR(second.friction_work, ke_loss, 1e-14 * ke_loss);
    // Energy lost overall = normal (inelastic) loss + friction work, from the velocities
    // themselves.
    const auto ke = [&](const Vec<2>& va, const Vec<2>& vb) {
      return 0.5 * node.mass_a * va.squaredNorm() + 0.5 * node.mass_b * vb.squaredNorm();
    };
    const double lost = ke(node.velocity_a, node.velocity_b) -
                        ke(velocity_after_a(node, second), velocity_after_b(node, second));
    EXPECT_NEAR(lost, 0.5 * m_red * approach * approach + second.friction_work, 1e-12);
    EXPECT_NEAR(first.friction_work / ke_loss - 1.0, -s / (2.0 * d_t - s), 1e-12);
  }
}

TEST(ContactExchange, SecondOrderWorkClosesEnergyBalanceUnderConstantForces) {
  // Constant tangential nodal forces: the fields start the step at v⁰ = v − f Δt/m and the contact
  // force Δp′/Δt is constant, so velocities are linear in time and every work is exact by the
  // trapezoid rule. Kinetic energy change = work of the nodal forces − normal collision loss −
  // friction work; eq. (34) must close this balance (eq. (30) carries the forces into f_t).
  const double step = 1e-3;
  ContactNode<2> node = two_field_node(2.0);
  node.force_a = Vec<2>(-300.0, 0.0);
  node.force_b = Vec<2>(900.0, 0.0);
  const auto ex = exchange_momentum<2>(node, CoulombFriction{0.3}, step, FrictionWorkOrder::second);
  ASSERT_TRUE(ex.sliding);
  const Vec<2> va0 = node.velocity_a - node.force_a * step / node.mass_a;
  const Vec<2> vb0 = node.velocity_b - node.force_b * step / node.mass_b;
  const Vec<2> va1 = velocity_after_a(node, ex), vb1 = velocity_after_b(node, ex);
  ASSERT_GT((vb0 - va0).x(), 0.0);  // slid the whole step (eq. (34) branch)
  const double force_work =
      step * (node.force_a.dot(0.5 * (va0 + va1)) + node.force_b.dot(0.5 * (vb0 + vb1)));
  // The normal contact impulse acts on normal velocities that the forces do not change.
  const double normal_loss = 0.5 * m_red * std::pow((node.velocity_b - node.velocity_a).y(), 2);
  const auto ke = [&](const Vec<2>& va, const Vec<2>& vb) {
    return 0.5 * node.mass_a * va.squaredNorm() + 0.5 * node.mass_b * vb.squaredNorm();
  };
  const double friction_work = ke(va0, vb0) + force_work - normal_loss - ke(va1, vb1);
  EXPECT_NEAR(ex.friction_work, friction_work, 1e-12 * friction_work);
  const auto first =
      exchange_momentum<2>(node, CoulombFriction{0.3}, step, FrictionWorkOrder::first);
  EXPECT_GT(std::abs(first.friction_work - friction_work),
            1e-3 * friction_work);  // first order is not exact

  // Slip starting within the step (v⁰ reversed): eq. (36) = W₁²/(2W₂) with t_s of eq. (35).
  ContactNode<2> onset = node;
  onset.force_b = Vec<2>(9000.0, 0.0);
  const auto late =
      exchange_momentum<2>(onset, CoulombFriction{0.3}, step, FrictionWorkOrder::second);
  ASSERT_TRUE(late.sliding);
  const double s = late.momentum_change_a.x(), d_t = m_red * 2.0;
  const double f_t = (onset.mass_a * onset.force_b.x() - onset.mass_b * onset.force_a.x()) /
                     (onset.mass_a + onset.mass_b);
  const double w1 = s * (d_t - s) / m_red, w2 = s * (f_t * step - s) / m_red;
  ASSERT_GT(w2, w1);
  EXPECT_NEAR(late.friction_work, w1 * w1 / (2.0 * w2), 1e-14 * w1);
  // = sliding force × mean slip speed over [t_s, Δt].
  const double slip_end = (d_t - s) / m_red, t_s = step * (1.0 - w1 / w2);
  EXPECT_NEAR(late.friction_work, (s / step) * 0.5 * slip_end * (step - t_s), 1e-12 * w1);
}

TEST(ContactExchange, ContactAreaSumsToTheNodeSpacingAcrossAStraightInterface) {
  // Interface parallel to the grid at height y₀ between nodes at y = 0 and y = h, material a below:
  // with bilinear weights Ω_b(node 0) = h (h − y₀)²/(2h) and Ω_a(node h) = h y₀²/(2h) ([NBS18] eq.
  // (5)).
  const double h = 2e-3, t = 1e-3;
  for (double y0 : {0.0, 0.3e-3, 1.0e-3, 1.7e-3}) {
    const double lower =
        contact_area_2d(h * h, h * h - 0.5 * (h - y0) * (h - y0), 0.5 * (h - y0) * (h - y0), h, t);
    const double upper = contact_area_2d(h * h, 0.5 * y0 * y0, h * h - 0.5 * y0 * y0, h, t);
    EXPECT_NEAR(lower + upper, h * t, 1e-15);
  }
  // Interface through a node: half the node's domain on each side gives A_c = h t.
  EXPECT_NEAR(contact_area_2d(h * h, 0.5 * h * h, 0.5 * h * h, h, t), h * t, 1e-18);
  EXPECT_NEAR(contact_area_3d(h * h * h, 0.5 * h * h * h, 0.5 * h * h * h, h), h * h, 1e-18);
  EXPECT_EQ(contact_area_2d(h * h, 0.0, h * h, h, t), 0.0);
}

namespace {

/// Ω_j and g_j ([NBS18] eq. (5)-(6)) of node (0, 0) with bilinear hats of spacing h for the field
/// occupying the rectangle [x0, x1] × [y0, y1], by the midpoint rule on n × n tiles per cell (the
/// exact Σ S_ip V_p, Σ G_ip V_p of a CPDI/GIMP tiling in the limit).
struct FieldIntegrals {
  double volume = 0.0;
  Vec<2> gradient = Vec<2>::Zero();
};
FieldIntegrals integrate_field(double h, double x0, double x1, double y0, double y1, int n) {
  FieldIntegrals out;
  const double s = h / n;
  for (double x = std::max(x0, -h) + 0.5 * s; x < std::min(x1, h); x += s)
    for (double y = std::max(y0, -h) + 0.5 * s; y < std::min(y1, h); y += s) {
      const double wx = 1.0 - std::abs(x) / h, wy = 1.0 - std::abs(y) / h;
      out.volume += wx * wy * s * s;
      out.gradient +=
          Vec<2>(-std::copysign(1.0, x) / h * wy, -std::copysign(1.0, y) / h * wx) * s * s;
    }
  return out;
}

}  // namespace

TEST(ContactExchange, AreaFromDomainGradientsIsExactWhereTheInterfaceEnds) {
  const double h = 1.0, t = 1.0;
  const Vec<2> n(0.0, 1.0);  // a below, b above
  // Straight interface at y₀ = 0.3 h across the whole support: hat-weighted length h − y₀;
  // eq. (11) and the gradient form agree.
  {
    const auto a = integrate_field(h, -2, 2, -2, 0.3, 400),
               b = integrate_field(h, -2, 2, 0.3, 2, 400);
    const double exact = 0.7;
    EXPECT_NEAR(contact_area_2d(a.volume + b.volume, a.volume, b.volume, h, t), exact, 1e-4);
    EXPECT_NEAR(contact_area_from_gradients<2>(a.gradient, b.gradient, n), exact, 1e-4);
  }
  // Interface on the node's grid line, b ending at x = 0.25 h (the edge of a block): the covered
  // hat-weighted length is ∫_{−h}^{0.25h} (1 − |x|/h) dx = 0.5 + 0.25 − 0.25²/2 = 0.71875 h.
  // Eq. 11 over-estimates it; the gradient form is exact.
  {
    const auto a = integrate_field(h, -2, 2, -2, 0.0, 400),
               b = integrate_field(h, -2, 0.25, 0.0, 2, 400);
    const double exact = 0.71875, f = exact / h;
    EXPECT_NEAR(contact_area_from_gradients<2>(a.gradient, b.gradient, n), exact, 1e-4);
    const double eq11 = contact_area_2d(a.volume + b.volume, a.volume, b.volume, h, t);
    EXPECT_NEAR(eq11, exact * std::sqrt((1.0 + f) / (2.0 * f)), 1e-4);
    EXPECT_GT(eq11, 1.05 * exact);
  }
}

// Lumped-slip work: the friction impulse on the slip of the lumped velocities l = v − Δt f/m,
// here the trial velocities less a force increment on a. Node of two_field_node(2.0): s = μ N* =
// 0.36 N s along t̂ = +x. Field a carries a force that added 0.5 m/s in +x this step, so its
// lumped velocity is 0.5 m/s slower in x than its trial one and the lumped slip is 2.5 m/s:
// W = 0.36 × 2.5 = 0.9 J. The same node with a light field a (m = 0.02 kg) whose force pushed it
// 50 m/s against the slip: the trial slip shrinks, but the lumped slip and W stay what the
// material brought.
TEST(ContactExchange, LumpedSlipWorkIsTheImpulseOnTheLumpedSlip) {
  const CoulombFriction law{0.3};
  ContactNode<2> node = two_field_node(2.0);
  node.force_a = Vec<2>(0.5 * node.mass_a / dt, 0.0);
  const auto ex = run(node, law, FrictionWorkOrder::lumped_slip);
  ASSERT_TRUE(ex.sliding);
  EXPECT_NEAR(ex.momentum_change_a.x(), 0.36, 1e-12);
  EXPECT_NEAR(ex.friction_work, 0.36 * 2.5, 1e-12);

  ContactNode<2> light = two_field_node(60.0);
  light.mass_a = 0.02;
  light.velocity_a.x() += 50.0;  // trial slip 10 m/s; lumped slip 60 m/s
  light.force_a = Vec<2>(50.0 * light.mass_a / dt, 0.0);
  const auto light_ex = run(light, law, FrictionWorkOrder::lumped_slip);
  ASSERT_TRUE(light_ex.sliding);
  const double reduced = light.mass_a * light.mass_b / (light.mass_a + light.mass_b);
  const double s = 0.3 * reduced * 1.0;  // μ m_red × approach speed 1 m/s
  EXPECT_NEAR(light_ex.friction_work, s * 60.0, 1e-12 * s * 60.0);
  // A slip the force reversed within the step books nothing.
  ContactNode<2> reversed = two_field_node(2.0);
  reversed.force_a = Vec<2>(-3.0 * reversed.mass_a / dt, 0.0);  // lumped slip −1 m/s
  EXPECT_EQ(run(reversed, law, FrictionWorkOrder::lumped_slip).friction_work, 0.0);
}
