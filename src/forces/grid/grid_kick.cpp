// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "forces/grid/grid_kick.h"

#include <cmath>
#include <limits>

#include "forces/drive_nodes.h"
#include "forces/grid/grid_layout.h"
#include "forces/grid/vector_clones.h"
#include "forces/kick_drift.h"
#include "invariant.h"

namespace cubespring {
namespace {

// The sweep, for bodies with and without mass damping and nodal loads (arrays that may be empty,
// so their reads cannot hide behind a select). kContiguous: the nodes' points are the nodes'
// own numbers shifted by point_of_node[begin] - begin (in a box, for one, every point is a
// node), so the spring forces are plain loads, not gathers through point_of_node.
template <bool kMassDamping, bool kNodal, bool kContiguous>
CUBESPRING_VECTOR_CLONES double kick_nodes(const GridKick& k, const int* __restrict point_of_node,
                                           const double* const spring_force[3], int begin, int end,
                                           double* __restrict forces) {
  const double* __restrict fx = spring_force[0];
  const double* __restrict fy = spring_force[1];
  const double* __restrict fz = spring_force[2];
  const double* __restrict mass = k.model.mass.data();
  const double* __restrict inertia = k.model.inertia().data();
  const double* __restrict mass_damping = k.model.mass_damping.data();
  const double* __restrict damped_velocity = k.state.velocities.data();
  const double* __restrict nodal = k.loads.nodal_forces.data();
  const double* __restrict v0 = k.kick.from->velocities.data();
  const double* __restrict x0 = k.kick.from->positions.data();
  double* __restrict v1 = k.kick.to->velocities.data();
  double* __restrict x1 = k.kick.to->positions.data();
  const double gravity[3] = {k.loads.gravity.x(), k.loads.gravity.y(), k.loads.gravity.z()};
  const double kick = k.kick.kick, drift = k.kick.drift;
  double fastest_sq = 0.0;
  double poison = 0.0;  // a sum of (a - a): 0 while every a is finite, NaN after any is not
  const int shift = begin < end ? point_of_node[begin] - begin : 0;
#pragma omp simd reduction(max : fastest_sq) reduction(+ : poison)
  for (int n = begin; n < end; ++n) {
    const int g = kContiguous ? n + shift : point_of_node[n];
    const double spring[3] = {fx[g], fy[g], fz[g]};
    const double m = mass[n];
    const double rate = kick / inertia[n];
    double speed_sq = 0.0;
#pragma GCC unroll 3
    for (int axis = 0; axis < 3; ++axis) {
      const int i = 3 * n + axis;
      const double f =
          with_node_loads(spring[axis], kMassDamping, kMassDamping ? mass_damping[n] : 0.0,
                          kMassDamping ? damped_velocity[i] : 0.0, m, gravity[axis], kNodal, kNodal ? nodal[i] : 0.0);
      forces[i] = f;
      const KickedCoordinate kicked = kick_and_drift(v0[i], x0[i], rate, drift, f);
      v1[i] = kicked.velocity;
      x1[i] = kicked.position;
      speed_sq += kicked.velocity * kicked.velocity;
      poison += kicked.position - kicked.position;
    }
    poison += speed_sq - speed_sq;
    fastest_sq = fastest_sq > speed_sq ? fastest_sq : speed_sq;
  }
  return std::isnan(poison) ? std::numeric_limits<double>::quiet_NaN() : fastest_sq;
}

// The sweep for this body's kind of nodes and loads.
double kick_nodes_of_kind(const GridKick& kick, const int* point_of_node, const double* const spring_force[3],
                          int begin, int end, Eigen::Matrix3Xd& forces) {
  const bool nodal = kick.loads.nodal_forces.cols() == kick.model.num_nodes();
  double* out = forces.data();
  if (on_consecutive_points(point_of_node, begin, end)) {
    if (kick.mass_damping) {
      return nodal ? kick_nodes<true, true, true>(kick, point_of_node, spring_force, begin, end, out)
                   : kick_nodes<true, false, true>(kick, point_of_node, spring_force, begin, end, out);
    }
    return nodal ? kick_nodes<false, true, true>(kick, point_of_node, spring_force, begin, end, out)
                 : kick_nodes<false, false, true>(kick, point_of_node, spring_force, begin, end, out);
  }
  if (kick.mass_damping) {
    return nodal ? kick_nodes<true, true, false>(kick, point_of_node, spring_force, begin, end, out)
                 : kick_nodes<true, false, false>(kick, point_of_node, spring_force, begin, end, out);
  }
  return nodal ? kick_nodes<false, true, false>(kick, point_of_node, spring_force, begin, end, out)
               : kick_nodes<false, false, false>(kick, point_of_node, spring_force, begin, end, out);
}

}  // namespace

double kick_grid_nodes(const GridKick& kick, const int* point_of_node, const double* const spring_force[3], int begin,
                       int end, Eigen::Matrix3Xd& forces) {
  CUBESPRING_ASSERT(kick.kick.to != kick.kick.from && kick.kick.to != &kick.state);  // read and written apart
  const double fastest_sq = kick_nodes_of_kind(kick, point_of_node, spring_force, begin, end, forces);
  const KickDrift& k = kick.kick;
  if (k.driven != nullptr && !drive_nodes(*k.driven, k.step_of_drive(), k.start_of_drive(), *k.to, begin, end)) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  return fastest_sq;
}

}  // namespace cubespring
