// Rigid walls ([NBS18] §2.12: a field in contact with a wall takes the wall's velocity in the
// normal direction; the friction law limits the tangential change). Node impulses J give each
// wall's reaction force and the wall work Σ J·v_wall. Friction work comes from the same exchange as
// between two fields, with the wall as an infinitely heavy partner.
#include <limits>

#include "fragmpm/mpm/contact_exchange.hpp"
#include "step/nodes_behind_plane.hpp"
#include "step/stages.hpp"

namespace fragmpm::mpm {

namespace {

/// The velocity change of one field at a wall node, with the friction work it does.
template <int D>
Vec<D> wall_change(const StepState<D>& state, const WallSpec<D>& wall, const Vec<D>& wall_velocity,
                   int f, std::size_t i, double dt, double& friction) {
  const double m = state.nodes.mass[f][i];
  const Vec<D>& velocity = state.nodes.velocity[f][i];
  const Vec<D> relative = velocity - wall_velocity;
  switch (wall.kind) {
    case WallKind::fixed:
      return -relative;
    case WallKind::roller:
      return -relative.dot(wall.normal) * wall.normal;
    case WallKind::penalty:  // acts through particle forces (penalty_walls.cpp)
      return Vec<D>::Zero();
    case WallKind::contact:
      break;
  }
  ContactNode<D> pair;
  pair.mass_a = m;
  pair.mass_b = std::numeric_limits<double>::infinity();
  pair.velocity_a = velocity;
  pair.velocity_b = wall_velocity;
  pair.normal = -wall.normal;  // from the material towards the wall
  pair.area = 0.0;
  pair.force_a = state.nodes.force[f][i];
  if (state.thermal) pair.temperature = state.thermal->temperature[f][i];
  const ContactExchange<D> exchange =
      exchange_momentum<D>(pair, wall.friction, dt, state.problem.contact.friction_work_order);
  if (!exchange.in_contact) return Vec<D>::Zero();
  friction = exchange.friction_work;
  return exchange.momentum_change_a / m;
}

}  // namespace

template <int D>
void apply_walls(StepState<D>& state, double dt) {
  const double tolerance = 1e-9 * state.grid.cell_size;
  const int fields = state.fields();
  WallScratch<D>& scratch = state.wall_scratch;
  const std::size_t capacity = state.node_count();
  if (scratch.nodes.capacity() < capacity) {
    scratch.nodes.reserve(capacity + capacity / 4);
    scratch.impulse.reserve(capacity + capacity / 4);
    scratch.work.reserve(capacity + capacity / 4);
    scratch.friction.reserve(capacity + capacity / 4);
  }
  for (std::size_t w = 0; w < state.problem.walls.size(); ++w) {
    const WallSpec<D>& wall = state.problem.walls[w];
    if (wall.kind == WallKind::penalty) continue;  // particle forces, penalty_walls.cpp
    const Vec<D> wall_velocity = wall.velocity.velocity(state.time + dt);
    const Vec<D> wall_shift = wall.velocity.displacement(state.time + dt);
    // A bilateral wall (fixed, roller) holds the nodes it touches: when it moves away from the
    // material it pulls them along instead of letting go, so its plane test keeps the start plane
    // until the wall advances into the material. Without this a driven edge whose wall retracts was
    // released at once and its Poisson pre-stress came free as a kinetic-energy burst. A contact
    // wall is one-sided and always tests its current plane. (Limitation: a bilateral wall that
    // advances and then retracts releases the nodes it took beyond its start plane.)
    const double advance = wall_shift.dot(wall.normal);
    const bool holds = wall.kind != WallKind::contact && advance < 0.0;
    const Vec<D> held_shift = wall_shift - (holds ? advance : 0.0) * wall.normal;
    const Vec<D> wall_point = wall.point + held_shift;
    // A node behind the plane is not material behind it: a node carries mass from particles up to
    // a support's width away, so a moving wall tested on node positions reaches the material up
    // to a cell early, holds it through the node row it has passed and takes the next row at
    // once when its plane crosses the next node line. A platen then knocks a grain ahead of it
    // once per cell of travel (docs/verification.md, "Known shortfalls"). With gap_test the
    // wall also considers the node row in front of its plane and acts on a field where that
    // field's material position is within wall_gap_cells of the plane.
    const bool by_material = wall.gap_test && wall.kind == WallKind::contact;
    const double reach = by_material ? state.grid.cell_size : 0.0;
    const double touching = wall_gap_cells * state.grid.cell_size;
    scratch.nodes.clear();
    for_each_node_behind_plane<D>(state.grid, wall_point, wall.normal, tolerance + reach,
                                  [&](std::int64_t i, const Vec<D>& x) {
                                    if (wall.region.contains(x, held_shift, tolerance))
                                      scratch.nodes.push_back(i);
                                  });
    const std::int64_t count = static_cast<std::int64_t>(scratch.nodes.size());
    scratch.impulse.resize(scratch.nodes.size());
    scratch.work.resize(scratch.nodes.size());
    scratch.friction.resize(scratch.nodes.size());
    // Nodes are independent; the sums are taken serially in node order below, so they do not
    // depend on the thread count.
#pragma omp parallel for schedule(static) if (count > 4096)
    for (std::int64_t k = 0; k < count; ++k) {
      const std::size_t i = static_cast<std::size_t>(scratch.nodes[k]);
      Vec<D> impulse = Vec<D>::Zero();
      double work = 0.0, friction_sum = 0.0;
      for (int f = 0; f < fields; ++f) {
        const double m = state.nodes.mass[f][i];
        if (m <= state.negligible_mass) continue;
        if (by_material &&
            (state.nodes.position[f][i] / m - wall_point).dot(wall.normal) > touching)
          continue;
        double friction = 0.0;
        const Vec<D> change = wall_change(state, wall, wall_velocity, f, i, dt, friction);
        state.nodes.velocity[f][i] += change;
        if (change.squaredNorm() > 0.0) state.nodes.touched[i] |= touched_by_wall;
        impulse += m * change;
        work += m * change.dot(wall_velocity);
        friction_sum += friction;
        if (state.thermal && friction != 0.0) state.thermal->wall_heat[f][i] += friction;
      }
      scratch.impulse[k] = impulse;
      scratch.work[k] = work;
      scratch.friction[k] = friction_sum;
    }
    Vec<D> impulse_sum = Vec<D>::Zero();
    double work = 0.0, friction = 0.0;
    for (std::int64_t k = 0; k < count; ++k) {
      impulse_sum += scratch.impulse[k];
      work += scratch.work[k];
      friction += scratch.friction[k];
    }
    state.row.wall_force[w] = -impulse_sum / dt;  // force of the material on the wall
    state.totals.wall_work += work;
    state.totals.friction_work += friction;
  }
}

template void apply_walls<2>(StepState<2>&, double);
template void apply_walls<3>(StepState<3>&, double);

}  // namespace fragmpm::mpm
