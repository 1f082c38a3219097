// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The inside test along the grid axes (docs/voxelize.md, section 3): every row of samples along an
// axis is one ray; its signed crossings with the surface, counted exactly, give the winding number
// of each sample of the row, or no answer when the row passes through a hole.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "voxelize/sample_grid.h"

namespace cubespring::voxelize_detail {

/// Votes of the three axes for each sample (one byte each, to keep big grids small).
struct AxisVotes {
  std::vector<std::uint8_t> inside;   ///< axes whose ray puts the sample inside
  std::vector<std::uint8_t> abstain;  ///< axes whose ray passed through a hole
  explicit AxisVotes(std::int64_t samples)
      : inside(static_cast<std::size_t>(samples), 0), abstain(static_cast<std::size_t>(samples), 0) {}
  int outside(std::int64_t s) const {
    return 3 - inside[static_cast<std::size_t>(s)] - abstain[static_cast<std::size_t>(s)];
  }
};

/// Adds the votes of rays along `axis` for the triangles (3 x count vertex indices, oriented
/// outward). A sample is inside when its winding number is not zero.
void cast_axis_rays(const Eigen::Matrix3Xd& vertices, const Eigen::Matrix3Xi& triangles, const SampleGrid& grid,
                    int axis, AxisVotes& votes);

}  // namespace cubespring::voxelize_detail
