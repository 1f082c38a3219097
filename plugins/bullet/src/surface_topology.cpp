// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "surface_topology.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <tuple>

#include <Eigen/Geometry>

namespace cubespring::bullet {
namespace {

// Triangles that share a vertex, joined (union-find with path halving).
std::vector<int> connected_parts(const Eigen::Matrix3Xi& triangles, int num_vertices) {
  std::vector<int> parent(static_cast<std::size_t>(num_vertices));
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&parent](int v) {
    while (parent[static_cast<std::size_t>(v)] != v) {
      parent[static_cast<std::size_t>(v)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(v)])];
      v = parent[static_cast<std::size_t>(v)];
    }
    return v;
  };
  for (Eigen::Index t = 0; t < triangles.cols(); ++t) {
    for (int k = 1; k < 3; ++k) parent[static_cast<std::size_t>(root(triangles(k, t)))] = root(triangles(0, t));
  }
  std::vector<int> part(static_cast<std::size_t>(triangles.cols()));
  for (Eigen::Index t = 0; t < triangles.cols(); ++t) part[static_cast<std::size_t>(t)] = root(triangles(0, t));
  return part;
}

// Whether a ray from `origin` along `direction` crosses triangle (a, b, c) ahead of its origin.
bool ray_crosses(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, const Eigen::Vector3d& a,
                 const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d e1 = b - a, e2 = c - a;
  const Eigen::Vector3d p = direction.cross(e2);
  const double determinant = e1.dot(p);
  if (determinant == 0.0) return false;
  const Eigen::Vector3d s = origin - a;
  const double u = s.dot(p) / determinant;
  if (u < 0.0 || u > 1.0) return false;
  const Eigen::Vector3d q = s.cross(e1);
  const double v = direction.dot(q) / determinant;
  if (v < 0.0 || u + v > 1.0) return false;
  return e2.dot(q) / determinant > 0.0;
}

}  // namespace

SurfaceTopology surface_topology(const Eigen::Matrix3Xd& rest_positions, const Eigen::Matrix3Xi& triangles) {
  const auto num_triangles = triangles.cols();
  const auto num_vertices = static_cast<int>(rest_positions.cols());
  SurfaceTopology topology;

  // edges: (upper vertex, triangle, corner) under their lower vertex, each vertex's sorted, so
  // that a shared edge's two entries are next to each other (a counting sort by the lower vertex:
  // a cut body finds its topology again at every cut)
  std::vector<int> lower_offset(static_cast<std::size_t>(num_vertices) + 1, 0);
  const auto lower = [&](Eigen::Index t, int k) { return std::min(triangles(k, t), triangles((k + 1) % 3, t)); };
  const auto upper = [&](Eigen::Index t, int k) { return std::max(triangles(k, t), triangles((k + 1) % 3, t)); };
  for (Eigen::Index t = 0; t < num_triangles; ++t) {
    for (int k = 0; k < 3; ++k) ++lower_offset[static_cast<std::size_t>(lower(t, k)) + 1];
  }
  std::partial_sum(lower_offset.begin(), lower_offset.end(), lower_offset.begin());
  std::vector<std::tuple<int, int, int>> edges(static_cast<std::size_t>(3 * num_triangles));
  {
    std::vector<int> fill(lower_offset.begin(), lower_offset.end() - 1);
    for (Eigen::Index t = 0; t < num_triangles; ++t) {
      for (int k = 0; k < 3; ++k) {
        edges[static_cast<std::size_t>(fill[static_cast<std::size_t>(lower(t, k))]++)] = {upper(t, k),
                                                                                          static_cast<int>(t), k};
      }
    }
  }
  topology.neighbour.setConstant(3, num_triangles, -1);
  for (std::size_t v = 0; v < static_cast<std::size_t>(num_vertices); ++v) {
    const auto first = edges.begin() + lower_offset[v], last = edges.begin() + lower_offset[v + 1];
    std::sort(first, last);
    for (auto i = first; i != last;) {
      auto end = i;
      while (end != last && std::get<0>(*end) == std::get<0>(*i)) ++end;
      if (end - i == 2) {
        const auto [upper_a, ta, ka] = *i;
        const auto [upper_b, tb, kb] = *(i + 1);
        topology.neighbour(ka, ta) = tb;
        topology.neighbour(kb, tb) = ta;
      }
      i = end;
    }
  }

  topology.vertex_offset.assign(static_cast<std::size_t>(num_vertices) + 1, 0);
  for (Eigen::Index t = 0; t < num_triangles; ++t) {
    for (int k = 0; k < 3; ++k) ++topology.vertex_offset[static_cast<std::size_t>(triangles(k, t)) + 1];
  }
  std::partial_sum(topology.vertex_offset.begin(), topology.vertex_offset.end(), topology.vertex_offset.begin());
  topology.vertex_triangle.resize(static_cast<std::size_t>(3 * num_triangles));
  std::vector<int> fill(topology.vertex_offset.begin(), topology.vertex_offset.end() - 1);
  for (Eigen::Index t = 0; t < num_triangles; ++t) {
    for (int k = 0; k < 3; ++k) {
      topology.vertex_triangle[static_cast<std::size_t>(fill[static_cast<std::size_t>(triangles(k, t))]++)] =
          static_cast<int>(t);
    }
  }

  // a part lies inside another when a ray from one of its triangles' centroids crosses the
  // other parts an odd number of times (the direction is oblique so that it rarely grazes an
  // edge of an axis-aligned surface, such as the lattice's own)
  const std::vector<int> part = connected_parts(triangles, num_vertices);
  topology.outer.assign(static_cast<std::size_t>(num_triangles), 1);
  const Eigen::Vector3d direction = Eigen::Vector3d(0.5773, 0.5812, 0.5736).normalized();
  std::vector<int> parts = part;
  std::sort(parts.begin(), parts.end());
  parts.erase(std::unique(parts.begin(), parts.end()), parts.end());
  if (parts.size() < 2) return topology;
  for (const int p : parts) {
    const auto first = static_cast<Eigen::Index>(std::find(part.begin(), part.end(), p) - part.begin());
    const Eigen::Vector3d origin = (rest_positions.col(triangles(0, first)) + rest_positions.col(triangles(1, first)) +
                                    rest_positions.col(triangles(2, first))) /
                                   3.0;
    int crossings = 0;
    for (Eigen::Index t = 0; t < num_triangles; ++t) {
      if (part[static_cast<std::size_t>(t)] == p) continue;
      crossings += ray_crosses(origin, direction, rest_positions.col(triangles(0, t)),
                               rest_positions.col(triangles(1, t)), rest_positions.col(triangles(2, t)));
    }
    if (crossings % 2 == 0) continue;
    for (Eigen::Index t = 0; t < num_triangles; ++t) {
      if (part[static_cast<std::size_t>(t)] == p) topology.outer[static_cast<std::size_t>(t)] = 0;
    }
  }
  return topology;
}

Eigen::Vector3d vertex_normal(const SurfaceTopology& topology, const Eigen::Matrix3Xd& positions,
                              const Eigen::Matrix3Xi& triangles, int v) {
  // the triangles in ascending order, as vertex_normals() visits them
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int k = topology.vertex_offset[static_cast<std::size_t>(v)];
       k < topology.vertex_offset[static_cast<std::size_t>(v) + 1]; ++k) {
    const int t = topology.vertex_triangle[static_cast<std::size_t>(k)];
    const Eigen::Vector3d a = positions.col(triangles(0, t));
    sum += (positions.col(triangles(1, t)) - a).cross(positions.col(triangles(2, t)) - a);
  }
  const double length = sum.norm();
  if (length > 0.0) sum /= length;
  return sum;
}

}  // namespace cubespring::bullet
