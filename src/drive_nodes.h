// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Driven nodes (constraints.h) reach their target at the end of a step with the velocity that
// gets them there.
#pragma once

#include <cstdint>

#include "cubespring/constraints.h"
#include "cubespring/state.h"

namespace cubespring {

/// Node n, if `constraints` drive it: end.x = target, end.v = (target - start.x) / dt [s].
/// Returns false if that velocity is not finite (a far target in a tiny step).
inline bool drive_node(const Constraints& constraints, double dt, const State& start, State& end, int n) {
  if (constraints.driven_flags()[n] == 0) return true;
  end.positions.col(n) = constraints.target(n);
  end.velocities.col(n) = (constraints.target(n) - start.positions.col(n)) / dt;
  return end.velocities.col(n).allFinite();
}

/// drive_node() for the nodes [begin, end_node), skipping free nodes a word of flags at a time.
/// Returns false if a driven velocity is not finite.
bool drive_nodes(const Constraints& constraints, double dt, const State& start, State& end, int begin,
                 int end_node);

}  // namespace cubespring
