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
#include "round_tool_contact.h"

namespace cubespring::bullet {

// Contacts between a soft body's surface and one rigid body at a time: every surface point inside
// it is moved out, which changes no momentum, and the two exchange an inelastic impulse along the
// normal that stops the point's approach and, within Coulomb's cone, a tangential one that stops
// its sliding, through their effective masses. The points of a pass are resolved together: a
// node reached by several takes the weighted mean of their corrections (apply_points). The
// rigid track takes the opposite of what the tissue took.
class ContactProjector {
 public:
  explicit ContactProjector(SoftBody& body) : body_(body) {}

  /// Every surface vertex inside a rigid shape of `tracks`, then (with face contacts) every
  /// triangle a convex tool reaches through between its corners.
  void resolve(std::vector<RigidTrack>& tracks);

  /// How deep the body's surface reaches into the track's shape [m] (ContactWrench::penetration).
  static double penetration(const SoftBody& body, const RigidTrack& track);

 private:
  // A contact point as a weighted sum of nodes (point_nodes_[first_node .. end_node)).
  struct ContactPoint {
    Eigen::Vector3d push{0, 0, 0};      // the move that takes it out of the rigid body [m]
    Eigen::Vector3d contact{0, 0, 0};   // where it touches [m]
    Eigen::Vector3d impulse{0, 0, 0};   // the impulse it would take on its own [N s]
    double inverse_mass = 0.0;          // [1/kg]
    int first_node = 0, end_node = 0;
  };

  // Per surface vertex, 1 where every node it is embedded in is anchored to `object`: such a
  // vertex moves with the body that holds it and is not pushed out of it (the anchor's spring
  // pulled it back in, and the two fought, pumping energy into the tissue). Empty when no anchor
  // holds the soft body to `object`.
  std::vector<char> vertices_held_by(const btCollisionObject* object) const;
  // The one point where a round tool's core is nearest the surface (or deepest inside it) is
  // pushed to the tool's surface along the tissue's normal there.
  void resolve_round_tool(RigidTrack& track, const RoundCore& core, const std::vector<char>& held);
  void add_vertex_point(int vertex, const Eigen::Vector3d& push);
  void add_face_point(int triangle, const Eigen::Vector3d& barycentric, const Eigen::Vector3d& push);
  ContactPoint& new_point(const Eigen::Vector3d& push);
  void add_vertex(ContactPoint& point, int vertex, double scale);
  // count: whether the points count as contacts of the sub-step (RigidTrack::substep_contacts)
  void apply_points(RigidTrack& track, bool count = true);

  SoftBody& body_;
  std::vector<ContactPoint> points_;               // this pass's contacts
  std::vector<std::pair<int, double>> point_nodes_;
  std::vector<double> node_weight_;                // per node: the points' weights on it, summed
  Eigen::Matrix3Xd node_position_, node_velocity_;  // per node: the points' corrections, weighted
  std::vector<int> moved_nodes_;                   // the nodes some point reaches
};

}  // namespace cubespring::bullet
