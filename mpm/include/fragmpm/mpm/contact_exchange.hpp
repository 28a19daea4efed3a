#pragma once
// Node-level frictional contact between two velocity fields a and b of one grid node (or a field a
// and a rigid wall b): the momentum-exchange scheme of [NBS18] §2.6-2.10 with any friction law of
// friction_law.hpp. The solver gathers a ContactNode per separable node and applies the returned
// momentum change: p′_a = p_a + Δp′_a, p′_b = p_b − Δp′_a ([NBS18] eq. (18)), so momentum is
// conserved exactly by construction. Nothing here allocates or calls through a virtual table.
#include <limits>

#include "fragmpm/mpm/friction_law.hpp"
#include "fragmpm/mpm/types.hpp"

namespace fragmpm::mpm {

/// Frictional work per step: first order takes the final slip velocity as constant over the step
/// ([NBS18] eq. (27)); second order adds the relative acceleration and stick-to-slip onset within
/// the step ([NBS18] eq. (31)-(36)); lumped slip takes the friction impulse s on the slip w₀ of the
/// lumped velocities, s w₀, friction's part of the step's energy identity in update-stress-last
/// MPM (contact_exchange.cpp). Second order and lumped slip need the nodal forces.
enum class FrictionWorkOrder { first, second, lumped_slip };

/// The two fields at one node after the grid velocity update, before contact.
/// In 2D all extensive quantities (mass, force, area) are per unit thickness.
template <int D>
struct ContactNode {
  double mass_a = 0.0;  ///< m_a [kg]
  double mass_b =
      0.0;  ///< m_b [kg]; +infinity = b is a rigid wall ([NBS18] §2.12: v_cm = v_b, m_red = m_a)
  Vec<D> velocity_a = Vec<D>::Zero();  ///< trial velocity of field a [m/s]
  Vec<D> velocity_b =
      Vec<D>::Zero();  ///< trial velocity of field b (the wall's velocity if rigid) [m/s]
  Vec<D> normal = Vec<D>::Zero();  ///< unit normal pointing from a towards b
  /// Nodal forces of this step (internal + external, before contact; [NBS18] eq. (3)) [N]. Only the
  /// friction work reads them: second order ([NBS18] eq. (29)-(30)), and lumped slip, which takes
  /// the lumped velocity of a field as its trial velocity less Δt f/m; a rigid wall's force is
  /// ignored.
  Vec<D> force_a = Vec<D>::Zero();
  Vec<D> force_b = Vec<D>::Zero();
  double area = 0.0;  ///< contact area A_c ([NBS18] eq. (11)) [m² in 3D, m per unit thickness in
                      ///< 2D]; only adhesion uses it
  double temperature = 0.0;  ///< interface temperature max(θ_a, θ_b) [K] for
                             ///< ThermalSofteningFriction ([XLS21] eq. (15))
  bool gap_closed = true;    ///< result of the optional position test δ_n < 0 ([NBS18] eq. (8));
                             ///< false = surfaces apart
};

/// What contact did at the node.
template <int D>
struct ContactExchange {
  bool in_contact =
      false;  ///< momenta were exchanged (contact, or separating surfaces held by tensile adhesion)
  bool sliding = false;  ///< the friction law limited the tangential exchange
  Vec<D> momentum_change_a =
      Vec<D>::Zero();  ///< Δp′_a ([NBS18] eq. (17)-(18)) [N s]; b receives exactly −Δp′_a
  /// N A_c Δt = −Δp′_a·n [N s]: ≥ 0 in compression; negative only while tensile adhesion
  /// ([NBS18] eq. (25)) holds separating surfaces together.
  double normal_impulse = 0.0;
  double slip_speed =
      0.0;  ///< |Δv′|, tangential relative speed after the exchange ([NBS18] eq. (21)) [m/s]
  double friction_work = 0.0;  ///< energy dissipated by slip during this step [J] ([NBS18] eq.
                               ///< (27) or (34)/(36), or the lumped-slip share)
};

/// Contact momentum exchange at one two-field node ([NBS18] §2.6-2.10).
///
/// Stick impulse Δp_a = m_red Δv, Δv = v_b − v_a ([NBS18] eq. (12), (14)), split into d_n = Δp_a·n
/// and the tangential part d_t t̂ (eq. (15)). Contact when Δv·n < 0 and `gap_closed` (§2.4); then
/// the normal approach is removed entirely and the tangential impulse is min(d_t, S_slide A_c Δt)
/// with the sliding impulse from the friction law (eq. (17), (20), (23), (24), (43); [XLS21] eq.
/// (15)). Separated surfaces are untouched unless an AdhesiveFriction with tensile strength keeps
/// them stuck (eq. (25)). `dt` [s] is the step; it enters only through A_c Δt (adhesion) and the
/// second-order work.
template <int D>
ContactExchange<D> exchange_momentum(const ContactNode<D>& node, const FrictionLaw& law, double dt,
                                     FrictionWorkOrder order);

/// Contact area at a node in 2D ([NBS18] eq. (11)): A_c = t √(2 Ω_i min(Ω_a, Ω_b)) / h⊥.
/// `node_volume` Ω_i is the node's total domain Σ_j Ω_{i,j} (= h² for a node surrounded by
/// material), `volume_a`, `volume_b` the fields' domains Ω_{i,a}, Ω_{i,b} ([NBS18] eq. (5); areas
/// [m²] in 2D), `cell_size` h⊥ [m] (the element side on a square grid), `thickness` t [m]; pass t =
/// 1 for an area per unit thickness [m], consistent with masses per unit thickness. For a straight
/// interface the areas of the nodes on either side sum to t times the node spacing.
double contact_area_2d(double node_volume, double volume_a, double volume_b, double cell_size,
                       double thickness);

/// The 3D form of [NBS18] eq. (11) (t dropped): A_c = √(2 Ω_i min(Ω_a, Ω_b)) / h⊥ with volumes
/// [m³]; [m²].
double contact_area_3d(double node_volume, double volume_a, double volume_b, double cell_size);

/// Contact area at a node from the fields' domain gradients g_j = Σ_p G_ip V_p ([NBS18] eq. (6)):
/// A_c = min(|g_a·n|, |g_b·n|) [m per unit thickness in 2D (multiply by t), m² in 3D].
/// Why: by the divergence theorem g_j = ∫_{Ω_j} ∇S_i dV = ∮_{∂Ω_j} S_i n dS, so g_j·n is the
/// shape-function-weighted measure of field j's boundary facing along n: the interface's tributary
/// area at node i plus any free surface of j with the same orientation, which only adds. The
/// smaller of the two is the interface's. Exact (for GIMP/CPDI weights) for a straight interface at
/// any offset from the node, where eq. (11) is exact too, and also where the interface ends inside
/// the node's support (e.g. under the edge of a sliding block), where eq. (11) over-estimates by
/// √((1+f)/(2f)) for a covered fraction f. Not in the seeds: our alternative to eq. (11).
template <int D>
double contact_area_from_gradients(const Vec<D>& gradient_a, const Vec<D>& gradient_b,
                                   const Vec<D>& normal);

}  // namespace fragmpm::mpm
