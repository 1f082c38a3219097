// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "forces/drive_nodes.h"

#include <algorithm>
#include <cstring>

namespace cubespring {

bool drive_nodes(const Constraints& constraints, double dt, const State& start, State& end, int begin, int end_node) {
  bool finite = true;
  const std::uint8_t* driven = constraints.driven_flags();
  constexpr int kWord = sizeof(std::uint64_t);
  for (int first = begin; first < end_node; first += kWord) {
    const int last = std::min(first + kWord, end_node);
    if (last - first == kWord) {  // most nodes are free: skip them a word of flags at a time
      std::uint64_t word;
      std::memcpy(&word, driven + first, sizeof word);
      if (word == 0) continue;
    }
    for (int n = first; n < last; ++n) finite = drive_node(constraints, dt, start, end, n) && finite;
  }
  return finite;
}

}  // namespace cubespring
