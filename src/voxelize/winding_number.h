// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The generalized winding number (Jacobson, Kavan, Sorkine-Hornung 2013): the solid angle that a
// surface subtends at a point over 4 pi. 1 inside a closed outward surface, 0 outside, and a value
// between where the surface has holes: the fallback where axis rays disagree.
#pragma once

#include <Eigen/Core>

namespace cubespring::voxelize_detail {

/// Winding number of the triangles (3 x count vertex indices) at a point.
double winding_number(const Eigen::Matrix3Xd& vertices, const Eigen::Matrix3Xi& triangles,
                      const Eigen::Vector3d& point);

}  // namespace cubespring::voxelize_detail
