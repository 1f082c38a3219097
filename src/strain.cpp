// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "cubespring/strain.h"

#include <cmath>
#include <cstddef>

#include "cell_geometry.h"

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

}  // namespace cubespring
