// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "voxelize/cell_connectivity.h"

#include <algorithm>
#include <array>

namespace cubespring::voxelize_detail {

namespace {

// Labels face-connected pieces; returns the size of each piece.
std::vector<int> label_pieces(const CellGrid& grid, std::vector<int>& piece) {
  piece.assign(grid.label.size(), -1);
  std::vector<int> piece_size;
  std::vector<Eigen::Vector3i> queue;
  const std::array<Eigen::Vector3i, 6> faces{Eigen::Vector3i(1, 0, 0), Eigen::Vector3i(-1, 0, 0),
                                             Eigen::Vector3i(0, 1, 0), Eigen::Vector3i(0, -1, 0),
                                             Eigen::Vector3i(0, 0, 1), Eigen::Vector3i(0, 0, -1)};
  for (int k = 0; k < grid.size.z(); ++k) {
    for (int j = 0; j < grid.size.y(); ++j) {
      for (int i = 0; i < grid.size.x(); ++i) {
        if (!grid.occupied(i, j, k) || piece[grid.index(i, j, k)] >= 0) continue;
        const int id = static_cast<int>(piece_size.size());
        piece_size.push_back(0);
        queue.assign(1, Eigen::Vector3i(i, j, k));
        piece[grid.index(i, j, k)] = id;
        while (!queue.empty()) {
          const Eigen::Vector3i cell = queue.back();
          queue.pop_back();
          ++piece_size.back();
          for (const Eigen::Vector3i& step : faces) {
            const Eigen::Vector3i next = cell + step;
            if (!grid.occupied(next.x(), next.y(), next.z())) continue;
            int& next_piece = piece[grid.index(next.x(), next.y(), next.z())];
            if (next_piece >= 0) continue;
            next_piece = id;
            queue.push_back(next);
          }
        }
      }
    }
  }
  return piece_size;
}

// Cell pairs across an edge (2 of the 4 cells around it, diagonally) and across a corner (2 of
// the 8, opposite), each pair counted once.
const std::array<Eigen::Vector3i, 6> kEdgeDiagonals{Eigen::Vector3i(1, 1, 0), Eigen::Vector3i(1, -1, 0),
                                                    Eigen::Vector3i(1, 0, 1), Eigen::Vector3i(1, 0, -1),
                                                    Eigen::Vector3i(0, 1, 1), Eigen::Vector3i(0, 1, -1)};
const std::array<Eigen::Vector3i, 4> kCornerDiagonals{Eigen::Vector3i(1, 1, 1), Eigen::Vector3i(1, 1, -1),
                                                      Eigen::Vector3i(1, -1, 1), Eigen::Vector3i(1, -1, -1)};

// True when no other cell around the shared edge or corner is occupied: the pair shares
// nodes with nothing else there, and turns about them freely.
bool only_pair_around(const CellGrid& grid, const Eigen::Vector3i& cell, const Eigen::Vector3i& step) {
  // the cells around the shared feature are cell + any sub-step of step (each component 0 or step)
  for (int mask = 1; mask < 7; ++mask) {
    Eigen::Vector3i other = cell;
    bool valid = true;
    for (int axis = 0; axis < 3; ++axis) {
      if ((mask >> axis) & 1) {
        if (step[axis] == 0) valid = false;
        other[axis] += step[axis];
      }
    }
    if (!valid || other == cell + step) continue;
    if (grid.occupied(other.x(), other.y(), other.z())) return false;
  }
  return true;
}

}  // namespace

CellConnectivity analyse_connectivity(CellGrid& grid, bool drop_islands) {
  CellConnectivity report;
  for (int k = 0; k < grid.size.z(); ++k) {
    for (int j = 0; j < grid.size.y(); ++j) {
      for (int i = 0; i < grid.size.x(); ++i) {
        if (!grid.occupied(i, j, k)) continue;
        const Eigen::Vector3i cell(i, j, k);
        for (const Eigen::Vector3i& step : kEdgeDiagonals) {
          const Eigen::Vector3i other = cell + step;
          if (grid.occupied(other.x(), other.y(), other.z()) && only_pair_around(grid, cell, step)) {
            ++report.edge_only_contacts;
          }
        }
        for (const Eigen::Vector3i& step : kCornerDiagonals) {
          const Eigen::Vector3i other = cell + step;
          if (grid.occupied(other.x(), other.y(), other.z()) && only_pair_around(grid, cell, step)) {
            ++report.corner_only_contacts;
          }
        }
      }
    }
  }
  std::vector<int> piece;
  const std::vector<int> piece_size = label_pieces(grid, piece);
  if (piece_size.empty()) return report;
  const auto largest = static_cast<int>(std::max_element(piece_size.begin(), piece_size.end()) - piece_size.begin());
  for (std::size_t p = 0; p < piece_size.size(); ++p) {
    if (static_cast<int>(p) == largest) continue;
    ++report.islands;
    report.island_cells += piece_size[p];
  }
  if (drop_islands && report.islands > 0) {
    for (std::size_t c = 0; c < grid.label.size(); ++c) {
      if (grid.label[c] >= 0 && piece[c] != largest) grid.label[c] = -1;
    }
    report.dropped_cells = report.island_cells;
  }
  return report;
}

void count_nodes_and_springs(const CellGrid& grid, int& nodes, int& springs) {
  // a node is used when any of the 8 cells around it is occupied; an edge along an axis when any of
  // the 4 cells around it is; each cell adds its 4 body diagonals
  std::int64_t node_count = 0;
  std::int64_t edge_count = 0;
  std::int64_t cell_count = 0;
  const Eigen::Vector3i& n = grid.size;
  for (int k = 0; k <= n.z(); ++k) {
    for (int j = 0; j <= n.y(); ++j) {
      for (int i = 0; i <= n.x(); ++i) {
        // any occupied cell among i - 1 + low.x .. i, and so on per axis
        const auto any = [&](int low_i, int low_j, int low_k) {
          for (int ck = k - 1 + low_k; ck <= k; ++ck)
            for (int cj = j - 1 + low_j; cj <= j; ++cj)
              for (int ci = i - 1 + low_i; ci <= i; ++ci)
                if (grid.occupied(ci, cj, ck)) return true;
          return false;
        };
        if (any(0, 0, 0)) ++node_count;
        if (i < n.x() && any(1, 0, 0)) ++edge_count;  // edge (i,j,k)-(i+1,j,k): cells i, j-1..j, k-1..k
        if (j < n.y() && any(0, 1, 0)) ++edge_count;
        if (k < n.z() && any(0, 0, 1)) ++edge_count;
        if (grid.occupied(i, j, k)) ++cell_count;
      }
    }
  }
  nodes = static_cast<int>(node_count);
  springs = static_cast<int>(edge_count + 4 * cell_count);
}

}  // namespace cubespring::voxelize_detail
