// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "cubespring/render/wireframe.h"

#include <vector>

namespace cubespring {

void lattice_wireframe(const Model& model, const Eigen::Matrix3Xd& node_positions, Eigen::Matrix3Xd& points,
                       Eigen::Matrix2Xi& segments) {
  points = node_positions;

  // cells that touch share edge springs: mark each spring once
  std::vector<bool> is_edge(model.spring_nodes.size(), false);
  for (const auto& edges : model.cell_edges) {
    for (int spring : edges) is_edge[static_cast<std::size_t>(spring)] = true;
  }

  // one segment per marked spring, in spring order
  Eigen::Index count = 0;
  for (bool edge : is_edge) count += edge ? 1 : 0;
  segments.resize(2, count);
  Eigen::Index next = 0;
  for (std::size_t s = 0; s < is_edge.size(); ++s) {
    if (!is_edge[s]) continue;
    segments(0, next) = model.spring_nodes[s][0];
    segments(1, next) = model.spring_nodes[s][1];
    ++next;
  }
}

}  // namespace cubespring
