// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Passes of forces.cpp shared with the stiffness assembly.
#pragma once

#include <Eigen/Core>

#include "cubespring/forces.h"

namespace cubespring {

/// Fills ws.spring_length, ws.cell_tension and ws.spring_tension (no damping) at positions x.
void measure_tensions(const Model& model, const Eigen::Matrix3Xd& x, ForceWorkspace& ws);

}  // namespace cubespring
