// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Mean edge vectors of a cell and the signed volume they span (docs/model-baudet2007.md section 5).
#pragma once

#include <array>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "cubespring/model.h"

namespace cubespring {

/// Grid offset of corner c from the cell's corner 0 (model.h: bit a of c is the offset along a).
inline Eigen::Vector3i corner_offset(int corner) { return {corner & 1, (corner >> 1) & 1, (corner >> 2) & 1}; }

/// side(corner, axis) = +1 when the corner is on the + side of the cell along that axis, else -1.
inline double corner_side(int corner, int axis) { return (corner >> axis) & 1 ? 1.0 : -1.0; }

/// [v]x, the matrix with [v]x w = v x w (the curvature of a cell's volume, sections 5 of
/// docs/model-baudet2007.md and 4 of docs/model-neo-hookean.md).
inline Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

/// The three mean edge vectors of a cell: edge[a] = 1/4 sum over the a-edges of (x_+ - x_-).
struct CellFrame {
  std::array<Eigen::Vector3d, 3> edge;

  double volume() const { return edge[0].dot(edge[1].cross(edge[2])); }

  /// d(volume)/d(x_corner) for each of the 8 corners.
  std::array<Eigen::Vector3d, kCornersPerCell> volume_gradient() const {
    const Eigen::Vector3d yz = edge[1].cross(edge[2]);
    const Eigen::Vector3d zx = edge[2].cross(edge[0]);
    const Eigen::Vector3d xy = edge[0].cross(edge[1]);
    std::array<Eigen::Vector3d, kCornersPerCell> gradient;
    for (int corner = 0; corner < kCornersPerCell; ++corner) {
      gradient[corner] =
          0.25 * (corner_side(corner, 0) * yz + corner_side(corner, 1) * zx + corner_side(corner, 2) * xy);
    }
    return gradient;
  }
};

inline CellFrame cell_frame(const Model& model, const Eigen::Matrix3Xd& x, int cell) {
  CellFrame frame;
  for (int axis = 0; axis < 3; ++axis) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (int corner = 0; corner < kCornersPerCell; ++corner) {
      sum += corner_side(corner, axis) * x.col(model.cell_nodes[cell][corner]);
    }
    frame.edge[axis] = 0.25 * sum;
  }
  return frame;
}

}  // namespace cubespring
