// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#pragma once

#include <array>
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
  /// What each vertex is (an input vertex, where an input edge crosses a cut's plane, where a grid
  /// line crosses an input triangle, a grid corner): two cuts of one surface give a point they
  /// both make the same key, so the vertices of one can be matched with the other's.
  std::vector<std::array<long long, 4>> vertex_keys;
};

/// Cuts `surface` (rest positions [m], closed, counter-clockwise seen from outside) by the cells
/// `removed` (grid indices) of the grid with node (0, 0, 0) at `origin` [m] and cells of
/// `cell_size` [m]. The cut's planes are the grid's moved by about a millionth of a cell, unequally
/// along the axes, so that a surface built on the grid's planes (a box on the lattice's faces) is
/// cut in general position. Each part of the surface (MeshPart) is closed and capped on its own (a
/// tumour's surface inside a liver's). Cut a body's surface again from the surface it started with, by every
/// cell removed so far: a cut surface's caps lie on the cut's planes, and cutting them again on the
/// same planes is not in general position. A cavity's wall that a cut opens is not capped where it
/// crosses a removed cell's face (its hole is covered instead).
CutSurface cut_surface(const TriangleMesh& surface, const Eigen::Vector3d& origin, const Eigen::Vector3d& cell_size,
                       const std::vector<Eigen::Vector3i>& removed);

}  // namespace cubespring
