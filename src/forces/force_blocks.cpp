// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "forces/force_blocks.h"

#include <algorithm>

namespace cubespring {
namespace {

// Below this many springs a block costs more in barriers than a second thread saves.
constexpr int kMinSpringsPerBlock = 4096;
// Enough blocks for the threads of a workstation; more only add halo nodes.
constexpr int kMaxBlocks = 16;
// A block spans at least this many times the longest spring's node-index span, so that its halo
// (the nodes of the next block its springs reach) is a small part of that block.
constexpr int kMinBlockSpans = 4;

// Node ranges of about equal spring counts; false when some block's springs reach past the next.
bool try_split(const Model& model, int blocks, ForceBlocks& split) {
  const int num_nodes = model.num_nodes();
  const int num_springs = model.num_springs();
  std::vector<int> nodes(blocks + 1, num_nodes);
  nodes[0] = 0;
  for (int b = 1; b < blocks; ++b) {
    const long long target = static_cast<long long>(num_springs) * b / blocks;
    const auto it = std::lower_bound(model.node_first_spring.begin(), model.node_first_spring.end() - 1, target);
    nodes[b] = std::max(nodes[b - 1], static_cast<int>(it - model.node_first_spring.begin()));
  }
  std::vector<int> reach(blocks);
  for (int b = 0; b < blocks; ++b) {
    if (nodes[b + 1] <= nodes[b]) return false;
    reach[b] = nodes[b + 1];
    for (int n = nodes[b]; n < nodes[b + 1]; ++n) {
      // springs of a node are sorted by second node: the last one reaches farthest
      const int last = model.node_first_spring[n + 1] - 1;
      if (last >= model.node_first_spring[n]) reach[b] = std::max(reach[b], model.spring_nodes[last][1] + 1);
    }
    if (b + 2 <= blocks && reach[b] > nodes[std::min(b + 2, blocks)]) return false;
  }
  split.nodes = std::move(nodes);
  split.reach = std::move(reach);
  return true;
}

}  // namespace

ForceBlocks split_force_blocks(const Model& model) {
  ForceBlocks split;
  split.num_nodes = model.num_nodes();
  int span = 1;
  for (const auto& ends : model.spring_nodes) span = std::max(span, ends[1] - ends[0]);
  int blocks = 1;
  while (2 * blocks <= kMaxBlocks && model.num_springs() / (2 * blocks) >= kMinSpringsPerBlock &&
         model.num_nodes() / (2 * blocks) >= kMinBlockSpans * span) {
    blocks *= 2;
  }
  for (; blocks > 1; blocks /= 2) {
    if (try_split(model, blocks, split)) return split;
  }
  (void)try_split(model, 1, split);
  return split;
}

}  // namespace cubespring
