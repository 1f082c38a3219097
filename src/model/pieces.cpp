// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "model/pieces.h"

#include <numeric>
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

}  // namespace cubespring
