// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#pragma once

#include <vector>

#include "cubespring/triangle_mesh.h"

/// Units are SI throughout the API: metres, kilograms, seconds, newtons, pascals.
namespace cubespring {

/// What was wrong with a surface, counted before repair (docs/voxelize.md, section 2).
struct SurfaceProblems {
  int open_edges = 0;            ///< edges used by one triangle: holes in the surface
  int non_manifold_edges = 0;    ///< edges used by three triangles or more
  int flipped_triangles = 0;     ///< triangles turned to agree with their neighbours (inconsistent
                                 ///< orientation), or whole parts turned inside-out
  int degenerate_triangles = 0;  ///< zero area, or two corners on one vertex: dropped
  int duplicate_triangles = 0;   ///< same three vertices as an earlier triangle of the solid: dropped
  int components = 0;            ///< edge-connected pieces of surface, over all parts

  bool clean() const {
    return open_edges == 0 && non_manifold_edges == 0 && flipped_triangles == 0 && degenerate_triangles == 0 &&
           duplicate_triangles == 0;
  }
};

/// A surface ready for an inside test: every solid consistently oriented with outward normals.
/// A solid is a part, or several parts whose surfaces share edges (a closed tool split into
/// pieces by material): only together do they enclose a volume.
struct RepairedSurface {
  TriangleMesh mesh;  ///< same vertices; triangles dropped or turned; parts kept
  SurfaceProblems problems;
  std::vector<int> part_solid;                ///< solid of each part
  std::vector<std::vector<int>> solid_parts;  ///< parts of each solid, in file order
  std::vector<double> solid_volume;           ///< enclosed volume of each solid [m^3]
};

/// Groups parts into solids, drops degenerate and duplicated triangles, then orients each solid:
/// every edge-connected piece is made consistent across its two-triangle edges, keeping the
/// orientation most of its area already had, and a solid whose enclosed volume comes out negative
/// is turned inside-out (a file written with clockwise triangles). A hollow solid keeps its inner
/// surface facing the cavity.
/// The mesh must pass validate().
RepairedSurface repair_surface(const TriangleMesh& mesh);

/// Enclosed volume of the triangles first .. first + count - 1 by the divergence theorem [m^3]:
/// positive for a closed surface with outward normals.
double signed_volume(const TriangleMesh& mesh, int first, int count);

}  // namespace cubespring
