// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "surface_refinement.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace cubespring::bullet {
namespace {

// Splitting the long edges of the triangles that the last round cut can leave a new edge (a
// median) still long; each round at least halves the longest edge of a triangle that was cut in
// four, so this many rounds end any mesh whose edges are within 2^30 of max_edge.
constexpr int kMaxRounds = 64;

std::uint64_t edge_key(int a, int b) {
  const auto [low, high] = std::minmax(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(low)) << 32) | static_cast<std::uint32_t>(high);
}

}  // namespace

TriangleMesh split_long_edges(const TriangleMesh& mesh, double max_edge) {
  std::vector<Eigen::Vector3d> vertices(static_cast<std::size_t>(mesh.num_vertices()));
  for (int v = 0; v < mesh.num_vertices(); ++v) vertices[static_cast<std::size_t>(v)] = mesh.vertices.col(v);
  std::vector<std::array<int, 3>> triangles(static_cast<std::size_t>(mesh.num_triangles()));
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    triangles[static_cast<std::size_t>(t)] = {mesh.triangles(0, t), mesh.triangles(1, t), mesh.triangles(2, t)};
  }
  const double max_squared = max_edge * max_edge;
  const auto at = [&](int v) { return vertices[static_cast<std::size_t>(v)]; };
  for (int round = 0; round < kMaxRounds; ++round) {
    std::unordered_map<std::uint64_t, int> midpoint_of;
    const auto midpoint = [&](int a, int b) {
      if ((at(a) - at(b)).squaredNorm() <= max_squared) return -1;
      const auto [entry, added] = midpoint_of.emplace(edge_key(a, b), static_cast<int>(vertices.size()));
      if (added) vertices.push_back(0.5 * (at(a) + at(b)));
      return entry->second;
    };
    std::vector<std::array<int, 3>> next;
    next.reserve(triangles.size());
    for (const std::array<int, 3>& corner : triangles) {
      // edge k runs from corner k to corner k + 1
      const std::array<int, 3> middle{midpoint(corner[0], corner[1]), midpoint(corner[1], corner[2]),
                                      midpoint(corner[2], corner[0])};
      const int splits = (middle[0] >= 0) + (middle[1] >= 0) + (middle[2] >= 0);
      // turned (cyclically: the winding stays) so that edge 0 is split, and with two splits
      // edge 2 is the one that is not
      int first = 0;
      if (splits == 1) first = middle[0] >= 0 ? 0 : middle[1] >= 0 ? 1 : 2;
      if (splits == 2) first = middle[0] < 0 ? 1 : middle[1] < 0 ? 2 : 0;
      const int a = corner[static_cast<std::size_t>(first)];
      const int b = corner[static_cast<std::size_t>((first + 1) % 3)];
      const int c = corner[static_cast<std::size_t>((first + 2) % 3)];
      const int ab = middle[static_cast<std::size_t>(first)];
      const int bc = middle[static_cast<std::size_t>((first + 1) % 3)];
      const int ca = middle[static_cast<std::size_t>((first + 2) % 3)];
      switch (splits) {
        case 0: next.push_back({a, b, c}); break;
        case 1:
          next.push_back({a, ab, c});
          next.push_back({ab, b, c});
          break;
        case 2: {
          next.push_back({ab, b, bc});
          // the quad a, ab, bc, c cut along its shorter diagonal
          if ((at(a) - at(bc)).squaredNorm() <= (at(ab) - at(c)).squaredNorm()) {
            next.push_back({a, ab, bc});
            next.push_back({a, bc, c});
          } else {
            next.push_back({a, ab, c});
            next.push_back({ab, bc, c});
          }
          break;
        }
        default:
          next.push_back({a, ab, ca});
          next.push_back({ab, b, bc});
          next.push_back({ca, bc, c});
          next.push_back({ab, bc, ca});
          break;
      }
    }
    triangles = std::move(next);
    if (midpoint_of.empty()) break;
  }
  TriangleMesh refined;
  refined.vertices.resize(3, static_cast<Eigen::Index>(vertices.size()));
  for (std::size_t v = 0; v < vertices.size(); ++v) refined.vertices.col(static_cast<Eigen::Index>(v)) = vertices[v];
  refined.triangles.resize(3, static_cast<Eigen::Index>(triangles.size()));
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const std::array<int, 3>& corner = triangles[t];
    refined.triangles.col(static_cast<Eigen::Index>(t)) = Eigen::Vector3i(corner[0], corner[1], corner[2]);
  }
  return refined;
}

}  // namespace cubespring::bullet
