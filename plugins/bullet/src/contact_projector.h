// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Contacts between a soft body's surface and rigid bodies, one sub-step's worth
// (docs/bullet-plugin.md, section 2).
#pragma once

#include <utility>
#include <vector>

#include <Eigen/Core>

#include "cubespring/bullet/soft_body.h"
#include "rigid_track.h"

namespace cubespring::bullet {

// One contact between a surface point and a rigid body: the point is moved out of the body,
// which changes no momentum, then the two exchange an inelastic impulse along the normal that
// stops their approach and, within Coulomb's cone, a tangential one that stops their sliding,
// both through their effective masses. The rigid track takes the opposite impulse at once, so
// that the next contact against the same body sees its new velocity.
class ContactProjector {
 public:
  explicit ContactProjector(SoftBody& body) : body_(body) {}

  /// Every surface vertex inside a rigid shape of `tracks`, then (with face contacts) every
  /// triangle a convex tool reaches through between its corners.
  void resolve(std::vector<RigidTrack>& tracks);

  /// A contact at surface vertex v; returns the impulse given to the tissue [N s].
  Eigen::Vector3d apply_vertex(int vertex, const Eigen::Vector3d& push, RigidTrack& track);
  /// A contact at a point of a surface triangle, by its barycentric coordinates.
  Eigen::Vector3d apply_face(int triangle, const Eigen::Vector3d& barycentric, const Eigen::Vector3d& push,
                             RigidTrack& track);

 private:
  // Per surface vertex, 1 where every node it is embedded in is anchored to `object`: such a
  // vertex moves with the body that holds it and is not pushed out of it (the anchor's spring
  // pulled it back in, and the two fought, pumping energy into the tissue). Empty when no anchor
  // holds the soft body to `object`.
  std::vector<char> vertices_held_by(const btCollisionObject* object) const;
  void add_vertex(int vertex, double scale);
  Eigen::Vector3d apply(const Eigen::Vector3d& push, RigidTrack& track);

  SoftBody& body_;
  std::vector<std::pair<int, double>> nodes_;  // the contact point as a weighted sum of nodes
};

}  // namespace cubespring::bullet
