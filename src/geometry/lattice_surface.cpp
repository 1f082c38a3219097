// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "cubespring/lattice_surface.h"

#include <array>
#include <cstdint>
#include <set>
#include <unordered_map>
#include <unordered_set>
#include <utility>

namespace cubespring {

namespace {

std::int64_t grid_key(const Eigen::Vector3i& index) {
  constexpr std::int64_t kOffset = std::int64_t{1} << 20;
  return ((index.x() + kOffset) << 42) | ((index.y() + kOffset) << 21) | (index.z() + kOffset);
}

}  // namespace

LatticeSurface lattice_boundary_surface(const Model& model) {
  std::unordered_set<std::int64_t> occupied;
  for (const Eigen::Vector3i& cell : model.cell_grid_index) occupied.insert(grid_key(cell));
  // a split face bounds both its cells (each side has its own copies of the face's nodes)
  std::set<std::pair<std::int64_t, int>> split;
  for (const CellFace& face : model.split_faces) split.emplace(grid_key(face.cell), face.axis);
  LatticeSurface surface;
  std::unordered_map<int, int> vertex_of_node;
  std::vector<std::array<int, 3>> triangles;
  const auto vertex = [&](int node) {
    const auto [it, inserted] = vertex_of_node.emplace(node, static_cast<int>(vertex_of_node.size()));
    if (inserted) surface.nodes.push_back(node);
    return it->second;
  };
  // a cell's corner k sits at offset ((k >> 0) & 1, (k >> 1) & 1, (k >> 2) & 1) in x, y, z
  const std::array<std::array<int, 2>, 4> steps{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}};
  for (int c = 0; c < model.num_cells(); ++c) {
    const auto& corners = model.cell_nodes[static_cast<std::size_t>(c)];
    for (int axis = 0; axis < 3; ++axis) {
      for (int side = 0; side < 2; ++side) {
        Eigen::Vector3i neighbour = model.cell_grid_index[static_cast<std::size_t>(c)];
        neighbour[axis] += side == 1 ? 1 : -1;
        const Eigen::Vector3i& lower = side == 1 ? model.cell_grid_index[static_cast<std::size_t>(c)] : neighbour;
        if (occupied.count(grid_key(neighbour)) != 0 && split.count({grid_key(lower), axis}) == 0) continue;
        // the face's corners in the order (0,0), (1,0), (1,1), (0,1) of the next two axes turn
        // counter-clockwise about +axis; the low side is turned the other way
        const int b = (axis + 1) % 3;
        const int cc = (axis + 2) % 3;
        std::array<int, 4> quad{};
        for (std::size_t k = 0; k < 4; ++k) {
          const int corner = (side << axis) | (steps[k][0] << b) | (steps[k][1] << cc);
          quad[k] = vertex(corners[static_cast<std::size_t>(corner)]);
        }
        if (side == 0) std::swap(quad[1], quad[3]);
        triangles.push_back({quad[0], quad[1], quad[2]});
        triangles.push_back({quad[0], quad[2], quad[3]});
      }
    }
  }
  surface.triangles.resize(3, static_cast<Eigen::Index>(triangles.size()));
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    surface.triangles.col(static_cast<Eigen::Index>(t)) << triangles[t][0], triangles[t][1], triangles[t][2];
  }
  return surface;
}

Eigen::Matrix3Xd surface_vertices(const LatticeSurface& surface, const Eigen::Matrix3Xd& node_positions) {
  Eigen::Matrix3Xd vertices(3, static_cast<Eigen::Index>(surface.nodes.size()));
  for (std::size_t v = 0; v < surface.nodes.size(); ++v) {
    vertices.col(static_cast<Eigen::Index>(v)) = node_positions.col(surface.nodes[v]);
  }
  return vertices;
}

}  // namespace cubespring
