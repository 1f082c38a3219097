// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Whether triangles make a closed, consistently oriented surface, and the volume it encloses:
// the cutting tests' checks.
#pragma once

#include <algorithm>
#include <map>
#include <utility>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace cubespring::test {

/// Every edge walked as often one way as the other: no boundary edge, and the triangles on either
/// side of an edge turn alike (an edge where cells meet along an edge only is walked twice each
/// way: non-manifold, a vertex to duplicate, but closed).
inline bool closed_and_oriented(const Eigen::Matrix3Xi& triangles) {
  std::map<std::pair<int, int>, int> walks;  // (a, b) with a < b: +1 for a -> b, -1 for b -> a
  for (Eigen::Index t = 0; t < triangles.cols(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const int a = triangles(k, t), b = triangles((k + 1) % 3, t);
      walks[{std::min(a, b), std::max(a, b)}] += a < b ? 1 : -1;
    }
  }
  return std::all_of(walks.begin(), walks.end(), [](const auto& walk) { return walk.second == 0; });
}

/// The volume the triangles over `vertices` enclose [m^3], by the divergence theorem (positive
/// for a closed surface turned counter-clockwise seen from outside).
inline double enclosed_volume(const Eigen::Matrix3Xd& vertices, const Eigen::Matrix3Xi& triangles) {
  double six_volume = 0.0;
  for (Eigen::Index t = 0; t < triangles.cols(); ++t) {
    six_volume += vertices.col(triangles(0, t)).dot(vertices.col(triangles(1, t)).cross(vertices.col(triangles(2, t))));
  }
  return six_volume / 6.0;
}

}  // namespace cubespring::test
