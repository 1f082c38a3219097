// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// A scene made physical: the organ as a cubespring soft body in a Bullet world, the table as a
// static box, the tools as kinematic bodies that follow their key frames.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <btBulletDynamicsCommon.h>
#include <Eigen/Geometry>

#include "cubespring/bullet/world.h"
#include "cubespring/result.h"
#include "cubespring/scene/scene.h"
#include "cubespring/triangle_mesh.h"

namespace cubespring::scene {

struct SceneTool {
  std::string name;
  std::vector<Keyframe> keyframes;
  TriangleMesh mesh;  ///< in the tool's frame (tip at the origin), for drawing
  Eigen::Isometry3d shape_offset = Eigen::Isometry3d::Identity();  ///< collision body in the tool's frame
  std::unique_ptr<btCollisionShape> shape;
  std::unique_ptr<btRigidBody> body;  ///< kinematic, unless the caller took the tool
  bool scripted = true;               ///< place_tools() moves it (false once taken: take_tool())
  /// A cautery tool (ToolSpec::cut): its capsule's radius and length [m], and the organ's cells
  /// it has burnt away so far.
  std::optional<CutSpec> cut;
  double radius = 0.0, length = 0.0;
  int cells_removed = 0;
};

/// The organ's cells one cutting tool reaches after a step (SceneWorld::cuts_due()).
struct ToolCut {
  std::size_t tool = 0;  ///< index into SceneWorld::tools()
  std::vector<int> cells;
};

/// What the organ became, for the log.
struct OrganSummary {
  int cells = 0;
  int nodes = 0;
  int fixed_nodes = 0;
  double cell_size = 0.0;          ///< [m]
  double sub_step = 0.0;           ///< the soft body's sub-step [s]
  std::vector<std::string> notes;  ///< e.g. parts that took the default tissue
};

class SceneWorld {
 public:
  /// Loads and voxelizes the organ, builds every body and puts the tools at their t = 0 poses.
  /// Errors name the scene file and key at fault where a key is at fault.
  static Result<std::unique_ptr<SceneWorld>> create(const Scene& scene);
  ~SceneWorld();
  SceneWorld(const SceneWorld&) = delete;
  SceneWorld& operator=(const SceneWorld&) = delete;

  /// Moves every scripted tool to its pose at time t [s] (kinematic: Bullet derives its velocity).
  void place_tools(double t);
  /// Hands the tool of that name over to the caller (a haptic device drives it): place_tools()
  /// leaves it where the caller puts it from then on. Null when there is no such tool.
  SceneTool* take_tool(const std::string& name);
  /// One Bullet step of dt [s] with the tools already placed at the step's end; an error when the
  /// organ went unstable.
  Status step(double dt);

  /// The organ's cells each cutting tool reaches now: within its radius plus three quarters of a
  /// cell of its capsule's axis (cell centres, the mean of their nodes), while the force on it is
  /// at least its threshold; tools that reach none are left out. Read after step().
  std::vector<ToolCut> cuts_due() const;
  /// Takes those cells out of the organ (bullet::SoftBody::remove_cells: its surface clipped and
  /// capped) and counts each to the first tool that reached it. Nothing that reads the organ may
  /// run meanwhile (a frame being drawn): its model, embedding and state change size.
  Result<bullet::SoftBody::Cut> apply_cuts(const std::vector<ToolCut>& cuts);

  bullet::World& world() { return *world_; }
  bullet::SoftBody& organ() { return *organ_; }
  /// The organ's mesh as loaded (the surface drawn is organ().embedding(), which a cut changes).
  const TriangleMesh& organ_mesh() const { return organ_mesh_; }
  const std::vector<SceneTool>& tools() const { return tools_; }
  const OrganSummary& summary() const { return summary_; }
  /// The world pose of a tool's frame now.
  Eigen::Isometry3d tool_pose(const SceneTool& tool) const;

 private:
  SceneWorld();
  Status build_organ(const Scene& scene);
  Status build_table(const Scene& scene);
  Status build_tools(const Scene& scene);

  std::unique_ptr<btDefaultCollisionConfiguration> configuration_;
  std::unique_ptr<btCollisionDispatcher> dispatcher_;
  std::unique_ptr<btDbvtBroadphase> broadphase_;
  std::unique_ptr<btSequentialImpulseConstraintSolver> solver_;
  std::unique_ptr<bullet::World> world_;
  std::unique_ptr<bullet::SoftBody> organ_;
  TriangleMesh organ_mesh_;
  std::unique_ptr<btCollisionShape> table_shape_;
  std::unique_ptr<btRigidBody> table_;
  std::vector<SceneTool> tools_;
  OrganSummary summary_;
};

/// Lets the organ come to rest on the table for scene.settle_time before the story starts, the
/// tools held at their first pose. An error when the organ goes unstable, with when.
Status settle(SceneWorld& world, const Scene& scene);

}  // namespace cubespring::scene
