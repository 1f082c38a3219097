// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Where faces between cells are split (LatticeDesc::split_faces), the grid points whose node the
// split parts: which cells around each point still hold together there, and so how many copies of
// its node the point has and which copy each cell's corner takes.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

#include "cubespring/lattice.h"
#include "cubespring/model.h"
#include "cubespring/result.h"

namespace cubespring {

/// The node copies at one grid point that a split face touches.
struct PointCopies {
  Eigen::Vector3i point{0, 0, 0};  ///< grid index
  int count = 1;                   ///< copies of its node (1: the cells around it still hold together)
  /// Around the point, the cell whose corner k lies on it (its index in the cells given), or -1,
  /// and the copy that corner takes (0 .. count-1, numbered in the order of the cells' indices).
  std::array<int, kCornersPerCell> cell{};
  std::array<int, kCornersPerCell> copy{};
};

/// For `cells` (grid indices, no repeats) split along `faces`: the points the faces touch, each
/// once, with their copies. Around a point, two cells hold together when they share a face that
/// is not split, or touch along an edge or at the point only with no cell of the body between
/// them (as every touching cell did before any split); the groups that holding together makes are
/// the copies. Errors name a face (its index in `faces`) whose axis is not 0-2, whose cell or
/// neighbour is not in `cells`, or which is listed twice.
Result<std::vector<PointCopies>> split_point_copies(const std::vector<Eigen::Vector3i>& cells,
                                                    const std::vector<CellFace>& faces);

}  // namespace cubespring
