// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "cubespring/strain.h"

#include <cmath>
#include <cstddef>

#include "model/cell_geometry.h"

namespace cubespring {

Eigen::VectorXd cell_equivalent_strains(const Model& model, const Eigen::Matrix3Xd& positions) {
  Eigen::VectorXd strains(model.num_cells());
  for (int cell = 0; cell < model.num_cells(); ++cell) {
    const CellFrame frame = cell_frame(model, positions, cell);
    Eigen::Matrix3d deformation_gradient;
    for (int axis = 0; axis < 3; ++axis) deformation_gradient.col(axis) = frame.edge[axis] / model.cell_size[axis];
    // Green-Lagrange rather than the small strain: a rotated cell must read as unstrained
    const Eigen::Matrix3d green =
        0.5 * (deformation_gradient.transpose() * deformation_gradient - Eigen::Matrix3d::Identity());
    const Eigen::Matrix3d deviator = green - green.trace() / 3.0 * Eigen::Matrix3d::Identity();
    strains[cell] = std::sqrt(2.0 / 3.0 * deviator.squaredNorm());
  }
  return strains;
}

Eigen::VectorXd node_means_of_cells(const Model& model, const Eigen::VectorXd& cell_values) {
  Eigen::VectorXd sums = Eigen::VectorXd::Zero(model.num_nodes());
  Eigen::VectorXd counts = Eigen::VectorXd::Zero(model.num_nodes());
  for (int cell = 0; cell < model.num_cells(); ++cell) {
    for (const int node : model.cell_nodes[static_cast<std::size_t>(cell)]) {
      sums[node] += cell_values[cell];
      counts[node] += 1.0;
    }
  }
  // every node belongs to a cell, so no count is zero
  return sums.cwiseQuotient(counts);
}

double trilinear_cell_volume(const Model& model, const Eigen::Matrix3Xd& positions, int cell) {
  const auto& corners = model.cell_nodes[static_cast<std::size_t>(cell)];
  // the Gauss points of [-1, 1] at -+1/sqrt(3), mapped to the cell's local [0, 1]
  const double gauss[2] = {0.5 - 0.5 / std::sqrt(3.0), 0.5 + 0.5 / std::sqrt(3.0)};
  double volume = 0.0;
  for (int point = 0; point < 8; ++point) {
    const Eigen::Vector3d at(gauss[point & 1], gauss[(point >> 1) & 1], gauss[(point >> 2) & 1]);
    Eigen::Matrix3d jacobian = Eigen::Matrix3d::Zero();  // dx/dt, t the local coordinates in [0, 1]^3
    for (int corner = 0; corner < kCornersPerCell; ++corner) {
      const Eigen::Vector3d x = positions.col(corners[static_cast<std::size_t>(corner)]);
      for (int axis = 0; axis < 3; ++axis) {
        // d/dt_axis of the trilinear weight of this corner
        double weight = corner_side(corner, axis);
        for (int other = 0; other < 3; ++other) {
          if (other == axis) continue;
          weight *= ((corner >> other) & 1) ? at[other] : 1.0 - at[other];
        }
        jacobian.col(axis) += weight * x;
      }
    }
    volume += jacobian.determinant() / 8.0;  // each Gauss point weighs 1/8 of the unit cube
  }
  return volume;
}

double body_volume(const Model& model, const Eigen::Matrix3Xd& positions) {
  double volume = 0.0;
  for (int cell = 0; cell < model.num_cells(); ++cell) volume += trilinear_cell_volume(model, positions, cell);
  return volume;
}

}  // namespace cubespring
