// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Distances from points and segments to surface triangles, and which side of a closed surface a
// point is on (docs/bullet-plugin.md, section 2.6). Lengths in metres.
#pragma once

#include <Eigen/Core>

#include "surface_topology.h"

namespace cubespring::bullet {

/// The barycentric coordinates of the point of triangle (a, b, c) nearest to p. On an edge one of
/// them is exactly 0, at a corner two are (Ericson, Real-Time Collision Detection, 5.1.5).
Eigen::Vector3d closest_barycentric(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                    const Eigen::Vector3d& c);

/// The nearest points of segment p0-p1 and triangle (a, b, c): the segment's at p0 + along (p1 -
/// p0), along in [0, 1], the triangle's at `barycentric`; distance 0 where the segment crosses it.
struct SegmentTriangleClosest {
  double along = 0.0;
  Eigen::Vector3d barycentric{1, 0, 0};
  double distance = 0.0;
};
SegmentTriangleClosest closest_segment_triangle(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                                const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                                const Eigen::Vector3d& c);

/// A point of a surface triangle.
struct SurfacePoint {
  int triangle = 0;
  Eigen::Vector3d barycentric{1, 0, 0};
};

/// The outward unit normal that tells the sides of a closed surface apart at a point of it: the
/// triangle's normal inside it, the sum of both triangles' normals on an edge, the angle-weighted
/// sum of the normals around a corner. A point x whose nearest surface point is `at` is outside
/// when (x - at) . pseudonormal > 0 (Baerentzen and Aanaes, IEEE TVCG 11(3), 2005).
Eigen::Vector3d pseudonormal(const Eigen::Matrix3Xd& positions, const Eigen::Matrix3Xi& triangles,
                             const SurfaceTopology& topology, const SurfacePoint& at);

}  // namespace cubespring::bullet
