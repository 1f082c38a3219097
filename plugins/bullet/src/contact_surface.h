// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The surface that touches rigid bodies: each vertex a weighted sum of lattice nodes.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "cubespring/embedding.h"
#include "cubespring/model.h"

namespace cubespring::bullet {

struct ContactSurface {
  std::vector<int> offset;  ///< vertex v: entries offset[v] .. offset[v+1]-1
  std::vector<int> node;    ///< distinct within a vertex's entries
  std::vector<double> weight;
  Eigen::Matrix3Xi triangles;  ///< counter-clockwise seen from outside
};

/// The boundary faces of the lattice (faces without a cell on their other side), two triangles
/// each; vertices are the nodes of those faces, weight 1.
ContactSurface lattice_boundary_surface(const Model& model);

/// The vertices of an embedded visual mesh, each with the 8 trilinear weights of its cell.
ContactSurface embedded_surface(const Model& model, const Embedding& embedding);

}  // namespace cubespring::bullet
