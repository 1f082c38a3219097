// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "model/node_copies.h"

#include <algorithm>
#include <bitset>
#include <cstdint>
#include <map>
#include <numeric>
#include <set>
#include <string>

#include "model/cell_geometry.h"

namespace cubespring {
namespace {

using GridKey = std::array<int, 3>;
GridKey key_of(const Eigen::Vector3i& g) { return {g.x(), g.y(), g.z()}; }

std::string cell_text(const Eigen::Vector3i& cell) {
  return "(" + std::to_string(cell.x()) + ", " + std::to_string(cell.y()) + ", " + std::to_string(cell.z()) + ")";
}

std::string face_text(std::size_t f, const CellFace& face) {
  return "split face " + std::to_string(f) + " (cell " + cell_text(face.cell) + ", axis " + std::to_string(face.axis) +
         ")";
}

// Union-find over the 8 corners around a point.
struct CornerGroups {
  std::array<int, kCornersPerCell> parent;
  CornerGroups() { std::iota(parent.begin(), parent.end(), 0); }
  int root(int k) {
    while (parent[static_cast<std::size_t>(k)] != k) k = parent[static_cast<std::size_t>(k)];
    return k;
  }
  void join(int a, int b) { parent[static_cast<std::size_t>(root(a))] = root(b); }
};

}  // namespace

Result<std::vector<PointCopies>> split_point_copies(const std::vector<Eigen::Vector3i>& cells,
                                                    const std::vector<CellFace>& faces) {
  std::map<GridKey, int> cell_at;
  for (std::size_t c = 0; c < cells.size(); ++c) cell_at.emplace(key_of(cells[c]), static_cast<int>(c));
  std::set<std::pair<GridKey, int>> split;  // (lower cell, axis)
  std::set<GridKey> points;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const CellFace& face = faces[f];
    if (face.axis < 0 || face.axis > 2) {
      return Status::error(face_text(f, face) + ": the axis must be 0, 1 or 2 (x, y, z)");
    }
    Eigen::Vector3i next = face.cell;
    next[face.axis] += 1;
    for (const Eigen::Vector3i& side : {face.cell, next}) {
      if (cell_at.count(key_of(side)) == 0) {
        return Status::error(face_text(f, face) + ": cell " + cell_text(side) +
                             " is not a cell of the body (a face can only be split between two cells)");
      }
    }
    if (!split.emplace(key_of(face.cell), face.axis).second)
      return Status::error(face_text(f, face) + " is listed twice");
    // the face's 4 corners: the points its split may part
    const int b = (face.axis + 1) % 3, c = (face.axis + 2) % 3;
    for (int i = 0; i < 2; ++i) {
      for (int j = 0; j < 2; ++j) {
        Eigen::Vector3i point = next;
        point[b] += i;
        point[c] += j;
        points.insert(key_of(point));
      }
    }
  }

  std::vector<PointCopies> copies;
  for (const GridKey& key : points) {
    PointCopies at;
    at.point = {key[0], key[1], key[2]};
    std::array<Eigen::Vector3i, kCornersPerCell> cell_index;
    for (int k = 0; k < kCornersPerCell; ++k) {
      cell_index[static_cast<std::size_t>(k)] = at.point - corner_offset(k);
      const auto found = cell_at.find(key_of(cell_index[static_cast<std::size_t>(k)]));
      at.cell[static_cast<std::size_t>(k)] = found == cell_at.end() ? -1 : found->second;
    }
    const auto present = [&](int k) { return at.cell[static_cast<std::size_t>(k)] >= 0; };
    CornerGroups groups;
    for (int a = 0; a < kCornersPerCell; ++a) {
      for (int b = a + 1; b < kCornersPerCell; ++b) {
        if (!present(a) || !present(b)) continue;
        const int differ = a ^ b;
        bool together = false;
        if (std::bitset<3>(static_cast<unsigned>(differ)).count() == 1) {  // a shared face
          int axis = 0;
          while ((differ >> axis) != 1) ++axis;
          // the cell whose corner on the point has the axis's bit set lies below it: the face's cell
          const Eigen::Vector3i& lower = cell_index[static_cast<std::size_t>((a & differ) ? a : b)];
          together = split.count({key_of(lower), axis}) == 0;
        } else {  // an edge or the point only: together when no cell lies between them
          together = true;
          for (int k = 0; k < kCornersPerCell && together; ++k) {
            // the cells between share a's corner bits outside `differ` and differ from both
            const bool between = (k & ~differ) == (a & ~differ) && k != a && k != b;
            together = !(between && present(k));
          }
        }
        if (together) groups.join(a, b);
      }
    }
    // copies numbered in the order of their first cell
    std::map<int, int> first_cell_of_root;
    for (int k = 0; k < kCornersPerCell; ++k) {
      if (!present(k)) continue;
      auto [it, inserted] = first_cell_of_root.emplace(groups.root(k), at.cell[static_cast<std::size_t>(k)]);
      if (!inserted) it->second = std::min(it->second, at.cell[static_cast<std::size_t>(k)]);
    }
    std::vector<std::pair<int, int>> order;  // (first cell, root)
    for (const auto& [root, first] : first_cell_of_root) order.emplace_back(first, root);
    std::sort(order.begin(), order.end());
    at.count = static_cast<int>(order.size());
    for (int k = 0; k < kCornersPerCell; ++k) {
      at.copy[static_cast<std::size_t>(k)] = -1;
      if (!present(k)) continue;
      const int root = groups.root(k);
      at.copy[static_cast<std::size_t>(k)] = static_cast<int>(
          std::find_if(order.begin(), order.end(), [&](const auto& entry) { return entry.second == root; }) -
          order.begin());
    }
    copies.push_back(at);
  }
  return copies;
}

}  // namespace cubespring
