// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// How far a point is inside a rigid shape, as the shortest move that takes it out: the contact
// projection of docs/bullet-plugin.md, section 2.
#pragma once

#include <optional>

#include <Eigen/Core>
#include <btBulletCollisionCommon.h>

namespace cubespring::bullet {

/// The move [m] from `point` to the nearest point of the shape's surface when the point is inside
/// the shape or within `tolerance` of its surface from outside (the move is then zero or points
/// outward); nothing when it is clear of the shape. Convex shapes, compounds of them, static
/// planes and concave triangle meshes (one-sided: inside means behind the nearest triangle, less
/// than `thickness` deep). Spheres, boxes, capsules, cylinders and convex polyhedra (hulls) are
/// tested exactly in their own frame; other convex shapes (cones, scaled or user shapes) do not
/// take part in contact yet.
std::optional<Eigen::Vector3d> penetration_push(const btCollisionShape& shape, const btTransform& transform,
                                                const Eigen::Vector3d& point, double tolerance, double thickness);

}  // namespace cubespring::bullet
