// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#pragma once

#include <vector>

#include <Eigen/Core>

#include "cubespring/triangle_mesh.h"

/// Units are SI throughout the API: metres, kilograms, seconds, newtons, pascals.
namespace cubespring {

/// A closed surface after cells of a lattice were taken out of the solid it bounds (cutting,
/// cell_removal.h; docs/cutting.md).
struct CutSurface {
  /// The surface's triangles outside the removed cells as they were; those across the removed
  /// cells' faces clipped there; and the cap: each face between a removed cell and one that is
  /// not, where it lies inside the solid, facing into the removed cell. Closed and
  /// consistently oriented when the input is, so the cut shows its inside.
  TriangleMesh mesh;
  /// Which input vertex each vertex is (its position unchanged), or -1: made by the cut. Input
  /// vertices come first, in their order; those no kept triangle uses are left out.
  std::vector<int> vertex_source;
  int cap_triangles = 0;  ///< the last ones of the mesh
};

/// Cuts `surface` (rest positions [m], closed, counter-clockwise seen from outside) by the cells
/// `removed` (grid indices) of the grid with node (0, 0, 0) at `origin` [m] and cells of
/// `cell_size` [m]. The grid's planes are moved by a millionth of a cell, so that a surface built
/// on them (a box on the lattice's faces) is cut in general position. A cavity's wall that a cut
/// opens is not capped where it crosses a removed cell's face (its hole is covered instead).
CutSurface cut_surface(const TriangleMesh& surface, const Eigen::Vector3d& origin, const Eigen::Vector3d& cell_size,
                       const std::vector<Eigen::Vector3i>& removed);

}  // namespace cubespring
