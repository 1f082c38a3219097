// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Cells joined only by an edge or a corner (hinges and ball joints that flop) and face-connected
// islands (pieces that float away): found on the occupancy grid (docs/voxelize.md, section 5).
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "cubespring/voxelize.h"

namespace cubespring::voxelize_detail {

/// Occupancy of a grid of cells: -1 where empty, else any label (a part index).
struct CellGrid {
  Eigen::Vector3i size{0, 0, 0};
  std::vector<std::int16_t> label;

  bool occupied(int i, int j, int k) const {
    if (i < 0 || j < 0 || k < 0 || i >= size.x() || j >= size.y() || k >= size.z()) return false;
    return label[index(i, j, k)] >= 0;
  }
  std::size_t index(int i, int j, int k) const {
    return static_cast<std::size_t>(i) +
           static_cast<std::size_t>(size.x()) *
               (static_cast<std::size_t>(j) + static_cast<std::size_t>(size.y()) * static_cast<std::size_t>(k));
  }
};

/// Counts hinges, ball joints and islands; with drop_islands, empties every cell outside the
/// largest face-connected piece.
CellConnectivity analyse_connectivity(CellGrid& grid, bool drop_islands);

/// Nodes and springs of the lattice the occupied cells make (shared nodes and edges once).
void count_nodes_and_springs(const CellGrid& grid, int& nodes, int& springs);

}  // namespace cubespring::voxelize_detail
