// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "cubespring/shapes.h"

#include <array>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

namespace cubespring {

namespace {

TriangleMesh from_lists(const std::vector<Eigen::Vector3d>& vertices,
                        const std::vector<std::array<int, 3>>& triangles) {
  TriangleMesh mesh;
  mesh.vertices.resize(3, static_cast<Eigen::Index>(vertices.size()));
  for (std::size_t v = 0; v < vertices.size(); ++v) mesh.vertices.col(static_cast<Eigen::Index>(v)) = vertices[v];
  mesh.triangles.resize(3, static_cast<Eigen::Index>(triangles.size()));
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    for (int c = 0; c < 3; ++c)
      mesh.triangles(c, static_cast<Eigen::Index>(t)) = triangles[t][static_cast<std::size_t>(c)];
  }
  mesh.parts = {MeshPart{"", "", 0, static_cast<int>(triangles.size())}};
  return mesh;
}

}  // namespace

TriangleMesh sphere_mesh(double radius, int subdivisions, const Eigen::Vector3d& centre) {
  // unit octahedron; midpoints are normalised, so every vertex is computed from its own
  // coordinates' magnitudes and the sphere keeps the octahedron's symmetry exactly
  std::vector<Eigen::Vector3d> vertices{{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  std::vector<std::array<int, 3>> triangles{{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                                            {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (int level = 0; level < subdivisions; ++level) {
    std::map<std::pair<int, int>, int> midpoint_of;
    const auto midpoint = [&](int a, int b) {
      const std::pair<int, int> key{std::min(a, b), std::max(a, b)};
      const auto found = midpoint_of.find(key);
      if (found != midpoint_of.end()) return found->second;
      vertices.push_back((vertices[static_cast<std::size_t>(a)] + vertices[static_cast<std::size_t>(b)]).normalized());
      const int index = static_cast<int>(vertices.size()) - 1;
      midpoint_of.emplace(key, index);
      return index;
    };
    std::vector<std::array<int, 3>> finer;
    finer.reserve(triangles.size() * 4);
    for (const auto& [a, b, c] : triangles) {
      const int ab = midpoint(a, b);
      const int bc = midpoint(b, c);
      const int ca = midpoint(c, a);
      finer.push_back({a, ab, ca});
      finer.push_back({ab, b, bc});
      finer.push_back({ca, bc, c});
      finer.push_back({ab, bc, ca});
    }
    triangles = std::move(finer);
  }
  for (Eigen::Vector3d& v : vertices) v = centre + radius * v;
  return from_lists(vertices, triangles);
}

TriangleMesh torus_mesh(double major_radius, double minor_radius, int around, int tube, const Eigen::Vector3d& centre) {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;
  for (int i = 0; i < around; ++i) {
    const double phi = 2.0 * M_PI * i / around;
    for (int j = 0; j < tube; ++j) {
      const double theta = 2.0 * M_PI * j / tube;
      const double ring = major_radius + minor_radius * std::cos(theta);
      vertices.push_back(centre +
                         Eigen::Vector3d(ring * std::cos(phi), ring * std::sin(phi), minor_radius * std::sin(theta)));
    }
  }
  const auto at = [&](int i, int j) { return (i % around) * tube + (j % tube); };
  for (int i = 0; i < around; ++i) {
    for (int j = 0; j < tube; ++j) {
      // (i, j) -> (i+1, j) runs along phi, (i, j) -> (i, j+1) along theta: their cross product
      // points out of the tube
      triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  }
  return from_lists(vertices, triangles);
}

TriangleMesh box_mesh(const Eigen::Vector3d& lower, const Eigen::Vector3d& upper) {
  std::vector<Eigen::Vector3d> vertices;
  for (int corner = 0; corner < 8; ++corner) {
    vertices.emplace_back((corner & 1) ? upper.x() : lower.x(), (corner & 2) ? upper.y() : lower.y(),
                          (corner & 4) ? upper.z() : lower.z());
  }
  const std::vector<std::array<int, 3>> triangles{
      {0, 2, 3}, {0, 3, 1},  // z = lower
      {4, 5, 7}, {4, 7, 6},  // z = upper
      {0, 1, 5}, {0, 5, 4},  // y = lower
      {2, 6, 7}, {2, 7, 3},  // y = upper
      {0, 4, 6}, {0, 6, 2},  // x = lower
      {1, 3, 7}, {1, 7, 5},  // x = upper
  };
  return from_lists(vertices, triangles);
}

TriangleMesh hollow_mesh(const TriangleMesh& outer, const TriangleMesh& inner) {
  TriangleMesh inside_out = inner;
  inside_out.triangles.row(1).swap(inside_out.triangles.row(2));
  TriangleMesh hollow = combine_meshes(outer, inside_out);
  hollow.parts = {MeshPart{"", "", 0, hollow.num_triangles()}};
  return hollow;
}

TriangleMesh combine_meshes(const TriangleMesh& a, const TriangleMesh& b) {
  TriangleMesh combined;
  combined.vertices.resize(3, a.num_vertices() + b.num_vertices());
  combined.vertices << a.vertices, b.vertices;
  combined.triangles.resize(3, a.num_triangles() + b.num_triangles());
  combined.triangles << a.triangles, (b.triangles.array() + a.num_vertices()).matrix();
  combined.parts = parts_of(a);
  for (MeshPart part : parts_of(b)) {
    part.first_triangle += a.num_triangles();
    combined.parts.push_back(part);
  }
  return combined;
}

}  // namespace cubespring
