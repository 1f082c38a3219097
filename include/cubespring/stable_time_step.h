// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#pragma once

#include "cubespring/model.h"

/// Units are SI throughout the API: metres, kilograms, seconds, newtons, pascals.
namespace cubespring {

/// How the body's highest natural frequency omega_max (the square root of the largest eigenvalue
/// of M^-1 K, the linearised body at rest) is found for the explicit stability limit.
enum class FrequencyBound {
  /// Gershgorin's bound, max over rows of (1/m) sum |K_ij|: rigorous and cheap, but 1.3-1.5 times
  /// above omega_max on box lattices, so the step it allows is that much too short.
  kGershgorin,
  /// omega_max itself, by Lanczos iteration on M^-1/2 K M^-1/2 (its largest Ritz value plus that
  /// value's residual, capped by Gershgorin's bound): within 0.1% of the true value. The step it
  /// allows has no margin for a body deformed stiffer than at rest: multiply by a safety factor.
  /// It does not know what contact and anchors add: the Bullet plugin keeps Gershgorin, since at
  /// 0.9 of this step a block anchored to a light dynamic body blew up in its tests.
  kLanczos,
};

/// The body's highest natural frequency omega_max [rad/s], found as `bound` says. Both bounds
/// assemble the body's stiffness (0.3 s for 64x16x16 cells, 5 s and 1.2 GB for 64^3): find it
/// once per body. Throws std::length_error for a body too large for the matrix's int indices
/// (StiffnessAssembler).
double max_frequency(const Model& model, FrequencyBound bound = FrequencyBound::kGershgorin);

/// The largest time step [s] at which the explicit integrators stay stable for this body at rest:
/// 2 / omega_max, reduced for stiffness-proportional damping. Fixed nodes are ignored (they only
/// lower omega_max), so the limit holds for any constraints.
double max_stable_time_step(const Model& model, FrequencyBound bound = FrequencyBound::kGershgorin);

}  // namespace cubespring
