// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "cubespring/result.h"

/// Units are SI throughout the API: metres, kilograms, seconds, newtons, pascals.
namespace cubespring {

/// One named part of a surface mesh (an organ, a tumour inside it, a vessel): triangles
/// first_triangle .. first_triangle + triangle_count - 1 of the mesh.
struct MeshPart {
  std::string name;           ///< the mesh's name in its file ("" when it has none)
  std::string material_name;  ///< the name of its material in the file ("" when none)
  int first_triangle = 0;
  int triangle_count = 0;
};

/// A triangle surface of one or more parts, in metres. This is all that voxelizing needs: a
/// simulator with its own triangles fills it directly; cubespring::mesh fills it from a file.
struct TriangleMesh {
  Eigen::Matrix3Xd vertices;    ///< (3 x num_vertices) [m]
  Eigen::Matrix3Xi triangles;   ///< (3 x num_triangles) vertex indices, counter-clockwise seen
                                ///< from outside (the voxelizer repairs meshes that are not)
  std::vector<MeshPart> parts;  ///< cover all triangles in order; empty means one unnamed part

  int num_vertices() const { return static_cast<int>(vertices.cols()); }
  int num_triangles() const { return static_cast<int>(triangles.cols()); }
};

/// Checks what every later step relies on: finite coordinates, triangle indices that name a
/// vertex, parts that cover the triangles in order. The message names the first fault (the
/// vertex or triangle index and its value); `source` (a file name) prefixes it when not empty.
Status validate(const TriangleMesh& mesh, const std::string& source = "");

/// The parts of a mesh, with one unnamed part covering all triangles when mesh.parts is empty.
std::vector<MeshPart> parts_of(const TriangleMesh& mesh);

/// Joins vertices with identical coordinates (bit for bit) and renumbers the triangles; vertex
/// order follows first appearance. Files often repeat a vertex per face (STL always does).
TriangleMesh join_identical_vertices(const TriangleMesh& mesh);

/// The triangles of one part as a mesh of their own (vertices are shared, not copied out).
TriangleMesh part_mesh(const TriangleMesh& mesh, int part);

}  // namespace cubespring
