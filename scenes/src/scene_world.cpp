// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "cubespring/scene/scene_world.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>
#include <string>

#include "cubespring/bullet/conversions.h"
#include "cubespring/mesh/load_mesh.h"
#include "cubespring/scene/tool_motion.h"
#include "cubespring/voxelize.h"
#include "json_lines.h"
#include "tool_shapes.h"

namespace cubespring::scene {
namespace {

using bullet::to_bt;
using bullet::to_eigen;

std::string where(const Scene& scene, int line) {
  return line > 0 ? scene.source + ":" + std::to_string(line) + ": " : std::string();
}

// One material per voxelized part, matched by the part's material name, else by its name.
Result<std::vector<Material>> part_materials(const Scene& scene, const Voxelization& voxels, OrganSummary& summary) {
  std::vector<Material> materials;
  std::map<std::string, bool> used;
  for (const VoxelPart& part : voxels.parts) {
    auto found = scene.organ.materials.find(part.material_name);
    if (part.material_name.empty() || found == scene.organ.materials.end())
      found = scene.organ.materials.find(part.name);
    if (found == scene.organ.materials.end()) {
      materials.push_back(default_tissue());
      summary.notes.push_back("part \"" + part.name + "\" (material \"" + part.material_name +
                              "\") has no entry in organ.materials: it takes the default tissue");
    } else {
      materials.push_back(found->second);
      used[found->first] = true;
    }
  }
  for (const auto& [name, material] : scene.organ.materials) {
    if (used.count(name) != 0) continue;
    std::string parts;
    for (const VoxelPart& part : voxels.parts) {
      parts += (parts.empty() ? "" : ", ") + part.name + " (material " + part.material_name + ")";
    }
    const auto line = scene.organ.material_lines.find(name);
    return Status::error(where(scene, line == scene.organ.material_lines.end() ? 0 : line->second) +
                         quote_for_message(name) + " in \"organ.materials\" matches no part of " + scene.organ.mesh +
                         " (its parts: " + parts + ")");
  }
  return materials;
}

}  // namespace

SceneWorld::SceneWorld() = default;

SceneWorld::~SceneWorld() {
  if (!world_) return;
  for (SceneTool& tool : tools_) world_->removeRigidBody(tool.body.get());
  if (table_) world_->removeRigidBody(table_.get());
  if (organ_) world_->removeSoftBody(organ_.get());
}

Result<std::unique_ptr<SceneWorld>> SceneWorld::create(const Scene& scene) {
  std::unique_ptr<SceneWorld> built(new SceneWorld());
  built->configuration_ = std::make_unique<btDefaultCollisionConfiguration>();
  built->dispatcher_ = std::make_unique<btCollisionDispatcher>(built->configuration_.get());
  built->broadphase_ = std::make_unique<btDbvtBroadphase>();
  built->solver_ = std::make_unique<btSequentialImpulseConstraintSolver>();
  built->world_ = std::make_unique<bullet::World>(built->dispatcher_.get(), built->broadphase_.get(),
                                                  built->solver_.get(), built->configuration_.get());
  built->world_->setGravity(to_bt(scene.gravity));
  if (Status s = built->build_organ(scene); !s) return s;
  if (Status s = built->build_table(scene); !s) return s;
  if (Status s = built->build_tools(scene); !s) return s;
  return built;
}

Status SceneWorld::build_organ(const Scene& scene) {
  const OrganSpec& spec = scene.organ;
  LoadOptions load;
  load.scale = spec.scale;
  Result<TriangleMesh> mesh = load_mesh(spec.mesh, load);
  if (!mesh) return Status::error("organ mesh: " + mesh.message());
  organ_mesh_ = std::move(mesh).value();

  VoxelizeOptions options;
  if (spec.cells_across > 0) {
    options.cells_across = spec.cells_across;
  } else {
    options.cell_size = Eigen::Vector3d::Constant(spec.cell_size);
  }
  Result<Voxelization> voxels = voxelize(organ_mesh_, options);
  if (!voxels) return Status::error("voxelizing the organ " + spec.mesh + ": " + voxels.message());
  Result<std::vector<Material>> materials = part_materials(scene, *voxels, summary_);
  if (!materials) return materials.status();

  bullet::SoftBodySettings settings;
  settings.lattice = lattice_from_voxels(*voxels, *materials, spec.model);
  settings.law = spec.law;
  settings.visual_mesh = organ_mesh_;
  settings.integrator = scene.integrator;
  settings.contact.friction = spec.friction;
  settings.contact.face_contacts = spec.face_contacts;
  settings.contact.offset = spec.contact_offset;
  settings.max_added_mass = spec.max_added_mass;
  settings.time_step_safety = spec.time_step_safety;
  Result<std::unique_ptr<bullet::SoftBody>> body = bullet::SoftBody::create(settings);
  if (!body) return Status::error("organ: " + body.message());
  organ_ = std::move(body).value();

  for (std::size_t i = 0; i < spec.fixed_regions.size(); ++i) {
    const Box& box = spec.fixed_regions[i];
    if (Status s = organ_->constraints().fix_box(organ_->model(), box.lower, box.upper); !s) {
      std::ostringstream message;
      message << where(scene, box.line) << "organ.fixed_regions[" << i << "] from (" << box.lower.transpose()
              << ") to (" << box.upper.transpose() << ") m holds no node of the organ";
      return Status::error(message.str());
    }
  }
  world_->addSoftBody(organ_.get());
  summary_.cells = organ_->model().num_cells();
  summary_.nodes = organ_->model().num_nodes();
  summary_.fixed_nodes = organ_->constraints().num_driven();
  summary_.cell_size = voxels->cell_size.x();
  summary_.sub_step = organ_->sub_step();
  if (const MassScaling& added = organ_->mass_scaling(); added.nodes > 0) {
    char note[200];
    std::snprintf(note, sizeof note,
                  "organ.max_added_mass: %d nodes took %.1f g of inertia (%.1f%% of the organ's mass); the sub-step "
                  "is %.3f ms, %.2fx what it was",
                  added.nodes, 1e3 * added.added_mass, 100.0 * added.added_fraction, 1e3 * organ_->sub_step(),
                  added.time_step_after / added.time_step_before);
    summary_.notes.emplace_back(note);
  }
  return {};
}

Status SceneWorld::build_table(const Scene& scene) {
  if (!scene.table.enabled) return {};
  // a slab whose top is the table's height; thick enough that no vertex passes through it
  constexpr double kThickness = 0.02;
  const double half = scene.table.half_size;
  table_shape_ = std::make_unique<btBoxShape>(to_bt(Eigen::Vector3d(half, half, 0.5 * kThickness)));
  btRigidBody::btRigidBodyConstructionInfo info(0.0, nullptr, table_shape_.get());
  info.m_startWorldTransform.setIdentity();
  info.m_startWorldTransform.setOrigin(to_bt(Eigen::Vector3d(0, 0, scene.table.height - 0.5 * kThickness)));
  table_ = std::make_unique<btRigidBody>(info);
  world_->addRigidBody(table_.get());
  return {};
}

Status SceneWorld::build_tools(const Scene& scene) {
  for (const ToolSpec& spec : scene.tools) {
    SceneTool tool;
    tool.name = spec.name;
    tool.keyframes = spec.keyframes;
    tool.shape_offset = Eigen::Isometry3d::Identity();
    if (!spec.mesh.empty()) {
      LoadOptions load;
      load.scale = spec.scale;
      Result<TriangleMesh> mesh = load_mesh(spec.mesh, load);
      if (!mesh) return Status::error("tool \"" + spec.name + "\" mesh: " + mesh.message());
      tool.mesh = std::move(mesh).value();
    }
    if (spec.capsule) {
      const double radius = spec.capsule->radius * spec.scale;
      const double length = spec.capsule->length * spec.scale;
      if (spec.mesh.empty()) tool.mesh = capsule_mesh(radius, length);
      // Bullet's capsule is centred on its origin; the tool's frame has the tip there
      tool.shape = std::make_unique<btCapsuleShapeZ>(static_cast<btScalar>(radius),
                                                     static_cast<btScalar>(length - 2.0 * radius));
      tool.shape_offset.translation() = Eigen::Vector3d(0, 0, 0.5 * length);
      tool.radius = radius;
      tool.length = length;
      tool.cut = spec.cut;
    } else {
      // contact sees the mesh's convex hull; a small margin, as the plugin ignores it (doc section 5)
      auto hull = std::make_unique<btConvexHullShape>();
      for (int v = 0; v < tool.mesh.num_vertices(); ++v)
        hull->addPoint(to_bt(Eigen::Vector3d(tool.mesh.vertices.col(v))), false);
      hull->recalcLocalAabb();
      hull->setMargin(0.0005f);
      tool.shape = std::move(hull);
    }
    btRigidBody::btRigidBodyConstructionInfo info(0.0, nullptr, tool.shape.get());
    info.m_startWorldTransform = to_bt(pose_at(spec.keyframes, 0.0) * tool.shape_offset);
    tool.body = std::make_unique<btRigidBody>(info);
    tool.body->setCollisionFlags(tool.body->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
    tool.body->setActivationState(DISABLE_DEACTIVATION);
    world_->addRigidBody(tool.body.get());
    tools_.push_back(std::move(tool));
  }
  return {};
}

void SceneWorld::place_tools(double t) {
  for (SceneTool& tool : tools_) {
    if (tool.scripted) tool.body->setWorldTransform(to_bt(pose_at(tool.keyframes, t) * tool.shape_offset));
  }
}

SceneTool* SceneWorld::take_tool(const std::string& name) {
  for (SceneTool& tool : tools_) {
    if (tool.name != name) continue;
    tool.scripted = false;
    return &tool;
  }
  return nullptr;
}

Status SceneWorld::step(double dt) {
  world_->stepSimulation(static_cast<btScalar>(dt), 1, static_cast<btScalar>(dt));
  if (!world_->getSoftBodyError().empty())
    return Status::error("the organ went unstable: " + world_->getSoftBodyError());
  return {};
}

// How far beyond its surface a cautery burns [cells]: contact keeps the tissue outside the tool, so
// the cells it presses on keep their centres about half a cell from its surface; at half a cell
// the demo liver's cautery burnt 8 cells along its 2 cm path and ploughed the rest aside, at three
// quarters 15.
constexpr double kCauteryReachCells = 0.75;

std::vector<ToolCut> SceneWorld::cuts_due() const {
  std::vector<ToolCut> cuts;
  const Model& model = organ_->model();
  const Eigen::Matrix3Xd& x = organ_->state().positions;
  for (std::size_t i = 0; i < tools_.size(); ++i) {
    const SceneTool& tool = tools_[i];
    if (!tool.cut) continue;
    if (tool.cut->force_threshold > 0.0 &&
        !(world_->getContactWrench(tool.body.get()).force.norm() >= tool.cut->force_threshold)) {
      continue;
    }
    // the capsule's axis, tip first, in the scene's frame
    const Eigen::Isometry3d pose = tool_pose(tool);
    const Eigen::Vector3d a = pose * Eigen::Vector3d(0, 0, tool.radius);
    const Eigen::Vector3d b = pose * Eigen::Vector3d(0, 0, tool.length - tool.radius);
    const double reach = tool.radius + kCauteryReachCells * model.cell_size.minCoeff();
    const Eigen::Vector3d axis = b - a;
    ToolCut cut{i, {}};
    for (int c = 0; c < model.num_cells(); ++c) {
      Eigen::Vector3d centre = Eigen::Vector3d::Zero();
      for (const int node : model.cell_nodes[static_cast<std::size_t>(c)]) centre += x.col(node);
      centre /= kCornersPerCell;
      const double along = std::clamp((centre - a).dot(axis) / axis.squaredNorm(), 0.0, 1.0);
      if ((a + along * axis - centre).squaredNorm() <= reach * reach) cut.cells.push_back(c);
    }
    if (!cut.cells.empty()) cuts.push_back(std::move(cut));
  }
  return cuts;
}

Result<bullet::SoftBody::Cut> SceneWorld::apply_cuts(const std::vector<ToolCut>& cuts) {
  std::vector<int> cells;
  std::vector<int> counted(static_cast<std::size_t>(organ_->model().num_cells()), -1);  // the tool a cell counts to
  for (const ToolCut& cut : cuts) {
    for (const int c : cut.cells) {
      int& owner = counted[static_cast<std::size_t>(c)];
      if (owner >= 0) continue;
      owner = static_cast<int>(cut.tool);
      cells.push_back(c);
    }
  }
  Result<bullet::SoftBody::Cut> done = organ_->remove_cells(cells);
  if (!done) return Status::error("cutting the organ: " + done.message());
  for (const int owner : counted) {
    if (owner >= 0) ++tools_[static_cast<std::size_t>(owner)].cells_removed;
  }
  return done;
}

Eigen::Isometry3d SceneWorld::tool_pose(const SceneTool& tool) const {
  return to_eigen(tool.body->getWorldTransform()) * tool.shape_offset.inverse();
}

Status settle(SceneWorld& world, const Scene& scene) {
  const int steps = static_cast<int>(std::lround(scene.settle_time / scene.time_step));
  world.place_tools(0.0);
  for (int n = 0; n < steps; ++n) {
    if (Status s = world.step(scene.time_step); !s) {
      char before[32];
      std::snprintf(before, sizeof before, "%.3f s", scene.settle_time - n * scene.time_step);
      return Status::error(s.message() + " (while settling, " + before + " before t = 0)");
    }
  }
  return {};
}

}  // namespace cubespring::scene
