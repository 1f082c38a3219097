// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Round tools (spheres, capsules) against the tissue's whole surface, not only its vertices: the
// point of the tool's core that comes nearest the surface, or reaches deepest into the tissue
// (docs/bullet-plugin.md, section 2.6). Lengths in metres.
#pragma once

#include <limits>
#include <optional>
#include <vector>

#include <btBulletCollisionCommon.h>
#include <Eigen/Core>

#include "surface_distance.h"
#include "surface_topology.h"

namespace cubespring::bullet {

/// A round shape as the points within `radius` of a segment: a sphere's is its centre twice, a
/// capsule's its axis, in world coordinates.
struct RoundCore {
  Eigen::Vector3d from{0, 0, 0};
  Eigen::Vector3d to{0, 0, 0};
  double radius = 0.0;
};

/// The core of a sphere or a capsule (along any axis) at `transform`; nothing for other shapes.
std::optional<RoundCore> round_core(const btCollisionShape& shape, const btTransform& transform);

/// Where a core is nearest the tissue's outer surface (the triangles whose `topology.outer` is
/// set), or deepest inside the tissue when it crosses the surface.
struct CoreContact {
  SurfacePoint surface;                 ///< the surface's point nearest `core_point`
  Eigen::Vector3d core_point{0, 0, 0};  ///< on the core's segment
  double signed_distance = 0.0;         ///< from the surface to core_point, < 0 inside the tissue
  Eigen::Vector3d normal{0, 0, 0};      ///< the tissue's outward unit normal there, toward the core
};

/// The outer triangles (those whose `topology.outer` is set) whose bounding boxes come within
/// `reach` of the core's, in ascending order; looked for among `among` (ascending) when given,
/// else among all (only their positions are read).
std::vector<int> outer_triangles_near(const RoundCore& core, const Eigen::Matrix3Xd& positions,
                                      const Eigen::Matrix3Xi& triangles, const SurfaceTopology& topology, double reach,
                                      const std::vector<int>* among = nullptr);

/// The places where a core meets the surface, among the triangles `candidates`: when the core is
/// outside the tissue, the nearest point of every feature (a triangle's inside, an edge, a
/// corner) within `reach` of it that faces it, the nearest of all first (also when farther than
/// `reach`); when the core is inside or crosses the surface, only its deepest point. Empty when
/// there is no candidate.
///
/// `believed_depth` [m]: a verdict that the core is inside deeper than this is not believed, and
/// the core is taken as outside. Where the surface folds around a thin tool its walls cross, and
/// the pseudonormal of the nearest point can point the wrong way; a core that was outside a moment
/// ago cannot be a radius deep now (the caller knows how far it moved). Infinity believes all.
std::vector<CoreContact> core_contacts(const RoundCore& core, const Eigen::Matrix3Xd& positions,
                                       const Eigen::Matrix3Xi& triangles, const SurfaceTopology& topology,
                                       const std::vector<int>& candidates, double reach,
                                       double believed_depth = std::numeric_limits<double>::infinity());

}  // namespace cubespring::bullet
