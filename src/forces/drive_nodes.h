// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Driven nodes (constraints.h) reach their target at the end of a step with the velocity that
// gets them there.
#pragma once

#include <cmath>
#include <cstdint>

#include "cubespring/constraints.h"
#include "cubespring/state.h"

namespace cubespring {

/// Node n, if `constraints` drive it: end.x = target, end.v = (target - start.x) / dt [s], for
/// each driven component. Returns false if a velocity is not finite (a far target in a tiny step).
inline bool drive_node(const Constraints& constraints, double dt, const State& start, State& end, int n) {
  const std::uint8_t axes = constraints.driven_flags()[n];
  if (axes == 0) return true;
  const Eigen::Vector3d target = constraints.target(n);
  if (axes == Constraints::kAllAxes) {
    end.positions.col(n) = target;
    end.velocities.col(n) = (target - start.positions.col(n)) / dt;
    return end.velocities.col(n).allFinite();
  }
  bool finite = true;
  for (int a = 0; a < 3; ++a) {
    if (((axes >> a) & 1) == 0) continue;
    end.positions(a, n) = target[a];
    end.velocities(a, n) = (target[a] - start.positions(a, n)) / dt;
    finite = finite && std::isfinite(end.velocities(a, n));
  }
  return finite;
}

/// drive_node() for the nodes [begin, end_node), skipping free nodes a word of flags at a time.
/// Returns false if a driven velocity is not finite.
bool drive_nodes(const Constraints& constraints, double dt, const State& start, State& end, int begin, int end_node);

}  // namespace cubespring
