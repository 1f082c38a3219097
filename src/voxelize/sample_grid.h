// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The points where the inside test is asked: the centres of a regular grid's boxes (cells, or
// sub-cells when a cell is sampled several times per axis).
#pragma once

#include <cstdint>

#include <Eigen/Core>

namespace cubespring::voxelize_detail {

struct SampleGrid {
  Eigen::Vector3d origin{0, 0, 0};   ///< corner of box (0,0,0) [m]
  Eigen::Vector3d spacing{0, 0, 0};  ///< box size [m]
  Eigen::Vector3i size{0, 0, 0};     ///< boxes along x, y, z
  /// origin / spacing, an integer per axis: the grid is aligned with the world origin, so
  /// a mesh symmetric about a grid node gives symmetric samples bit for bit.
  Eigen::Matrix<std::int64_t, 3, 1> origin_index{0, 0, 0};

  std::int64_t count() const { return std::int64_t{size.x()} * size.y() * size.z(); }
  std::int64_t index(std::int64_t i, std::int64_t j, std::int64_t k) const { return i + size.x() * (j + size.y() * k); }
  Eigen::Vector3d centre(int i, int j, int k) const {
    return origin + spacing.cwiseProduct(Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5));
  }
};

}  // namespace cubespring::voxelize_detail
