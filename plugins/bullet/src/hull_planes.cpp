// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "hull_planes.h"

#include <algorithm>
#include <cmath>

#include <LinearMath/btConvexHullComputer.h>

#include "cubespring/bullet/conversions.h"

namespace cubespring::bullet {

std::vector<Eigen::Vector4d> hull_planes(const std::vector<btVector3>& points) {
  if (points.size() < 4) return {};
  btConvexHullComputer hull;
  hull.compute(&points[0].getX(), sizeof(btVector3), static_cast<int>(points.size()), 0, 0);
  // faces are turned away from the hull's centroid: the hull computer's face order is not
  // documented, the centroid is unambiguous
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (int v = 0; v < hull.vertices.size(); ++v) centroid += to_eigen(hull.vertices[v]);
  centroid /= std::max(1, hull.vertices.size());
  std::vector<Eigen::Vector4d> planes;
  for (int f = 0; f < hull.faces.size(); ++f) {
    const btConvexHullComputer::Edge* edge = &hull.edges[hull.faces[f]];
    const Eigen::Vector3d a = to_eigen(hull.vertices[edge->getSourceVertex()]);
    const Eigen::Vector3d b = to_eigen(hull.vertices[edge->getTargetVertex()]);
    const Eigen::Vector3d c = to_eigen(hull.vertices[edge->getNextEdgeOfFace()->getTargetVertex()]);
    Eigen::Vector3d normal = (b - a).cross(c - a);
    if (normal.squaredNorm() == 0.0) continue;
    normal.normalize();
    if (normal.dot(a - centroid) < 0.0) normal = -normal;
    planes.emplace_back(normal.x(), normal.y(), normal.z(), normal.dot(a));
  }
  return planes;
}

std::vector<btVector3> support_points(const btConvexShape& shape) {
  constexpr double kGoldenAngle = 2.39996322972865332;  // pi (3 - sqrt 5)
  std::vector<btVector3> points;
  points.reserve(kSupportDirections);
  for (int k = 0; k < kSupportDirections; ++k) {
    const double z = 1.0 - (2.0 * k + 1.0) / kSupportDirections;
    const double ring = std::sqrt(1.0 - z * z);
    const double angle = kGoldenAngle * k;
    const btVector3 direction(static_cast<btScalar>(ring * std::cos(angle)),
                              static_cast<btScalar>(ring * std::sin(angle)), static_cast<btScalar>(z));
    points.push_back(shape.localGetSupportingVertex(direction));
  }
  return points;
}

}  // namespace cubespring::bullet
