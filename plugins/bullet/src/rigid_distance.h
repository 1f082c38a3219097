// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// How far a point is inside a rigid shape, as the shortest move that takes it out: the contact
// projection of docs/bullet-plugin.md, section 2.
#pragma once

#include <optional>
#include <vector>

#include <btBulletCollisionCommon.h>
#include <Eigen/Core>

namespace cubespring::bullet {

/// How far around a rigid surface contact acts [m].
struct ContactReach {
  /// The surface is taken this far outside the shape: a skin that keeps the tissue off it.
  double offset = 0.0;
  /// One-sided surfaces (triangle meshes, and surface triangles in face_penetration): how deep
  /// behind them a point is still taken as inside and pushed out.
  double thickness = 0.0;
  /// Flat-faced shapes: how much farther than its nearest face the face the tissue presses on
  /// may be (0: always the nearest face).
  double detour = 0.0;
};

/// The tissue's outward unit normal at the point penetration_push() tests, worked out only when
/// asked for: a flat-faced shape needs it only where two of its faces are about equally near (at
/// an edge), and working it out for every vertex resting on a table took longer than the test.
class SurfaceNormal {
 public:
  /// A normal known beforehand (zero: unknown, then the nearest face is taken).
  SurfaceNormal(const Eigen::Vector3d& normal) : normal_(normal) {}  // NOLINT(google-explicit-constructor)

  /// A normal worked out by `compute()` when first asked for; `compute` must outlive the result.
  template <class Compute>
  static SurfaceNormal when_asked(const Compute& compute) {
    SurfaceNormal normal(Eigen::Vector3d::Zero());
    normal.context_ = &compute;
    normal.compute_ = [](const void* context) -> Eigen::Vector3d { return (*static_cast<const Compute*>(context))(); };
    return normal;
  }
  /// (a temporary would be gone before the normal is asked for)
  template <class Compute>
  static SurfaceNormal when_asked(const Compute&& compute) = delete;

  const Eigen::Vector3d& get() const {
    if (compute_ != nullptr) {
      normal_ = compute_(context_);
      compute_ = nullptr;
    }
    return normal_;
  }

 private:
  mutable Eigen::Vector3d normal_;
  const void* context_ = nullptr;
  mutable Eigen::Vector3d (*compute_)(const void*) = nullptr;
};

/// The move [m] from `point` to the nearest point of the shape's surface, grown by reach.offset,
/// when the point is inside it (or on it: the move is then zero); nothing when it is clear of the
/// shape. For flat-faced shapes (boxes,
/// cylinders, hulls) the face is the one the tissue presses on, found by the tissue's outward
/// unit normal `surface_normal` at the point (zero: unknown, then the nearest face); the move is
/// the shortest out through that face, if it is at most reach.detour farther than the nearest
/// face (else the nearest: docs/bullet-plugin.md, section 2.2). Convex shapes,
/// compounds of them, static planes and concave triangle meshes (one-sided: inside means behind
/// the nearest triangle, less than reach.thickness deep). Spheres, boxes, capsules, cylinders and
/// convex polyhedra (hulls) are tested exactly in their own frame, grown by the offset face by
/// face (a grown box keeps its sharp corners); every other convex shape (cones, multi-spheres,
/// scaled or user shapes) against the hull of its support points (hull_planes.h).
std::optional<Eigen::Vector3d> penetration_push(const btCollisionShape& shape, const btTransform& transform,
                                                const Eigen::Vector3d& point, const SurfaceNormal& surface_normal,
                                                const ContactReach& reach);

/// How far outside the shape's bounding box (Bullet's getAabb) penetration_push() may still find
/// a point inside [m]: reach.offset for solid shapes, and reach.thickness more where a part is
/// one-sided (a triangle mesh, a plane), whose inside lies behind its triangles.
double push_reach_beyond_bounds(const btCollisionShape& shape, const ContactReach& reach);

/// A convex part of a rigid shape reaching through a surface triangle from outside: the point of
/// the shape deepest behind the triangle's plane lies over the triangle. Vertex tests alone would
/// let a tool tip thinner than a triangle pass between its corners.
struct FacePenetration {
  Eigen::Vector3d barycentric;  ///< of the deepest point's foot on the triangle
  double depth = 0.0;           ///< behind the plane [m], > 0
};

/// The deepest convex child of a shape, grown by reach.offset, through triangle (a, b, c)
/// (counter-clockwise from outside), when less than reach.thickness deep; nothing for planes and
/// concave meshes, which vertex tests cover.
std::optional<FacePenetration> face_penetration(const btCollisionShape& shape, const btTransform& transform,
                                                const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                                const Eigen::Vector3d& c, const ContactReach& reach);

/// The points of a shape that face_penetration() can find reaching through a triangle, when they
/// are few: a box's 8 corners (its support points) [m]; nothing for other shapes (any point). Such
/// a point is within reach.offset + reach.thickness of the triangle it reaches through, so a box
/// whose corners are all far from the surface (a table under an organ) has no triangle to test.
std::optional<std::vector<Eigen::Vector3d>> face_penetration_points(const btCollisionShape& shape,
                                                                    const btTransform& transform);

/// A straight edge of a rigid shape, in the world frame [m].
struct RigidEdge {
  Eigen::Vector3d from{0, 0, 0};
  Eigen::Vector3d to{0, 0, 0};
};

/// The edges of a shape's boxes (a box, or a compound's boxes; none for other shapes), each box
/// grown by `offset` face by face as penetration_push() grows it, so its edges stay sharp.
std::vector<RigidEdge> box_edges(const btCollisionShape& shape, const btTransform& transform, double offset);

/// A rigid edge reaching through surface triangle (a, b, c) (counter-clockwise from outside)
/// between its corners, less than `thickness` [m] behind its plane: the edge's deepest point
/// behind the plane among its points over the triangle. Vertex contacts leave such an edge alone
/// (the corners lie on its two faces), and face_penetration() misses it where the shape's deepest
/// point lies elsewhere: a 200 g box on slippery 5 kPa tissue, an edge down, cut between the
/// vertices through 5 cm of tissue to the ground and blew it up.
std::optional<FacePenetration> edge_penetration(const RigidEdge& edge, const Eigen::Vector3d& a,
                                                const Eigen::Vector3d& b, const Eigen::Vector3d& c, double thickness);

}  // namespace cubespring::bullet
