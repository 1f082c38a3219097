// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The kick and drift of the explicit integrators, written once: the last terms of a node's force
// and one coordinate's kick-drift. The spring lists' finish (forces.cpp), its speed check after
// a crushed cell's recovery and the grid's vectorised sweep (forces/grid/grid_kick.cpp) all call
// these, so they agree to the bit (the build turns off contraction into fused multiply-adds).
#pragma once

#include "cubespring/constraints.h"
#include "cubespring/state.h"

namespace cubespring {

/// One kick-drift of every node, v' = v + kick M^-1 f, x' = x + drift v', from `from` into `to`
/// (a different State): kick and drift [s]. The nodes that `driven` (constraints of this model)
/// drives then reach their target instead, from their position in drive_start (null: `from`)
/// over drive_step [s] (0: `drift`; drive_nodes.h).
struct KickDrift {
  double kick = 0.0;
  double drift = 0.0;
  const State* from = nullptr;
  State* to = nullptr;
  const Constraints* driven = nullptr;
  const State* drive_start = nullptr;
  double drive_step = 0.0;

  const State& start_of_drive() const { return drive_start != nullptr ? *drive_start : *from; }
  double step_of_drive() const { return drive_step > 0.0 ? drive_step : drift; }
};

/// The terms a node's force gets after its springs and cells, for one coordinate: less its mass
/// damping (`damping` [kg/s] times the damped `velocity` [m/s]) when `damped`, plus its weight
/// (`mass` [kg] times `gravity` [m/s^2], added even when zero so that the grid's sweep needs no
/// branch), plus its nodal load `nodal` [N] when `loaded`. `spring` [N] is the rest of the force.
/// A caller whose flags are constants reads no array it does not need (pass 0 for it).
[[gnu::always_inline]] inline double with_node_loads(double spring, bool damped, double damping, double velocity,
                                                     double mass, double gravity, bool loaded, double nodal) {
  double force = spring;
  if (damped) force -= damping * velocity;
  force += mass * gravity;
  if (loaded) force += nodal;
  return force;
}

/// One coordinate after a kick and drift.
struct KickedCoordinate {
  double velocity;  ///< v' = v + rate f [m/s]
  double position;  ///< x' = x + drift v' [m]
};

/// The kick-drift of one coordinate of a node: `rate` is the kick over the node's mass [s/kg],
/// `drift` [s], `force` [N].
[[gnu::always_inline]] inline KickedCoordinate kick_and_drift(double velocity, double position, double rate,
                                                              double drift, double force) {
  const double kicked = velocity + rate * force;
  return {kicked, position + drift * kicked};
}

}  // namespace cubespring
