// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Blocks of consecutive first nodes that the force pass hands to threads (model.h,
// force_block_nodes; docs/data-layout.md).
#pragma once

#include "cubespring/model.h"

namespace cubespring {

/// Fills model.force_block_nodes and force_block_reach; needs spring_nodes and node_first_spring.
void split_force_blocks(Model& model);

inline int num_force_blocks(const Model& model) {
  return model.force_block_nodes.empty() ? 1 : static_cast<int>(model.force_block_nodes.size()) - 1;
}
/// First node of block b, and one past its last (b = num_force_blocks() gives num_nodes).
inline int force_block_begin(const Model& model, int b) {
  if (model.force_block_nodes.empty()) return b == 0 ? 0 : model.num_nodes();
  return model.force_block_nodes[b];
}
inline int force_block_end(const Model& model, int b) { return force_block_begin(model, b + 1); }
/// One past the highest second node of block b's springs.
inline int force_block_reach(const Model& model, int b) {
  return model.force_block_reach.empty() ? model.num_nodes() : model.force_block_reach[b];
}

}  // namespace cubespring
