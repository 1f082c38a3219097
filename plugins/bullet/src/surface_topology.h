// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// How a soft body's contact-surface triangles hang together, found once from the rest shape: what
// the signed distance to the surface (surface_distance.h) needs to tell inside from outside.
#pragma once

#include <vector>

#include <Eigen/Core>

namespace cubespring::bullet {

struct SurfaceTopology {
  /// Per triangle t and corner k: the triangle across the edge from corner k to corner k+1 (mod
  /// 3), or -1 where that edge has no other triangle or more than one (an open or non-manifold
  /// edge).
  Eigen::Matrix3Xi neighbour;
  /// The triangles around vertex v: vertex_triangle[vertex_offset[v] .. vertex_offset[v+1]-1].
  std::vector<int> vertex_offset;
  std::vector<int> vertex_triangle;
  /// Per triangle, 1 where it bounds the tissue from the outside: its connected part of the
  /// surface does not lie inside another part (an inclusion's surface, such as a tumour's inside
  /// an organ, does).
  std::vector<char> outer;
};

/// The topology of the triangles over `rest_positions` (one column a vertex; the triangles
/// counter-clockwise seen from outside).
SurfaceTopology surface_topology(const Eigen::Matrix3Xd& rest_positions, const Eigen::Matrix3Xi& triangles);

/// The unit outward normal at vertex `v` of the triangles over `positions`: the area-weighted sum
/// of its triangles' normals, summed as cubespring::vertex_normals() sums them (the same bits),
/// for one vertex; zero for a vertex of no triangle.
Eigen::Vector3d vertex_normal(const SurfaceTopology& topology, const Eigen::Matrix3Xd& positions,
                              const Eigen::Matrix3Xi& triangles, int v);

}  // namespace cubespring::bullet
