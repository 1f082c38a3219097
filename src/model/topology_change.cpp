// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "model/topology_change.h"

#include <numeric>
#include <string>
#include <vector>

namespace cubespring {

// union-find over the nodes, each cell joining its corners
int count_pieces(const Model& model) {
  std::vector<int> parent(static_cast<std::size_t>(model.num_nodes()));
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&](int n) {
    while (parent[static_cast<std::size_t>(n)] != n) {
      int& up = parent[static_cast<std::size_t>(n)];
      up = parent[static_cast<std::size_t>(up)];  // halve the path as we go
      n = up;
    }
    return n;
  };
  for (const auto& corners : model.cell_nodes) {
    for (int corner = 1; corner < kCornersPerCell; ++corner) {
      const int a = root(corners[0]), b = root(corners[static_cast<std::size_t>(corner)]);
      if (a != b) parent[static_cast<std::size_t>(b)] = a;
    }
  }
  int pieces = 0;
  for (int n = 0; n < model.num_nodes(); ++n) pieces += root(n) == n;
  return pieces;
}

Status check_body_sizes(const Model& model, const State& state, const Constraints& constraints) {
  const Eigen::Index nodes = model.num_nodes();
  if (state.positions.cols() != nodes || state.velocities.cols() != nodes) {
    return Status::error("the state has " + std::to_string(state.positions.cols()) + " positions and " +
                         std::to_string(state.velocities.cols()) + " velocities for a body of " +
                         std::to_string(nodes) + " nodes");
  }
  if (constraints.num_nodes() != nodes) {
    return Status::error("the constraints are for " + std::to_string(constraints.num_nodes()) +
                         " nodes, the body has " + std::to_string(nodes));
  }
  return {};
}

}  // namespace cubespring
