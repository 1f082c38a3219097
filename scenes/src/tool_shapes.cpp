// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "tool_shapes.h"

#include <cmath>
#include <vector>

namespace cubespring::scene {

TriangleMesh capsule_mesh(double radius, double length, int around, int cap_rings) {
  constexpr double kPi = 3.14159265358979323846;
  // rings from the tip up: the lower cap's rings, then the upper cap's, as (height, ring radius)
  std::vector<std::pair<double, double>> rings;
  for (int i = 1; i <= cap_rings; ++i) {
    const double angle = -0.5 * kPi + 0.5 * kPi * i / cap_rings;  // -90 deg (tip) .. 0 (equator)
    rings.emplace_back(radius + radius * std::sin(angle), radius * std::cos(angle));
  }
  for (int i = 0; i < cap_rings; ++i) {
    const double angle = 0.5 * kPi * i / cap_rings;  // 0 (equator) .. below 90 deg (top pole)
    rings.emplace_back(length - radius + radius * std::sin(angle), radius * std::cos(angle));
  }
  const int ring_count = static_cast<int>(rings.size());
  TriangleMesh mesh;
  mesh.vertices.resize(3, 2 + ring_count * around);
  mesh.vertices.col(0) = Eigen::Vector3d(0, 0, 0);
  for (int r = 0; r < ring_count; ++r) {
    for (int a = 0; a < around; ++a) {
      const double phi = 2.0 * kPi * a / around;
      mesh.vertices.col(1 + r * around + a) =
          Eigen::Vector3d(rings[r].second * std::cos(phi), rings[r].second * std::sin(phi), rings[r].first);
    }
  }
  const int top = 1 + ring_count * around;
  mesh.vertices.col(top) = Eigen::Vector3d(0, 0, length);

  std::vector<Eigen::Vector3i> triangles;
  const auto at = [around](int ring, int a) { return 1 + ring * around + (a % around); };
  for (int a = 0; a < around; ++a) triangles.emplace_back(0, at(0, a + 1), at(0, a));  // seen from below
  for (int r = 0; r + 1 < ring_count; ++r) {
    for (int a = 0; a < around; ++a) {
      triangles.emplace_back(at(r, a), at(r, a + 1), at(r + 1, a + 1));
      triangles.emplace_back(at(r, a), at(r + 1, a + 1), at(r + 1, a));
    }
  }
  for (int a = 0; a < around; ++a) triangles.emplace_back(top, at(ring_count - 1, a), at(ring_count - 1, a + 1));
  mesh.triangles.resize(3, static_cast<Eigen::Index>(triangles.size()));
  for (std::size_t t = 0; t < triangles.size(); ++t) mesh.triangles.col(static_cast<Eigen::Index>(t)) = triangles[t];
  mesh.parts.push_back({"capsule", "", 0, mesh.num_triangles()});
  return mesh;
}

}  // namespace cubespring::scene
