// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "contact_surface.h"

#include "cubespring/lattice_surface.h"

namespace cubespring::bullet {

ContactSurface lattice_boundary_surface(const Model& model) {
  const LatticeSurface boundary = cubespring::lattice_boundary_surface(model);
  ContactSurface surface;
  surface.node = boundary.nodes;
  surface.weight.assign(boundary.nodes.size(), 1.0);
  surface.offset.resize(boundary.nodes.size() + 1);
  for (std::size_t v = 0; v <= boundary.nodes.size(); ++v) surface.offset[v] = static_cast<int>(v);
  surface.triangles = boundary.triangles;
  return surface;
}

ContactSurface embedded_surface(const Model& model, const Embedding& embedding) {
  ContactSurface surface;
  surface.offset.push_back(0);
  for (int v = 0; v < embedding.num_vertices(); ++v) {
    const auto& corners =
        model.cell_nodes[static_cast<std::size_t>(embedding.vertex_cell[static_cast<std::size_t>(v)])];
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
