// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#pragma once

#include <vector>

#include <Eigen/Core>

#include "cubespring/model.h"

namespace cubespring {

/// The outside of a body's lattice: every cell face that no other cell shares (the faces of
/// cavities included), as two triangles turning counter-clockwise seen from outside the body.
struct LatticeSurface {
  std::vector<int> nodes;      ///< the lattice node behind each surface vertex, each node once
  Eigen::Matrix3Xi triangles;  ///< (3 x m) indices into `nodes`
};

/// The boundary faces of the lattice's cells, in cell order.
LatticeSurface lattice_boundary_surface(const Model& model);

/// The surface's vertex positions (3 x nodes.size()) taken from node positions (3 x num_nodes)
/// [m], e.g. State::positions or Model::rest_positions.
Eigen::Matrix3Xd surface_vertices(const LatticeSurface& surface, const Eigen::Matrix3Xd& node_positions);

}  // namespace cubespring
