// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// ContactSettings::offset, the contact's one length: a block rests that far above a plane and a
// triangle mesh at millimetre, centimetre and metre scales with the plane carrying its weight, a
// box rests that far above a slab, and bad values are refused by name.
#include <cmath>
#include <string>

#include <BulletCollision/CollisionShapes/btTriangleMesh.h>
#include <gtest/gtest.h>

#include "bullet_scene.h"

namespace cubespring {
namespace {

using test::at;
using test::block;
using test::BulletScene;

// E scaled with the cell so that every scale sags the same fraction of a cell under gravity
// (rho g h / E fixed); damping scaled with the time a wave takes to cross a cell.
Material tissue_at_scale(double h) {
  Material m;
  m.young_modulus = 1e5 * h / 0.01;
  m.poisson_ratio = 0.3;
  m.density = 1000.0;
  m.mass_damping = 20.0 * std::sqrt(0.01 / h);
  return m;
}

struct Ground {
  const char* name;
  bool triangle_mesh;
};

class OffsetAtScale : public ::testing::TestWithParam<std::tuple<double, Ground>> {};

TEST_P(OffsetAtScale, BlockRestsOffsetAboveTheGroundWhichCarriesItsWeight) {
  const double h = std::get<0>(GetParam());
  const Ground ground = std::get<1>(GetParam());
  const double offset = 0.2 * h;
  BulletScene scene;
  btRigidBody* floor = nullptr;
  btTriangleMesh triangles;
  if (ground.triangle_mesh) {
    const auto e = static_cast<btScalar>(10 * h);
    triangles.addTriangle(btVector3(-e, -e, 0), btVector3(e, -e, 0), btVector3(e, e, 0));
    triangles.addTriangle(btVector3(-e, -e, 0), btVector3(e, e, 0), btVector3(-e, e, 0));
    floor = scene.add_rigid(new btBvhTriangleMeshShape(&triangles, true), 0.0, btTransform::getIdentity());
  } else {
    floor = scene.add_floor();
  }
  bullet::SoftBodySettings settings = block({4, 4, 2}, h, tissue_at_scale(h), offset);
  settings.contact.offset = offset;
  bullet::SoftBody* soft = scene.add_soft(settings);
  ASSERT_NE(soft, nullptr);
  // 1.5 s at 1 cm; the block's own times go with sqrt(h)
  scene.run(1.5 * std::sqrt(h / 0.01));
  ASSERT_TRUE(scene.world().getSoftBodyError().empty()) << scene.world().getSoftBodyError();
  const double weight = soft->model().total_mass() * 9.81;
  const bullet::ContactWrench wrench = scene.world().getContactWrench(floor);
  EXPECT_NEAR(wrench.force.z(), -weight, 0.01 * weight) << ground.name << ", h = " << h;
  EXPECT_EQ(wrench.contacts, 25) << ground.name << ", h = " << h;
  // the bottom nodes end each sub-step projected onto the skin, not the surface
  const Eigen::VectorXd z = soft->state().positions.row(2).transpose();
  EXPECT_NEAR(z.minCoeff(), offset, 1e-6 * h) << ground.name << ", h = " << h;
  int on_skin = 0;
  for (Eigen::Index n = 0; n < z.size(); ++n) on_skin += std::abs(z[n] - offset) < 1e-6 * h;
  EXPECT_EQ(on_skin, 25) << ground.name << ", h = " << h;
}

INSTANTIATE_TEST_SUITE_P(MillimetreToMetre, OffsetAtScale,
                         ::testing::Combine(::testing::Values(0.001, 0.01, 1.0),
                                            ::testing::Values(Ground{"plane", false}, Ground{"triangle_mesh", true})),
                         [](const ::testing::TestParamInfo<std::tuple<double, Ground>>& param) {
                           const double h = std::get<0>(param.param);
                           return std::string(std::get<1>(param.param).name) + (h < 0.005 ? "_1mm"
                                                                                : h < 0.5 ? "_1cm"
                                                                                          : "_1m");
                         });

TEST(ContactOffset, DroppedBoxRestsOffsetAboveTheSlabCarriedByItsContactForce) {
  constexpr double kCell = 0.01;
  const double offset = 0.3 * kCell;
  BulletScene scene;
  scene.add_floor();
  Material m = tissue_at_scale(kCell);
  m.young_modulus = 5e4;
  m.stiffness_damping = 0.005;
  bullet::SoftBodySettings settings = block({6, 6, 3}, kCell, m);
  settings.lattice.model = CellModel::kExactBending;
  settings.contact.offset = offset;
  bullet::SoftBody* soft = scene.add_soft(settings);
  ASSERT_NE(soft, nullptr);
  const double mass = 0.02;
  const double half = 0.005;
  btRigidBody* box = scene.add_rigid(new btBoxShape(btVector3(0.012f, 0.012f, static_cast<btScalar>(half))), mass,
                                     at(0, 0, 0.03 + offset + half + 0.003));
  scene.run(2.0);
  ASSERT_TRUE(scene.world().getSoftBodyError().empty()) << scene.world().getSoftBodyError();
  EXPECT_NEAR(scene.world().getContactWrench(box).force.z(), mass * 9.81, 0.05 * mass * 9.81);
  // the box's bottom face is the skin's distance above the slab's top nodes under it
  const double bottom = static_cast<double>(box->getWorldTransform().getOrigin().z()) - half;
  double top = -1.0;
  const Eigen::Matrix3Xd& x = soft->state().positions;
  for (Eigen::Index n = 0; n < x.cols(); ++n) {
    if (std::abs(x(0, n)) < 0.01 && std::abs(x(1, n)) < 0.01) top = std::max(top, x(2, n));
  }
  // (to 0.2% of a cell: the box moves on after the sub-step that projected the nodes)
  EXPECT_NEAR(bottom - top, offset, 0.002 * kCell)
      << "box bottom " << bottom << " m, slab top under it " << top << " m";
}

TEST(ContactOffset, NegativeOrNotFiniteLengthsAreRefusedByName) {
  const struct {
    double offset, max_depth;
    const char* named;
  } cases[] = {
      {-0.001, 0.0, "contact offset"}, {std::nan(""), 0.0, "contact offset"}, {0.0, -1.0, "contact max_depth"}};
  for (const auto& c : cases) {
    bullet::SoftBodySettings settings = block({2, 2, 2}, 0.01, tissue_at_scale(0.01));
    settings.contact.offset = c.offset;
    settings.contact.max_depth = c.max_depth;
    const Result<std::unique_ptr<bullet::SoftBody>> body = bullet::SoftBody::create(settings);
    ASSERT_FALSE(body.ok()) << c.named;
    EXPECT_NE(body.message().find(c.named), std::string::npos) << body.message();
  }
}

}  // namespace
}  // namespace cubespring
