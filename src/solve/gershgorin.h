// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Gershgorin's bound on the explicit step, in parts: the stable step (stable_time_step.cpp) and
// selective mass scaling (mass_scaling.cpp) read the same row sums of one assembled stiffness
// (stiffness_row_sums.cpp).
#pragma once

#include <Eigen/Core>

#include "cubespring/model.h"
#include "cubespring/stiffness.h"

namespace cubespring {

/// The body's stiffness at rest, assembled once (0.3 s for 64x16x16 cells).
SparseMatrix rest_stiffness(const Model& model);
/// Each node's largest sum of |K_ij| over its three rows of `stiffness` [N/m].
Eigen::VectorXd node_row_sums(const SparseMatrix& stiffness);
/// max over nodes of row_sums / inertia [1/s^2]: at least every eigenvalue of M^-1 K.
double gershgorin_bound(const Eigen::VectorXd& row_sums, const Eigen::VectorXd& inertia);
/// The largest stable explicit step [s] for the highest frequency omega [rad/s]: 2 / omega,
/// reduced for the model's stiffness-proportional damping.
double stable_step_for_frequency(const Model& model, double omega);

}  // namespace cubespring
