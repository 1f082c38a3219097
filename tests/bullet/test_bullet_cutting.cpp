// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Cells taken out of a soft body in a Bullet world between steps (SoftBody::remove_cells): the
// body is rebuilt around its remaining cells, its pieces move on their own, and contact acts on
// the surface the cut left.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "bullet_scene.h"
#include "closed_surface.h"
#include "cubespring/embedding.h"
#include "cubespring/shapes.h"
#include "cubespring/voxelize.h"

namespace cubespring {
namespace {

Eigen::Vector3d momentum(const bullet::SoftBody& body) { return body.state().velocities * body.model().mass; }

// The visual mesh's vertices with the body at rest [m].
Eigen::Matrix3Xd visual_rest(const bullet::SoftBody& body) {
  Eigen::Matrix3Xd vertices;
  embedded_positions(body.model(), body.embedding(), body.model().rest_positions, vertices);
  return vertices;
}

// A 4 x 4 x 10 cm column of 10 kPa tissue hanging from its top layer of nodes, 1 cm above a
// table, its surface its lattice's.
struct HangingColumn {
  test::BulletScene scene;
  btRigidBody* floor = nullptr;
  bullet::SoftBodySettings settings = test::block({4, 4, 10}, 0.01, soft_tissue(1e4));
  bullet::SoftBody* body = nullptr;

  HangingColumn() {
    floor = scene.add_floor(-0.01);
    settings.contact.friction = 0.3;
    body = scene.add_soft(settings);
  }
  // The nodes at or below grid layer `layer` and their mass [kg].
  std::pair<std::vector<int>, double> nodes_up_to(int layer) const {
    std::pair<std::vector<int>, double> lower{{}, 0.0};
    for (int n = 0; n < body->model().num_nodes(); ++n) {
      if (body->model().node_grid_index[static_cast<std::size_t>(n)].z() <= layer) {
        lower.first.push_back(n);
        lower.second += body->model().mass[n];
      }
    }
    return lower;
  }
  // After 2 s more, the piece of `nodes` (of `mass` [kg]) rests on the table, which carries it.
  void expect_the_table_carries(const std::vector<int>& nodes, double mass) {
    scene.run(2.0);
    ASSERT_TRUE(scene.world().getSoftBodyError().empty()) << scene.world().getSoftBodyError();
    double lowest = 1.0, centre = 0.0, speed_sq = 0.0;
    for (const int n : nodes) {
      lowest = std::min(lowest, body->state().positions(2, n));
      centre += body->model().mass[n] * body->state().positions(2, n) / mass;
      speed_sq += body->model().mass[n] * body->state().velocities.col(n).squaredNorm() / mass;
    }
    const double ground = -scene.world().getContactWrench(floor).force.z();
    std::printf(
        "lower piece: %.4f kg, lowest node z = %.2f mm, centre %.2f mm, rms speed %.2e m/s; table %.5f N for %.5f N\n",
        mass, 1e3 * lowest, 1e3 * centre, std::sqrt(speed_sq), ground, mass * 9.81);
    EXPECT_NEAR(lowest, -0.01, 0.5e-3) << "it rests on the table";
    EXPECT_LT(std::sqrt(speed_sq), 1e-3);
    EXPECT_NEAR(ground, mass * 9.81, 0.01 * mass * 9.81);
  }
};

// The column's slab of cells 4 cm up is cut out: the lower piece falls, lands and the table
// carries it, while the upper piece hangs on.
TEST(BulletCutting, APieceCutOffFallsAndTheTableCarriesIt) {
  HangingColumn column;
  bullet::SoftBody* body = column.body;
  ASSERT_NE(body, nullptr);
  ASSERT_TRUE(body->constraints().fix_box(body->model(), {-1, -1, 0.0999}, {1, 1, 1}).ok());
  column.scene.run(0.5);
  ASSERT_TRUE(column.scene.world().getSoftBodyError().empty()) << column.scene.world().getSoftBodyError();
  EXPECT_NEAR(column.scene.world().getContactWrench(column.floor).force.z(), 0.0, 1e-12) << "hangs clear of the table";

  std::vector<int> slab;
  for (int c = 0; c < body->model().num_cells(); ++c) {
    if (body->model().cell_grid_index[static_cast<std::size_t>(c)].z() == 4) slab.push_back(c);
  }
  const double mass_before = body->model().total_mass();
  const Eigen::Vector3d momentum_before = momentum(*body);
  Result<bullet::SoftBody::Cut> cut = body->remove_cells(slab);
  ASSERT_TRUE(cut.ok()) << cut.message();
  EXPECT_EQ(cut->removed_cells, 16);
  EXPECT_EQ(cut->pieces, 2);
  EXPECT_NEAR(body->model().total_mass(), mass_before - cut->removed_mass, 1e-12 * mass_before);
  EXPECT_NEAR(cut->removed_mass, 16 * 1e-6 * column.settings.lattice.materials[0].density, 1e-15);
  EXPECT_LT((momentum_before - momentum(*body) - cut->removed_momentum).norm(),
            1e-12 * (body->state().velocities.cwiseAbs() * body->model().mass).norm() + 1e-18);
  EXPECT_EQ(body->constraints().num_driven(), 25) << "the top layer stays held";
  const auto [lower, lower_mass] = column.nodes_up_to(4);
  column.expect_the_table_carries(lower, lower_mass);
}

// The column split through 4 cm up, as a blade would: nothing leaves, the plane's 25 nodes get
// copies, and the lower half falls, lands and the table carries it, while the upper hangs on.
TEST(BulletCutting, AColumnSplitThroughFallsApartOntoTheTable) {
  HangingColumn column;
  bullet::SoftBody* body = column.body;
  ASSERT_NE(body, nullptr);
  ASSERT_TRUE(body->constraints().fix_box(body->model(), {-1, -1, 0.0999}, {1, 1, 1}).ok());
  column.scene.run(0.5);
  std::vector<CellFace> blade;
  for (const Eigen::Vector3i& cell : body->model().cell_grid_index) {
    if (cell.z() == 3) blade.push_back({cell, 2});
  }
  const double mass_before = body->model().total_mass();
  const Eigen::Vector3d momentum_before = momentum(*body);
  Result<bullet::SoftBody::Split> split = body->split_faces(blade);
  ASSERT_TRUE(split.ok()) << split.message();
  EXPECT_EQ(split->faces_split, 16);
  EXPECT_EQ(split->nodes_added, 25);
  EXPECT_EQ(split->pieces, 2);
  EXPECT_NEAR(body->model().total_mass(), mass_before, 1e-15 * mass_before);
  EXPECT_LT((momentum_before - momentum(*body)).norm(),
            1e-13 * (body->state().velocities.cwiseAbs() * body->model().mass).norm() + 1e-18);
  EXPECT_EQ(body->constraints().num_driven(), 25) << "the top layer stays held";
  // the lower half: the nodes below the plane and the plane's copies its cells have
  std::vector<char> lower_node(static_cast<std::size_t>(body->model().num_nodes()), 0);
  for (int c = 0; c < body->model().num_cells(); ++c) {
    if (body->model().cell_grid_index[static_cast<std::size_t>(c)].z() > 3) continue;
    for (const int n : body->model().cell_nodes[static_cast<std::size_t>(c)])
      lower_node[static_cast<std::size_t>(n)] = 1;
  }
  std::vector<int> lower;
  double lower_mass = 0.0;
  for (int n = 0; n < body->model().num_nodes(); ++n) {
    if (!lower_node[static_cast<std::size_t>(n)]) continue;
    lower.push_back(n);
    lower_mass += body->model().mass[n];
  }
  EXPECT_NEAR(lower_mass, 4 * 16 * 1e-6 * column.settings.lattice.materials[0].density, 1e-15);
  column.expect_the_table_carries(lower, lower_mass);
}

// A body with a visual mesh is not split (its visual surface would not follow), and nothing
// changes; a face that is not between two cells is refused by name.
TEST(BulletCutting, ASplitThatCannotBeMadeChangesNothing) {
  HangingColumn column;
  ASSERT_NE(column.body, nullptr);
  const int nodes = column.body->model().num_nodes();
  Result<bullet::SoftBody::Split> outside = column.body->split_faces({{{0, 0, 9}, 2}});
  ASSERT_FALSE(outside.ok());
  EXPECT_NE(outside.message().find("cell (0, 0, 10) is not a cell of the body"), std::string::npos)
      << outside.message();
  EXPECT_EQ(column.body->model().num_nodes(), nodes);

  test::BulletScene scene;
  bullet::SoftBodySettings settings = test::block({2, 2, 2}, 0.01, soft_tissue(1e4));
  settings.visual_mesh = box_mesh({0, 0, 0}, {0.02, 0.02, 0.02});
  bullet::SoftBody* body = scene.add_soft(settings);
  ASSERT_NE(body, nullptr);
  Result<bullet::SoftBody::Split> with_mesh = body->split_faces({{{0, 0, 0}, 0}});
  ASSERT_FALSE(with_mesh.ok());
  EXPECT_NE(with_mesh.message().find("a visual mesh does not follow a split yet"), std::string::npos)
      << with_mesh.message();
  EXPECT_TRUE(body->model().split_faces.empty());
}

// A 10 cm ball of 10 kPa tissue, its sphere the visual mesh, settled on a table; a cautery
// channel (the cells within 9 mm of its vertical axis, above its middle) is burnt into its top.
// The visual surface stays closed with a cap down the channel, the ball settles again, and the
// table carries what is left of it.
TEST(BulletCutting, AChannelBurntIntoABallKeepsItsSurfaceClosed) {
  TriangleMesh sphere = sphere_mesh(0.05, 4, {0, 0, 0.05});
  VoxelizeOptions options;
  options.cell_size = Eigen::Vector3d::Constant(0.008);
  Result<Voxelization> voxels = voxelize(sphere, options);
  ASSERT_TRUE(voxels.ok()) << voxels.message();
  bullet::SoftBodySettings settings;
  settings.lattice = lattice_from_voxels(*voxels, {soft_tissue(1e4)}, CellModel::kExactBending);
  settings.visual_mesh = sphere;
  settings.contact.friction = 0.3;
  test::BulletScene scene;
  btRigidBody* floor = scene.add_floor();
  bullet::SoftBody* body = scene.add_soft(settings);
  ASSERT_NE(body, nullptr);
  scene.run(1.0);
  ASSERT_TRUE(scene.world().getSoftBodyError().empty()) << scene.world().getSoftBodyError();

  std::vector<int> channel;
  const Model& model = body->model();
  for (int c = 0; c < model.num_cells(); ++c) {
    const Eigen::Vector3d centre =
        model.origin + (model.cell_grid_index[static_cast<std::size_t>(c)].cast<double>().array() + 0.5)
                           .matrix()
                           .cwiseProduct(model.cell_size);
    if (centre.head<2>().norm() < 0.009 && centre.z() > 0.05) channel.push_back(c);
  }
  ASSERT_GT(channel.size(), 10u);
  // burnt in two strokes, the upper half first; the second cuts the surface the first left
  std::sort(channel.begin(), channel.end(), [&](int a, int b) {
    return model.cell_grid_index[static_cast<std::size_t>(a)].z() >
           model.cell_grid_index[static_cast<std::size_t>(b)].z();
  });
  const std::vector<Eigen::Vector3i> lower_half_cells = [&] {
    std::vector<Eigen::Vector3i> cells;
    for (std::size_t i = channel.size() / 2; i < channel.size(); ++i) {
      cells.push_back(model.cell_grid_index[static_cast<std::size_t>(channel[i])]);
    }
    return cells;
  }();
  channel.resize(channel.size() / 2);
  int cap_triangles = 0;
  for (int stroke = 0; stroke < 2; ++stroke) {
    const Eigen::Matrix3Xd rest_before = visual_rest(*body);
    const int visual_before = body->embedding().num_vertices();
    Result<bullet::SoftBody::Cut> cut = body->remove_cells(channel);
    ASSERT_TRUE(cut.ok()) << cut.message();
    cap_triangles = cut->cap_triangles;
    EXPECT_EQ(cut->pieces, 1);
    EXPECT_GT(cut->cap_triangles, 0);
    ASSERT_EQ(static_cast<int>(cut->visual_vertex_source.size()), body->embedding().num_vertices());
    EXPECT_NE(body->embedding().num_vertices(), visual_before);
    EXPECT_TRUE(test::closed_and_oriented(body->embedding().triangles)) << "stroke " << stroke;
    EXPECT_TRUE(test::closed_and_oriented(body->surface_triangles())) << "the contact surface too, stroke " << stroke;
    // a vertex the cut kept is where it was, at rest
    const Eigen::Matrix3Xd rest_after = visual_rest(*body);
    for (int v = 0; v < rest_after.cols(); ++v) {
      const int source = cut->visual_vertex_source[static_cast<std::size_t>(v)];
      if (source >= 0) {
        EXPECT_LT((rest_after.col(v) - rest_before.col(source)).norm(), 1e-12) << "stroke " << stroke;
      }
    }
    channel.clear();  // the second stroke: the lower half, by its cells' grid places (indices changed)
    for (int c = 0; c < body->model().num_cells(); ++c) {
      const Eigen::Vector3i& g = body->model().cell_grid_index[static_cast<std::size_t>(c)];
      if (std::find(lower_half_cells.begin(), lower_half_cells.end(), g) != lower_half_cells.end())
        channel.push_back(c);
    }
  }

  scene.run(1.5);
  ASSERT_TRUE(scene.world().getSoftBodyError().empty()) << scene.world().getSoftBodyError();
  const double weight = body->model().total_mass() * 9.81;
  const double ground = -scene.world().getContactWrench(floor).force.z();
  const double rms_speed = std::sqrt((body->state().velocities.colwise().squaredNorm() * body->model().mass).value() /
                                     body->model().total_mass());
  std::printf("%zu + %zu cells burnt away: %d cap triangles; table %.4f N for a weight of %.4f N, rms speed %.2e m/s\n",
              lower_half_cells.size(), lower_half_cells.size(), cap_triangles, ground, weight, rms_speed);
  EXPECT_NEAR(ground, weight, 0.01 * weight);
  EXPECT_LT(rms_speed, 1e-3);
}

// A column hanging from a static hook by its top nodes (an anchor): a slab cut below the hook
// leaves the top piece held, the hook carrying only its weight; cutting the top layer of cells
// away takes the anchor's nodes with it, the anchor is detached and what is left falls.
TEST(BulletCutting, AnAnchorKeepsTheNodesThatRemainAndGoesWithTheLast) {
  test::BulletScene scene;
  btRigidBody* hook = scene.add_rigid(new btBoxShape(btVector3(0.05f, 0.05f, 0.005f)), 0.0, test::at(0, 0, 0.105));
  bullet::SoftBody* body = scene.add_soft(test::block({2, 2, 6}, 0.01, soft_tissue(2e4)));
  ASSERT_NE(body, nullptr);
  const Result<int> anchor = body->anchor_box(hook, {-1, -1, 0.0599}, {1, 1, 1});
  ASSERT_TRUE(anchor.ok()) << anchor.message();
  scene.run(0.5);
  const auto cells_at = [&](int layer) {
    std::vector<int> cells;
    for (int c = 0; c < body->model().num_cells(); ++c) {
      if (body->model().cell_grid_index[static_cast<std::size_t>(c)].z() == layer) cells.push_back(c);
    }
    return cells;
  };
  Result<bullet::SoftBody::Cut> slab = body->remove_cells(cells_at(2));
  ASSERT_TRUE(slab.ok()) << slab.message();
  EXPECT_EQ(slab->pieces, 2);
  ASSERT_TRUE(body->anchors()[static_cast<std::size_t>(*anchor)].has_value());
  EXPECT_EQ(body->anchors()[static_cast<std::size_t>(*anchor)]->nodes.size(), 9u) << "the top face's 3 x 3 nodes";
  scene.run(1.0);
  ASSERT_TRUE(scene.world().getSoftBodyError().empty()) << scene.world().getSoftBodyError();
  double top_piece_mass = 0.0;  // the cells above the slab: 3 layers of 4
  for (int c = 0; c < body->model().num_cells(); ++c) {
    if (body->model().cell_grid_index[static_cast<std::size_t>(c)].z() >= 3) {
      top_piece_mass += body->model().materials[0].density * body->model().rest_cell_volume();
    }
  }
  const double held = -scene.world().getContactWrench(hook).force.z();
  std::printf("hook: %.5f N for the top piece's weight of %.5f N\n", held, top_piece_mass * 9.81);
  EXPECT_NEAR(held, top_piece_mass * 9.81, 0.01 * top_piece_mass * 9.81);

  Result<bullet::SoftBody::Cut> top = body->remove_cells(cells_at(5));
  ASSERT_TRUE(top.ok()) << top.message();
  EXPECT_FALSE(body->anchors()[static_cast<std::size_t>(*anchor)].has_value()) << "its nodes all left";
  const double before = body->state().positions.row(2).maxCoeff();
  scene.run(0.1);
  EXPECT_LT(body->state().positions.row(2).maxCoeff(), before - 0.01) << "nothing holds it now";
}

TEST(BulletCutting, ACutThatCannotBeMadeChangesNothing) {
  test::BulletScene scene;
  bullet::SoftBody* body = scene.add_soft(test::block({3, 3, 3}, 0.01, soft_tissue(1e4)));
  ASSERT_NE(body, nullptr);
  const std::uint64_t revision = body->model().revision;
  Result<bullet::SoftBody::Cut> out_of_range = body->remove_cells({2, 27});
  ASSERT_FALSE(out_of_range.ok());
  EXPECT_NE(out_of_range.message().find("cell 27 to remove is out of range"), std::string::npos)
      << out_of_range.message();
  std::vector<int> all(27);
  for (int c = 0; c < 27; ++c) all[static_cast<std::size_t>(c)] = c;
  Result<bullet::SoftBody::Cut> everything = body->remove_cells(all);
  ASSERT_FALSE(everything.ok());
  EXPECT_NE(everything.message().find("remove the body instead"), std::string::npos) << everything.message();
  EXPECT_EQ(body->model().revision, revision);
  EXPECT_EQ(body->model().num_cells(), 27);
}

}  // namespace
}  // namespace cubespring
