// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "contact_surface.h"

#include <array>
#include <cstdint>
#include <unordered_map>
#include <unordered_set>

#include <Eigen/Geometry>

namespace cubespring::bullet {

namespace {

std::int64_t grid_key(const Eigen::Vector3i& index) {
  constexpr std::int64_t kOffset = std::int64_t{1} << 20;
  return ((index.x() + kOffset) << 42) | ((index.y() + kOffset) << 21) | (index.z() + kOffset);
}

}  // namespace

ContactSurface lattice_boundary_surface(const Model& model) {
  std::unordered_set<std::int64_t> occupied;
  for (const Eigen::Vector3i& cell : model.cell_grid_index) occupied.insert(grid_key(cell));
  ContactSurface surface;
  std::unordered_map<int, int> vertex_of_node;
  std::vector<std::array<int, 3>> triangles;
  const auto vertex = [&](int node) {
    const auto [it, inserted] = vertex_of_node.emplace(node, static_cast<int>(vertex_of_node.size()));
    if (inserted) {
      surface.node.push_back(node);
      surface.weight.push_back(1.0);
    }
    return it->second;
  };
  for (int c = 0; c < model.num_cells(); ++c) {
    const auto& corners = model.cell_nodes[static_cast<std::size_t>(c)];
    for (int axis = 0; axis < 3; ++axis) {
      for (int side = 0; side < 2; ++side) {
        Eigen::Vector3i neighbour = model.cell_grid_index[static_cast<std::size_t>(c)];
        neighbour[axis] += side == 1 ? 1 : -1;
        if (occupied.count(grid_key(neighbour)) != 0) continue;
        // the face's corners in the order (0,0), (1,0), (1,1), (0,1) of the next two axes turn
        // counter-clockwise about +axis; the low side is turned the other way
        const int b = (axis + 1) % 3;
        const int cc = (axis + 2) % 3;
        std::array<int, 4> quad{};
        const std::array<std::array<int, 2>, 4> steps{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}};
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
  surface.offset.resize(surface.node.size() + 1);
  for (std::size_t v = 0; v <= surface.node.size(); ++v) surface.offset[v] = static_cast<int>(v);
  surface.triangles.resize(3, static_cast<Eigen::Index>(triangles.size()));
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    surface.triangles.col(static_cast<Eigen::Index>(t)) << triangles[t][0], triangles[t][1], triangles[t][2];
  }
  return surface;
}

Eigen::Matrix3Xd vertex_normals(const Eigen::Matrix3Xd& positions, const Eigen::Matrix3Xi& triangles) {
  Eigen::Matrix3Xd normals = Eigen::Matrix3Xd::Zero(3, positions.cols());
  for (Eigen::Index t = 0; t < triangles.cols(); ++t) {
    const Eigen::Vector3d a = positions.col(triangles(0, t));
    // twice the area times the unit normal: larger triangles count more
    const Eigen::Vector3d weighted = (positions.col(triangles(1, t)) - a).cross(positions.col(triangles(2, t)) - a);
    for (int corner = 0; corner < 3; ++corner) normals.col(triangles(corner, t)) += weighted;
  }
  for (Eigen::Index v = 0; v < normals.cols(); ++v) {
    const double length = normals.col(v).norm();
    if (length > 0.0) normals.col(v) /= length;
  }
  return normals;
}

ContactSurface embedded_surface(const Model& model, const Embedding& embedding) {
  ContactSurface surface;
  surface.offset.push_back(0);
  for (int v = 0; v < embedding.num_vertices(); ++v) {
    const auto& corners = model.cell_nodes[static_cast<std::size_t>(embedding.vertex_cell[static_cast<std::size_t>(v)])];
    const Eigen::Vector3d u = embedding.vertex_local.col(v);
    for (int corner = 0; corner < kCornersPerCell; ++corner) {
      double weight = 1.0;
      for (int axis = 0; axis < 3; ++axis) weight *= ((corner >> axis) & 1) ? u[axis] : 1.0 - u[axis];
      surface.node.push_back(corners[static_cast<std::size_t>(corner)]);
      surface.weight.push_back(weight);
    }
    surface.offset.push_back(static_cast<int>(surface.node.size()));
  }
  surface.triangles = embedding.triangles;
  return surface;
}

}  // namespace cubespring::bullet
