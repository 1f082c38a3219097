// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Passes of forces.cpp shared with the stiffness assembly and the explicit integrators (the
// kick-drift itself: kick_drift.h).
#pragma once

#include <cmath>

#include <Eigen/Core>

#include "cubespring/constraints.h"
#include "cubespring/forces.h"
#include "forces/kick_drift.h"

namespace cubespring {

/// Springs shorter than this fraction of their rest length have no direction and give no force
/// (the spring lists and the grid passes alike).
inline constexpr double kDegenerateLengthFraction = 1e-12;

/// Fills ws.spring_length, ws.cell_tension and ws.spring_tension (no damping) at positions x.
void measure_tensions(const Model& model, const Eigen::Matrix3Xd& x, ForceWorkspace& ws);

/// compute_forces() followed by the kick-drift, each node moved as soon as its force is complete
/// (while it is still in cache). Returns the largest squared speed [m^2/s^2] of the kick
/// (driven nodes' before they are driven), NaN or infinity if a velocity or a new position of
/// the kick or a driven velocity is not finite. The states and forces are the same as from
/// compute_forces() and separate sweeps.
double compute_forces_and_kick(const Model& model, const State& state, const Loads& loads, const ForceOptions& options,
                               ForceWorkspace& workspace, Eigen::Matrix3Xd& forces, const KickDrift& kick);

/// The speed bookkeeping of the kick-drift: the larger squared speed, NaN once any is NaN.
inline double faster(double speed_sq, double fastest_sq) {
  return speed_sq > fastest_sq || std::isnan(speed_sq) ? speed_sq : fastest_sq;
}

}  // namespace cubespring
