// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The damage real-world meshes carry, done on purpose to a clean mesh: holes, flipped and
// duplicated triangles.
#pragma once

#include <algorithm>
#include <map>
#include <random>
#include <set>
#include <vector>

#include "cubespring/triangle_mesh.h"

namespace cubespring::test {

/// Keeps the triangles for which keep(t) is true; parts are shrunk to match.
template <typename Keep>
TriangleMesh filter_triangles(const TriangleMesh& mesh, Keep keep) {
  TriangleMesh out;
  out.vertices = mesh.vertices;
  std::vector<int> kept;
  for (const MeshPart& part : parts_of(mesh)) {
    MeshPart shrunk = part;
    shrunk.first_triangle = static_cast<int>(kept.size());
    for (int t = part.first_triangle; t < part.first_triangle + part.triangle_count; ++t) {
      if (keep(t)) kept.push_back(t);
    }
    shrunk.triangle_count = static_cast<int>(kept.size()) - shrunk.first_triangle;
    out.parts.push_back(shrunk);
  }
  out.triangles.resize(3, static_cast<Eigen::Index>(kept.size()));
  for (std::size_t i = 0; i < kept.size(); ++i)
    out.triangles.col(static_cast<Eigen::Index>(i)) = mesh.triangles.col(kept[i]);
  return out;
}

/// Each triangle split in 4 at its edge midpoints, `times` times (a flat face stays flat).
inline TriangleMesh subdivide(const TriangleMesh& mesh, int times) {
  TriangleMesh out = mesh;
  for (int level = 0; level < times; ++level) {
    std::vector<Eigen::Vector3d> vertices;
    for (int v = 0; v < out.num_vertices(); ++v) vertices.push_back(out.vertices.col(v));
    std::map<std::pair<int, int>, int> midpoint_of;
    const auto midpoint = [&](int a, int b) {
      const std::pair<int, int> key{std::min(a, b), std::max(a, b)};
      const auto found = midpoint_of.find(key);
      if (found != midpoint_of.end()) return found->second;
      vertices.push_back(0.5 * (out.vertices.col(a) + out.vertices.col(b)));
      midpoint_of.emplace(key, static_cast<int>(vertices.size()) - 1);
      return static_cast<int>(vertices.size()) - 1;
    };
    Eigen::Matrix3Xi finer(3, 4 * out.num_triangles());
    for (int t = 0; t < out.num_triangles(); ++t) {
      const int a = out.triangles(0, t), b = out.triangles(1, t), c = out.triangles(2, t);
      const int ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      finer.col(4 * t) << a, ab, ca;
      finer.col(4 * t + 1) << ab, b, bc;
      finer.col(4 * t + 2) << ca, bc, c;
      finer.col(4 * t + 3) << ab, bc, ca;
    }
    out.vertices.resize(3, static_cast<Eigen::Index>(vertices.size()));
    for (std::size_t v = 0; v < vertices.size(); ++v) out.vertices.col(static_cast<Eigen::Index>(v)) = vertices[v];
    out.triangles = finer;
    for (MeshPart& part : out.parts) {
      part.first_triangle *= 4;
      part.triangle_count *= 4;
    }
  }
  return out;
}

/// Removes `fraction` of the triangles, chosen at random (seeded).
inline TriangleMesh remove_triangles(const TriangleMesh& mesh, double fraction, unsigned seed = 11) {
  std::mt19937 rng(seed);
  std::vector<int> order(static_cast<std::size_t>(mesh.num_triangles()));
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  std::shuffle(order.begin(), order.end(), rng);
  const std::set<int> removed(order.begin(), order.begin() + static_cast<long>(fraction * mesh.num_triangles()));
  return filter_triangles(mesh, [&](int t) { return removed.count(t) == 0; });
}

/// Turns each triangle with probability `fraction` (1: all of them).
inline TriangleMesh flip_triangles(const TriangleMesh& mesh, double fraction, unsigned seed = 13) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> coin(0.0, 1.0);
  TriangleMesh out = mesh;
  for (int t = 0; t < out.num_triangles(); ++t) {
    if (fraction >= 1.0 || coin(rng) < fraction) std::swap(out.triangles(1, t), out.triangles(2, t));
  }
  return out;
}

/// Every triangle twice, the copy right after the original.
inline TriangleMesh duplicate_triangles(const TriangleMesh& mesh) {
  TriangleMesh out;
  out.vertices = mesh.vertices;
  out.triangles.resize(3, 2 * mesh.num_triangles());
  for (const MeshPart& part : parts_of(mesh)) {
    MeshPart doubled = part;
    doubled.first_triangle = 2 * part.first_triangle;
    doubled.triangle_count = 2 * part.triangle_count;
    out.parts.push_back(doubled);
  }
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    out.triangles.col(2 * t) = mesh.triangles.col(t);
    out.triangles.col(2 * t + 1) = mesh.triangles.col(t);
  }
  return out;
}

}  // namespace cubespring::test
