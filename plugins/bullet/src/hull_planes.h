// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Convex rigid shapes as the planes of a hull, for the exact inside test of polyhedra and the
// sampled one of every other convex shape (docs/bullet-plugin.md, section 2).
#pragma once

#include <vector>

#include <btBulletCollisionCommon.h>
#include <Eigen/Core>

namespace cubespring::bullet {

/// The planes of the convex hull of `points` (in the shape's frame [m]): unit outward normal and
/// offset (n, d) with n . x <= d inside. Empty for fewer than 4 points or a flat set.
std::vector<Eigen::Vector4d> hull_planes(const std::vector<btVector3>& points);

/// How many directions support_points() samples.
constexpr int kSupportDirections = 256;

/// The shape's support points (margin included, as Bullet's own collision sees the shape) in
/// kSupportDirections directions spread evenly over the sphere (a Fibonacci lattice). Their hull
/// is the shape to within r (1 - cos(0.11)), 0.6% of its size r, and never larger than it.
std::vector<btVector3> support_points(const btConvexShape& shape);

}  // namespace cubespring::bullet
