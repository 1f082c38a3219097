// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "voxelize/winding_number.h"

#include <cmath>

#include <Eigen/Geometry>

namespace cubespring::voxelize_detail {

double winding_number(const Eigen::Matrix3Xd& vertices, const Eigen::Matrix3Xi& triangles,
                      const Eigen::Vector3d& point) {
  // the solid angle of each triangle by Van Oosterom and Strackee (1983):
  // tan(omega / 2) = a . (b x c) / (|a||b||c| + (a.b)|c| + (b.c)|a| + (c.a)|b|)
  double total = 0.0;
  for (Eigen::Index t = 0; t < triangles.cols(); ++t) {
    const Eigen::Vector3d a = vertices.col(triangles(0, t)) - point;
    const Eigen::Vector3d b = vertices.col(triangles(1, t)) - point;
    const Eigen::Vector3d c = vertices.col(triangles(2, t)) - point;
    const double la = a.norm();
    const double lb = b.norm();
    const double lc = c.norm();
    const double numerator = a.dot(b.cross(c));
    const double denominator = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
    total += 2.0 * std::atan2(numerator, denominator);
  }
  return total / (4.0 * M_PI);
}

}  // namespace cubespring::voxelize_detail
