// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Random cuts of the demo's liver (its mesh the visual surface, 8 mm cells) in a Bullet world,
// stepped between them: after each, the body's mass is its remaining cells', its visual and contact
// surfaces are closed and consistently oriented, and it steps on. CUBESPRING_RANDOM_CUTS sets the
// count (the documented long run: docs/cutting.md).
#include <algorithm>
#include <cstdlib>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "bullet_scene.h"
#include "closed_surface.h"
#include "cubespring/mesh/load_mesh.h"
#include "cubespring/voxelize.h"

namespace cubespring {
namespace {

TEST(BulletLiverCuts, RandomCutsKeepTheLiversSurfaceClosed) {
  const char* count_text = std::getenv("CUBESPRING_RANDOM_CUTS");
  const int cuts = count_text != nullptr ? std::atoi(count_text) : 12;
  Result<TriangleMesh> mesh = load_mesh(std::string(CUBESPRING_DATA_DIR) + "/liver.obj");
  ASSERT_TRUE(mesh.ok()) << mesh.message();
  VoxelizeOptions options;
  options.cell_size = Eigen::Vector3d::Constant(0.008);
  Result<Voxelization> voxels = voxelize(*mesh, options);
  ASSERT_TRUE(voxels.ok()) << voxels.message();
  bullet::SoftBodySettings settings;
  settings.lattice =
      lattice_from_voxels(*voxels, {soft_tissue(8e3), soft_tissue(4e4)}, CellModel::kExactBending);  // liver, tumour
  settings.visual_mesh = *mesh;
  settings.contact.friction = 0.3;
  settings.contact.face_contacts = true;

  std::mt19937 rng(29);
  int made = 0;
  while (made < cuts) {
    test::BulletScene scene;
    scene.add_floor(mesh->vertices.row(2).minCoeff() - 0.0005);
    bullet::SoftBody* body = scene.add_soft(settings);
    ASSERT_NE(body, nullptr);
    for (; made < cuts && body->model().num_cells() > 200; ++made) {
      const Model& model = body->model();
      // a stroke: the cells within a cell of a random segment through the liver's box, or a few random cells
      std::vector<int> cells;
      if (rng() % 2 == 0) {
        std::uniform_int_distribution<int> pick(0, model.num_cells() - 1);
        for (int k = 0; k < 1 + static_cast<int>(rng() % 6); ++k) cells.push_back(pick(rng));
      } else {
        std::uniform_int_distribution<int> pick(0, model.num_cells() - 1);
        const Eigen::Vector3i a = model.cell_grid_index[static_cast<std::size_t>(pick(rng))];
        const Eigen::Vector3i b = model.cell_grid_index[static_cast<std::size_t>(pick(rng))];
        for (int c = 0; c < model.num_cells(); ++c) {
          const Eigen::Vector3d g = model.cell_grid_index[static_cast<std::size_t>(c)].cast<double>();
          const Eigen::Vector3d ab = (b - a).cast<double>();
          const double along = std::clamp((g - a.cast<double>()).dot(ab) / std::max(ab.squaredNorm(), 1.0), 0.0, 1.0);
          if ((a.cast<double>() + along * ab - g).norm() < 1.0) cells.push_back(c);
        }
      }
      if (cells.size() >= static_cast<std::size_t>(model.num_cells())) continue;
      const double expected_mass = model.total_mass();
      Result<bullet::SoftBody::Cut> cut = body->remove_cells(cells);
      ASSERT_TRUE(cut.ok()) << "cut " << made << ": " << cut.message();
      EXPECT_NEAR(body->model().total_mass(), expected_mass - cut->removed_mass, 1e-12 * expected_mass);
      ASSERT_TRUE(test::closed_and_oriented(body->embedding().triangles)) << "cut " << made << ", its visual surface";
      ASSERT_TRUE(test::closed_and_oriented(body->surface_triangles())) << "cut " << made << ", its contact surface";
      scene.run(0.02);
      ASSERT_TRUE(scene.world().getSoftBodyError().empty())
          << "cut " << made << ": " << scene.world().getSoftBodyError();
      ASSERT_TRUE(body->state().positions.allFinite());
    }
  }
}

}  // namespace
}  // namespace cubespring
