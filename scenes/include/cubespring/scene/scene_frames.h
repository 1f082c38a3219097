// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Pictures of a running scene: the organ's visual surface (coloured by how far it moved since
// t = 0 or by its strain, with a legend), the tools, the table, optionally the lattice.
#pragma once

#include <memory>

#include <vector>

#include <Eigen/Core>

#include "cubespring/render/renderer.h"
#include "cubespring/result.h"
#include "cubespring/scene/scene.h"
#include "cubespring/scene/scene_world.h"

namespace cubespring::scene {

class SceneFrames {
 public:
  static Result<SceneFrames> create(const Scene& scene);

  /// The organ surface's vertices now [m].
  static Eigen::Matrix3Xd organ_vertices(SceneWorld& world);
  /// The organ surface's vertices with its lattice nodes at `organ_positions` (3 x nodes) [m].
  static Eigen::Matrix3Xd organ_vertices(SceneWorld& world, const Eigen::Matrix3Xd& organ_positions);
  /// Where displacement is measured from (the surface at t = 0) [m].
  void set_rest(const Eigen::Matrix3Xd& rest_vertices) { rest_vertices_ = rest_vertices; }
  /// After a cut changed the organ's surface (bullet::SoftBody::Cut::visual_vertex_source): each
  /// vertex kept keeps where its displacement is measured from; a vertex the cut made measures
  /// from where it is now, `vertices` [m].
  void carry_rest(const std::vector<int>& vertex_source, const Eigen::Matrix3Xd& vertices);

  /// The scene as it is, tools at time t [s].
  Result<Image> render(SceneWorld& world, double t);
  /// The scene with the organ's lattice nodes at `organ_positions` (3 x nodes, a copy of its state
  /// taken at time t) [m] and the tools at time t [s]. It reads only what a step does not change
  /// (the organ's model, embedding and mesh, the tools' meshes and key frames), so it may draw on
  /// another thread while `world` steps on (the frames of `cubespring run` do).
  Result<Image> render(SceneWorld& world, const Eigen::Matrix3Xd& organ_positions, double t);

 private:
  SceneFrames(Renderer renderer, const Scene& scene);
  /// The organ's surface at `vertices`, coloured as the scene says, with its legend.
  Status draw_organ(SceneWorld& world, const Eigen::Matrix3Xd& organ_positions, const Eigen::Matrix3Xd& vertices);

  Renderer renderer_;
  RenderSpec spec_;
  Eigen::Matrix3Xd rest_vertices_;
  Eigen::Matrix3Xd organ_normals_scratch_;
};

}  // namespace cubespring::scene
