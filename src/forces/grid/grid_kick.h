// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The kick of compute_forces_and_kick (forces.cpp) for nodes whose spring forces the grid passes
// left in their arrays, as one vectorised sweep instead of a call per node.
#pragma once

#include <Eigen/Core>

#include "cubespring/forces.h"
#include "cubespring/model.h"
#include "cubespring/state.h"
#include "forces/force_passes.h"

namespace cubespring {

/// What the kick needs besides the spring forces: the loads and mass damping at `state`, and the
/// kick-drift from kick.from into kick.to, a State other than `state` and kick.from (the sweep
/// reads the one while it writes the other).
struct GridKick {
  const Model& model;
  const State& state;
  const Loads& loads;
  bool mass_damping;
  KickDrift kick;
};

/// Nodes [begin, end), whose spring forces [N] are at spring_force[axis][point_of_node[n]]: each
/// force gets its mass damping, gravity and nodal load (with_node_loads, the spring lists' terms
/// too) into `forces`; then v' = v0 + (kick / m) f and x' = x0 + drift v' into kick.to
/// (kick_and_drift); then the driven nodes among them are driven (KickDrift; kick_drift.h).
/// Returns the kick's largest squared speed [m^2/s^2], NaN if a speed or a new position of the
/// kick (an omp simd reduction: a max, and a sum of (a - a) that is +0 or NaN in any order) or a
/// driven velocity is not finite.
double kick_grid_nodes(const GridKick& kick, const int* point_of_node, const double* const spring_force[3], int begin,
                       int end, Eigen::Matrix3Xd& forces);

}  // namespace cubespring
