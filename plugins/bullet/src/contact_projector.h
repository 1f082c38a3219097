// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Contacts between a soft body's surface and rigid bodies, one sub-step's worth
// (docs/bullet-plugin.md, section 2): found in contact_projector.cpp, solved in contact_sweeps.cpp.
#pragma once

#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "cubespring/bullet/soft_body.h"
#include "rigid_distance.h"
#include "rigid_track.h"
#include "round_tool_contact.h"
#include "surface_window.h"

namespace cubespring::bullet {

// Contacts between a soft body's surface and one rigid body at a time: every surface point inside
// it is moved out, which changes no momentum, and the two exchange an inelastic impulse along the
// normal that stops the point's approach and, within Coulomb's cone, a tangential one that stops
// its sliding, through their effective masses. The points of a pass are resolved together, by
// projected Gauss-Seidel (apply_points). The rigid track takes the opposite of what the tissue took.
class ContactProjector {
 public:
  explicit ContactProjector(SoftBody& body);
  /// The revision of the body's model it was made for: a cut body has a new one, and the
  /// projector's per-node and per-vertex buffers are then another body's.
  std::uint64_t model_revision() const { return model_revision_; }

  /// After the lattice's step: refreshes the surface where `tracks` may touch it (the window), or
  /// all of it when the window no longer holds, and chooses it again.
  void refresh_surface(const std::vector<RigidTrack>& tracks);

  /// Every surface vertex inside a rigid shape of `tracks`, then (with face contacts) every
  /// triangle a convex tool reaches through between its corners.
  void resolve(std::vector<RigidTrack>& tracks);

  /// How deep the body's surface reaches into the track's shape [m] (ContactWrench::penetration),
  /// after resolve(): a round tool's inside verdicts are weighed as resolve() weighed them.
  double penetration(const RigidTrack& track) const;

 private:
  // A contact point as a weighted sum of nodes (point_nodes_[first_node .. end_node)).
  struct ContactPoint {
    Eigen::Vector3d push{0, 0, 0};     // the move that takes it out of the rigid body [m]
    Eigen::Vector3d contact{0, 0, 0};  // where it touches [m]
    Eigen::Vector3d normal{0, 0, 0};   // of the push
    double lift = 0.0;                 // the projection's multiplier so far [kg m]
    Eigen::Vector3d impulse{0, 0, 0};  // the tissue's impulse at it so far [N s]
    double inverse_mass = 0.0;         // [1/kg]
    int key = -1;                      // where its impulse is kept for the next sub-step: the
                                       // surface vertex of a vertex point, the triangle of a box
                                       // edge's; -1: not kept
    double share = 0.0;                // the weights on the nodes it moves, summed: an impulse J
                                       // there gives them the momentum share J
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
  // The rigid body's box edges pushed out of the triangles they reach through between corners
  // that the vertex contacts left on the box's faces, less than `thickness` behind them.
  void resolve_box_edges(RigidTrack& track, double thickness, const std::vector<char>& held);
  // The window's part for the body `object` refreshed, for a test that reads all of it.
  void freshen_part(const void* object);
  // The corners of the triangles around vertex v refreshed (its normal reads them).
  void freshen_triangles_around(int v);
  // Where a triangle must reach to be tested for face contacts with the track's shape: around the
  // points of it that can reach through a triangle (face_penetration_points) that are near the
  // window, or its bounding box, grown by the face contacts' depth and offset. Empty: none.
  Eigen::AlignedBox3d face_test_region(const RigidTrack& track, const ContactReach& face_reach) const;
  void add_vertex_point(int vertex, const Eigen::Vector3d& push);
  void add_face_point(int triangle, const Eigen::Vector3d& barycentric, const Eigen::Vector3d& push);
  ContactPoint& new_point(const Eigen::Vector3d& push);
  void add_vertex(ContactPoint& point, int vertex, double scale);
  // The impulses a rigid body's vertex points (or box-edge points) took in the last sub-step, by
  // their key (surface vertex, or triangle): each starts the next sub-step's sweeps from it (warm
  // start), as a resting contact needs about the same impulse every sub-step.
  // The projection's multipliers (lifts) are kept the same way: a resting contact is pressed in
  // by about the same depth every sub-step, and from zero the sweeps never reached their tolerance.
  struct LastImpulses {
    std::vector<Eigen::Vector3d> by_key;  // [N s], zero where no point was
    std::vector<double> lift_by_key;      // [kg m], zero where no point was
    std::vector<int> keys;                // where either is not zero
    bool seen = false;                    // in the current resolve()
    void resize(std::size_t size);
  };
  // count: whether the points count as contacts of the sub-step (RigidTrack::substep_contacts);
  // last: the track's impulses of the last sub-step, for vertex points
  void apply_points(RigidTrack& track, bool count = true, LastImpulses* last = nullptr);
  // A pass whose points start at `from`: the points before them are an earlier pass against the
  // same body, already solved; the impulses of both are then swept together.
  void solve_points(RigidTrack& track, std::size_t from, bool count, const LastImpulses* last);
  // Keeps the impulses of the points [from, to) in `last`, and only those.
  void remember(LastImpulses& last, std::size_t from, std::size_t to) const;
  // The parts of a pass, on the points from `from` on: each point's inverse mass, contact point
  // and normal; the positions' sweeps; the velocities' sweeps, started from `last`.
  void prepare_points(RigidTrack& track, bool count, std::size_t from);
  void project_positions(std::size_t from, const LastImpulses* last);
  void resolve_impulses(RigidTrack& track, const LastImpulses* last, std::size_t from);
  bool movable(int node, double weight) const;
  // A point's weighted sum of a per-node field (positions, velocities), and a change of it given
  // to the point's movable nodes as a mass-weighted share of `change` (a move times W, an impulse).
  Eigen::Vector3d at_point(const ContactPoint& point, const Eigen::Matrix3Xd& field) const;
  void move_nodes(const ContactPoint& point, Eigen::Matrix3Xd& field, const Eigen::Vector3d& change) const;
  // Two fields in one pass over the point's nodes (velocities and positions).
  void move_nodes(const ContactPoint& point, Eigen::Matrix3Xd& field, const Eigen::Vector3d& change,
                  Eigen::Matrix3Xd& second_field, const Eigen::Vector3d& second_change) const;

  // Where a round tool's core was at the end of the last sub-step, whether it was outside the
  // tissue then, and how far the surface was from it when last measured: an inside verdict deeper
  // than the core and the surface can have come together since is a fold's sign error.
  struct LastCore {
    Eigen::Vector3d from{0, 0, 0};
    Eigen::Vector3d to{0, 0, 0};
    bool outside = false;
    double clearance = 0.0;  // the nearest surface point's distance from the core then [m]
    double travel = 0.0;     // surface_travel_ then [m]
    bool seen = false;       // in the current resolve()
  };

  // Where each track's contacts may reach the surface, for the window.
  std::vector<ContactBox> contact_boxes(const std::vector<RigidTrack>& tracks) const;
  // The whole surface refreshed and the window chosen again around `boxes`.
  void choose_window(const std::vector<ContactBox>& boxes);
  // After a pass moved nodes: their vertices refreshed, the window kept valid.
  void refresh_moved();

  SoftBody& body_;
  std::uint64_t model_revision_ = 0;
  SurfaceWindow window_;
  // The surface's odometer: the farthest any vertex a round tool reads moved, summed over every
  // refresh of them [m]. No vertex near a round tool has moved farther than the difference of two
  // readings.
  double surface_travel_ = 0.0;
  // The window's vertices that round tools read, refreshed whole every sub-step and after every
  // pass (ascending; and flagged per surface vertex); the rest are refreshed when a test reads them.
  std::vector<int> whole_read_vertices_;
  std::vector<char> whole_read_;
  std::vector<ContactPoint> points_;              // this pass's contacts
  std::vector<Eigen::Vector3d> impulses_before_;  // resolve_impulses(): the points' impulses before it
  // A node of a contact point, its weight there, and what a change at the point gives it per unit
  // (weight / mass for a movable node, else 0), set by prepare_points().
  struct PointNode {
    int node = 0;
    double weight = 0.0;
    double share_per_mass = 0.0;  // [1/kg]
  };
  std::vector<PointNode> point_nodes_;
  std::map<const btCollisionObject*, LastImpulses> last_impulses_;
  std::map<const btCollisionObject*, LastImpulses> last_edge_impulses_;  // of box-edge points
  std::map<const btCollisionObject*, LastCore> last_cores_;
};

}  // namespace cubespring::bullet
