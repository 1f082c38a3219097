// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#pragma once

#include <vector>

#include <Eigen/Core>

#include "cubespring/model.h"
#include "cubespring/result.h"
#include "cubespring/triangle_mesh.h"

/// Units are SI throughout the API: metres, kilograms, seconds, newtons, pascals.
namespace cubespring {

/// A visual mesh bound to a lattice: each vertex moves with the 8 nodes of one cell by trilinear
/// interpolation, so any affine motion of the lattice moves the mesh by the same affine map.
struct Embedding {
  std::vector<int> vertex_cell;   ///< cell of each vertex (index into Model::cell_nodes)
  Eigen::Matrix3Xd vertex_local;  ///< (3 x num_vertices) trilinear coordinates (u, v, w) in that
                                  ///< cell: in [0, 1] inside it, outside for a vertex of an empty
                                  ///< cell bound to its nearest occupied cell (extrapolated)
  Eigen::Matrix3Xi triangles;     ///< the visual mesh's triangles, for its normals

  int num_vertices() const { return static_cast<int>(vertex_cell.size()); }
};

/// Binds every vertex of `visual` to the cell that contains it at rest, or to the nearest cell
/// when it lies in an empty one. Fails on an invalid mesh, a model with no cells, or a vertex
/// farther outside the lattice's box than the lattice is long (another unit or place, most likely).
Result<Embedding> embed_mesh(const Model& model, const TriangleMesh& visual);

/// Vertex positions (3 x num_vertices) [m] for node positions (3 x num_nodes) [m], e.g.
/// State::positions after a step.
void embedded_positions(const Model& model, const Embedding& embedding, const Eigen::Matrix3Xd& node_positions,
                        Eigen::Matrix3Xd& vertices);

/// A per-node scalar field (one value per node, e.g. node_means_of_cells of cell strains) at each
/// vertex, by the same trilinear weights as its position.
void embedded_values(const Model& model, const Embedding& embedding, const Eigen::VectorXd& node_values,
                     Eigen::VectorXd& vertex_values);

/// Unit vertex normals: the area-weighted sum of the normals of the triangles around each vertex
/// (counter-clockwise triangles give outward normals); zero for a vertex of no triangle.
void vertex_normals(const Eigen::Matrix3Xd& vertices, const Eigen::Matrix3Xi& triangles, Eigen::Matrix3Xd& normals);

}  // namespace cubespring
