// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The part of a soft body's contact surface near the rigid bodies it may touch: the only vertices a
// sub-step's contacts read and test (docs/bullet-plugin.md, section 2.1). An organ resting on a
// table and pressed by a probe touches them with a small part of its surface; refreshing and
// testing all of it every sub-step took a quarter of the default scene's physics.
#pragma once

#include <vector>

#include <Eigen/Geometry>

#include "surface_topology.h"

namespace cubespring::bullet {

/// Where a rigid body may meet the surface: its bounding box [m] grown by `reach` [m], the
/// farthest beyond the box that any contact test looks.
struct ContactBox {
  const void* object = nullptr;  ///< which body, to match the boxes of one choice to the next
  Eigen::AlignedBox3d box;
  double reach = 0.0;
  /// Whether the body's tests read its whole part at once (a round tool's triangles), so that the
  /// part is refreshed whole every sub-step; else each vertex is refreshed as a test reads it.
  bool read_whole = false;
};

/// Chosen from fresh surface positions, the window holds while no node has moved, and no box has
/// grown past its box then, by more than the margin in all: a vertex or a triangle outside the
/// window then cannot have come within reach of a box. It is chosen with room around the boxes,
/// so that a choice lasts many sub-steps; the vertices and triangles are in ascending order, so
/// that a loop over them meets the near ones in the order a loop over all would.
class SurfaceWindow {
 public:
  /// `spread`: the most a vertex moves per unit of node motion (the sum of its weights' magnitudes,
  /// the largest over the surface: 1 where every weight is >= 0).
  SurfaceWindow(double margin, double spread) : margin_(margin), spread_(spread) {}

  /// Chooses the vertices and triangles within reach plus the margin of the boxes, the triangles
  /// around the chosen vertices and around the corners of the chosen triangles (a vertex's normal
  /// and a corner's pseudonormal read them), and every corner of those.
  void choose(const Eigen::Matrix3Xd& nodes, const Eigen::Matrix3Xd& vertices, const Eigen::Matrix3Xi& triangles,
              const SurfaceTopology& topology, const std::vector<ContactBox>& boxes);

  /// Counts how far the nodes have moved since the choice: all of them, or the listed ones.
  void note_moved(const Eigen::Matrix3Xd& nodes);
  void note_moved(const Eigen::Matrix3Xd& nodes, const std::vector<int>& which);

  /// Whether the choice still holds for these boxes (the same bodies, read the same way, in any
  /// order).
  bool holds(const std::vector<ContactBox>& boxes) const;

  bool chosen() const { return chosen_; }
  const std::vector<int>& vertices() const { return vertices_; }
  const std::vector<int>& triangles() const { return triangles_; }
  /// The vertices and triangles the choice took for the box of `object` alone (ascending, each a
  /// subset of vertices() and triangles()): a contact test against that body needs no other.
  /// Empty when no box of the choice is the object's.
  const std::vector<int>& vertices_near(const void* object) const;
  const std::vector<int>& triangles_near(const void* object) const;
  /// The boxes of the current choice.
  const std::vector<ContactBox>& boxes() const { return boxes_; }
  /// How far any surface vertex may have moved since the choice [m]: the spread times the farthest
  /// any node has moved (note_moved). A test that a vertex cannot pass from where it was then
  /// (chosen_position) grown by this needs no fresh position of it.
  double vertex_travel() const { return spread_ * moved_; }
  /// Where vertex v was at the choice [m].
  Eigen::Vector3d chosen_position(int v) const { return chosen_vertices_.col(v); }
  /// The bounds of vertices_near(object) wherever they have moved since the choice [m]: their
  /// bounds then grown by vertex_travel(). Empty when no box of the choice is the object's.
  Eigen::AlignedBox3d bounds_near(const void* object) const;

 private:
  double margin_;
  double spread_;
  bool chosen_ = false;
  Eigen::Matrix3Xd chosen_nodes_;
  Eigen::Matrix3Xd chosen_vertices_;
  std::vector<ContactBox> boxes_;
  double moved_ = 0.0;  // the farthest any node has moved since the choice [m]
  std::vector<int> vertices_;
  std::vector<int> triangles_;
  std::vector<std::vector<int>> box_vertices_;   // per box of boxes_
  std::vector<std::vector<int>> box_triangles_;  // per box of boxes_
  std::vector<Eigen::AlignedBox3d> box_bounds_;  // per box of boxes_: its vertices' bounds at the choice
  std::size_t box_of(const void* object) const;  // boxes_.size() when none
};

}  // namespace cubespring::bullet
