// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Real organ meshes resting on a table, as a surgical scene starts (issues 24 and 25): the shared
// liver scaled to 15 cm along its longest side, the shared sphere and torus scaled to 12 cm, of
// 5 kPa tissue (nu = 0.45, density 1060, mass damping 40/s, exact-bending cells of 8 mm, the
// plugin's default neo-Hookean law), each mesh its own visual surface, dropped from where it lies
// onto a table like the scenes' (a static slab 2 cm thick, friction 0.3), 5 s at Bullet's 1/60 s
// steps. The liver, as its file stands it, topples: on 8 mm cells it rolls about 8 cm across the
// table and rests after 6-7 s, so it is given 8 s (it came to rest after 3.5 s while friction crept,
// its contacts sliding by dt^2 times their tangential acceleration each sub-step). The liver also on 4 mm
// cells, 37 across, where its triangles (edges of 5 to 48 mm) span up to 12 cells. They must come
// to rest: no blow-up, no crushed cell, the volume kept, the table carrying the weight. The meshes
// are reference data in ../shared/meshes (skipped without them). Label slow.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "bullet_scene.h"
#include "cubespring/forces.h"
#include "cubespring/mesh/load_mesh.h"
#include "cubespring/voxelize.h"

namespace cubespring {
namespace {

struct Organ {
  const char* name;
  const char* file;
  double longest_side;  // [m] once scaled
  double cell_size;     // [m]
  bool lay_down;        // turned a quarter about x, its y axis up (the torus: off its rim, flat)
  double seconds;       // on the table before it is checked [s]
};

struct Settled {
  double volume;       // of the lattice, deformed over rest
  double least_cell;   // the least cell volume over its rest volume
  double rms_speed;    // mass-weighted [m/s]
  double table_force;  // upward [N]
  double weight;       // [N]
};

// The organ, its lowest point on the table top z = 0, settled for `seconds`; nothing if it failed.
std::optional<Settled> settle_on_table(const Organ& organ, double seconds) {
  const std::filesystem::path path = std::filesystem::path(CUBESPRING_SHARED_MESHES_DIR) / organ.file;
  Result<TriangleMesh> unscaled = load_mesh(path.string());
  EXPECT_TRUE(unscaled.ok()) << unscaled.message();
  if (!unscaled) return std::nullopt;
  const Eigen::Vector3d extent = unscaled->vertices.rowwise().maxCoeff() - unscaled->vertices.rowwise().minCoeff();
  LoadOptions options;
  options.scale = organ.longest_side / extent.maxCoeff();
  Result<TriangleMesh> mesh = load_mesh(path.string(), options);
  EXPECT_TRUE(mesh.ok()) << mesh.message();
  if (!mesh) return std::nullopt;
  if (organ.lay_down) {
    const Eigen::Matrix3d quarter_about_x = Eigen::AngleAxisd(0.5 * M_PI, Eigen::Vector3d::UnitX()).toRotationMatrix();
    mesh->vertices = quarter_about_x * mesh->vertices;
  }
  mesh->vertices.row(2).array() -= mesh->vertices.row(2).minCoeff();

  VoxelizeOptions voxelize_options;
  voxelize_options.cell_size = Eigen::Vector3d::Constant(organ.cell_size);
  Result<Voxelization> voxels = voxelize(*mesh, voxelize_options);
  EXPECT_TRUE(voxels.ok()) << voxels.message();
  if (!voxels) return std::nullopt;
  const Material tissue = soft_tissue(5e3);  // its damping is the one the organs must come to rest with
  bullet::SoftBodySettings settings;
  settings.lattice = lattice_from_voxels(*voxels, {tissue}, CellModel::kExactBending);
  settings.visual_mesh = *mesh;
  settings.contact.friction = 0.3;

  test::BulletScene scene;
  btRigidBody* table = scene.add_rigid(new btBoxShape(btVector3(0.25f, 0.25f, 0.01f)), 0.0, test::at(0, 0, -0.01));
  bullet::SoftBody* soft = scene.add_soft(settings);
  if (soft == nullptr) return std::nullopt;
  scene.run(seconds);
  EXPECT_TRUE(scene.world().getSoftBodyError().empty()) << organ.file << ": " << scene.world().getSoftBodyError();
  if (!scene.world().getSoftBodyError().empty()) return std::nullopt;

  const Model& model = soft->model();
  Settled settled{0.0, 1e300, 0.0, 0.0, 0.0};
  for (int c = 0; c < model.num_cells(); ++c) {
    const double j = cell_signed_volume(model, soft->state().positions, c) / model.rest_cell_volume();
    settled.volume += j;
    settled.least_cell = std::min(settled.least_cell, j);
  }
  settled.volume /= model.num_cells();
  settled.rms_speed = std::sqrt(2.0 * kinetic_energy(model, soft->state()) / model.total_mass());
  settled.table_force = -scene.world().getContactWrench(table).force.z();
  settled.weight = model.total_mass() * 9.81;
  std::printf(
      "%s on %g mm cells: %d cells, volume %.4f of rest, least cell %.3f, rms speed %.2e m/s, table %.4f N "
      "for a weight of %.4f N\n",
      organ.file, 1e3 * organ.cell_size, model.num_cells(), settled.volume, settled.least_cell, settled.rms_speed,
      settled.table_force, settled.weight);
  return settled;
}

class OrgansOnTheTable : public ::testing::TestWithParam<Organ> {};

TEST_P(OrgansOnTheTable, SettleKeepingTheirVolume) {
  if (!std::filesystem::exists(std::filesystem::path(CUBESPRING_SHARED_MESHES_DIR) / GetParam().file)) {
    GTEST_SKIP() << "no " << GetParam().file << " in " << CUBESPRING_SHARED_MESHES_DIR
                 << " (the shared reference meshes)";
  }
  const std::optional<Settled> settled = settle_on_table(GetParam(), GetParam().seconds);
  ASSERT_TRUE(settled.has_value());
  EXPECT_GT(settled->least_cell, 0.5) << "no cell crushed";
  EXPECT_NEAR(settled->volume, 1.0, 0.03) << "a continuum at nu = 0.45 keeps its volume within a few percent";
  // at rest (the contact issue's target; when a pass's points shared their nodes' corrections by a
  // weighted mean, the sphere kept moving at 0.012 m/s)
  EXPECT_LT(settled->rms_speed, 1e-3);
  EXPECT_NEAR(settled->table_force, settled->weight, 0.01 * settled->weight);
}

INSTANTIATE_TEST_SUITE_P(SharedMeshes, OrgansOnTheTable,
                         ::testing::Values(Organ{"liver", "liver.obj", 0.15, 0.008, false, 8.0},
                                           Organ{"liver_at_4mm", "liver.obj", 0.15, 0.004, false, 5.0},
                                           Organ{"sphere", "sphere.obj", 0.12, 0.008, false, 5.0},
                                           Organ{"torus", "torus.obj", 0.12, 0.008, true, 5.0}),
                         [](const ::testing::TestParamInfo<Organ>& organ) { return std::string(organ.param.name); });

}  // namespace
}  // namespace cubespring
