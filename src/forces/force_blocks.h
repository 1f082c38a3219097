// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Blocks of consecutive first nodes that the spring-list passes hand to threads
// (docs/data-layout.md). Part of the force engine (force_engine.h), built from a Model.
#pragma once

#include <vector>

#include "cubespring/model.h"

namespace cubespring {

/// Block b holds the springs whose first node is in nodes[b] .. nodes[b+1]-1; their second nodes
/// stay below reach[b], which is at most the end of block b+1. Threads take whole blocks, and the
/// count depends on the body alone, so forces do not depend on the thread count. Empty: one block
/// of every node.
struct ForceBlocks {
  std::vector<int> nodes;
  std::vector<int> reach;
  int num_nodes = 0;

  int count() const { return nodes.empty() ? 1 : static_cast<int>(nodes.size()) - 1; }
  /// First node of block b, and one past its last (b = count() gives num_nodes).
  int begin(int b) const {
    if (nodes.empty()) return b == 0 ? 0 : num_nodes;
    return nodes[b];
  }
  int end(int b) const { return begin(b + 1); }
  /// One past the highest second node of block b's springs.
  int reach_of(int b) const { return reach.empty() ? num_nodes : reach[b]; }
};

/// The blocks of a model; needs its spring_nodes and node_first_spring.
ForceBlocks split_force_blocks(const Model& model);

}  // namespace cubespring
