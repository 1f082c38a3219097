// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Contact of cubespring bodies with each common Bullet shape, friction against Coulomb's law, and
// a soft body hanging from a swinging dynamic body.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <utility>

#include <BulletCollision/CollisionShapes/btTriangleMesh.h>
#include <BulletCollision/CollisionShapes/btUniformScalingShape.h>
#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "bullet_scene.h"
#include "cubespring/forces.h"
#include "cubespring/material.h"

namespace cubespring {
namespace {

using test::at;
using test::block;
using test::BulletScene;

constexpr double kCell = 0.01;

Material tissue(double young = 5e4) {
  Material m;
  m.young_modulus = young;
  m.poisson_ratio = 0.3;
  m.density = 1000.0;
  m.mass_damping = 20.0;
  m.stiffness_damping = 0.005;  // calms a rigid body resting on the tissue (a mass on a spring)
  return m;
}

bullet::SoftBodySettings slab() {
  bullet::SoftBodySettings settings = block({6, 6, 3}, kCell, tissue());
  settings.lattice.model = CellModel::kExactBending;
  return settings;
}

struct ShapeCase {
  std::string name;
  std::function<btCollisionShape*()> make;
  double half_height;  ///< from the body's origin down to its lowest point [m]
  /// How far a round body settles between the surface's vertices, which are where contact acts:
  /// r - sqrt(r^2 - s^2) for vertices s apart from its lowest point [m]
  double settles_between_vertices = 0.0;
};

class DroppedShape : public ::testing::TestWithParam<int> {};

std::vector<ShapeCase> shape_cases() {
  return {
      // between 4 vertices 0.5 * sqrt(2) cells away, and between 2 rows half a cell away
      {"sphere", [] { return new btSphereShape(0.012f); }, 0.012, 0.012 - std::sqrt(0.012 * 0.012 - 0.5 * 0.01 * 0.01)},
      {"capsule", [] { return new btCapsuleShapeX(0.006f, 0.02f); }, 0.006,
       0.006 - std::sqrt(0.006 * 0.006 - 0.005 * 0.005)},
      {"cylinder", [] { return new btCylinderShapeZ(btVector3(0.012f, 0.012f, 0.005f)); }, 0.005},
      {"convex hull",
       [] {
         auto* hull = new btConvexHullShape();
         hull->setMargin(0.0005f);  // Bullet's default 4 cm margin would hold it off the floor
         for (int c = 0; c < 8; ++c) {
           hull->addPoint(
               btVector3((c & 1) ? 0.012f : -0.012f, (c & 2) ? 0.012f : -0.012f, (c & 4) ? 0.005f : -0.005f));
         }
         return hull;
       },
       0.005},
      {"compound",
       [] {
         auto* compound = new btCompoundShape();
         compound->addChildShape(at(-0.008, 0, 0), new btBoxShape(btVector3(0.006f, 0.012f, 0.005f)));
         compound->addChildShape(at(0.008, 0, 0), new btBoxShape(btVector3(0.006f, 0.012f, 0.005f)));
         return compound;
       },
       0.005},
      // shapes without an exact test of their own: the hull of their support points
      {"cone",
       [] {
         auto* cone = new btConeShapeZ(0.012f, 0.012f);  // apex up, resting on its base
         cone->setMargin(0.0005f);                       // Bullet's collision adds it around the cone
         return cone;
       },
       0.006 + 0.0005},
      // it may turn so that an end rests between 4 vertices, as the sphere does
      {"multi-sphere",
       [] {
         const btVector3 centres[2] = {btVector3(-0.008f, 0, 0), btVector3(0.008f, 0, 0)};
         const btScalar radii[2] = {0.008f, 0.008f};
         return new btMultiSphereShape(centres, radii, 2);
       },
       0.008, 0.008 - std::sqrt(0.008 * 0.008 - 0.5 * 0.01 * 0.01)},
      {"scaled sphere", [] { return new btUniformScalingShape(new btSphereShape(0.006f), 2.0f); }, 0.012,
       0.012 - std::sqrt(0.012 * 0.012 - 0.5 * 0.01 * 0.01)},
  };
}

TEST_P(DroppedShape, ComesToRestOnTheTissueCarriedByItsContactForce) {
  const ShapeCase shape = shape_cases()[static_cast<std::size_t>(GetParam())];
  BulletScene scene;
  scene.add_floor();
  bullet::SoftBody* soft = scene.add_soft(slab());
  ASSERT_NE(soft, nullptr);
  const double mass = 0.02;
  btCollisionShape* collision_shape = shape.make();
  btRigidBody* body = scene.add_rigid(collision_shape, mass, at(0, 0, 0.03 + shape.half_height + 0.003));
  // 2.5 s: a sphere first balances on the node under it, then settles between four (the surface
  // meets rigid bodies at its vertices)
  scene.run(2.5);
  ASSERT_TRUE(scene.world().getSoftBodyError().empty()) << shape.name << ": " << scene.world().getSoftBodyError();
  const bullet::ContactWrench wrench = scene.world().getContactWrench(body);
  EXPECT_NEAR(wrench.force.z(), mass * 9.81, 0.05 * mass * 9.81) << shape.name;
  EXPECT_GT(wrench.contacts, 0) << shape.name;
  const double bottom = static_cast<double>(body->getWorldTransform().getOrigin().z()) - shape.half_height;
  EXPECT_GT(bottom, 0.03 - shape.settles_between_vertices - 0.1 * kCell) << shape.name << ": sank into the tissue";
  EXPECT_LT(bottom, 0.03 + 0.1 * kCell) << shape.name << ": floats above it";
  EXPECT_LT(static_cast<double>(body->getLinearVelocity().length()), 2e-3) << shape.name;
  if (shape.name == "compound") {
    auto* compound = static_cast<btCompoundShape*>(collision_shape);
    for (int c = compound->getNumChildShapes() - 1; c >= 0; --c) delete compound->getChildShape(c);
  }
  if (shape.name == "scaled sphere") delete static_cast<btUniformScalingShape*>(collision_shape)->getChildShape();
}

INSTANTIATE_TEST_SUITE_P(EveryConvexShape, DroppedShape, ::testing::Range(0, static_cast<int>(shape_cases().size())),
                         [](const ::testing::TestParamInfo<int>& param) {
                           std::string name = shape_cases()[static_cast<std::size_t>(param.param)].name;
                           for (char& c : name)
                             if (c == ' ' || c == '-') c = '_';
                           return name;
                         });

TEST(BulletContacts, StaticTriangleMeshCarriesTheBlock) {
  BulletScene scene;
  auto* triangles = new btTriangleMesh();  // kept alive by the shape below for the test's length
  triangles->addTriangle(btVector3(-1, -1, 0), btVector3(1, -1, 0), btVector3(1, 1, 0));
  triangles->addTriangle(btVector3(-1, -1, 0), btVector3(1, 1, 0), btVector3(-1, 1, 0));
  btRigidBody* ground = scene.add_rigid(new btBvhTriangleMeshShape(triangles, true), 0.0, btTransform::getIdentity());
  bullet::SoftBody* soft = scene.add_soft(block({4, 4, 2}, kCell, tissue(1e5)));
  ASSERT_NE(soft, nullptr);
  scene.run(1.5);
  const double weight = soft->model().total_mass() * 9.81;
  EXPECT_NEAR(scene.world().getContactWrench(ground).force.z(), -weight, 0.01 * weight);
  EXPECT_GE(soft->state().positions.row(2).minCoeff(), -1e-12);
  delete triangles;
}

// A rigid box on a soft slab whose base is held, with gravity tilted by theta (a tilted slab):
// it holds when tan(theta) < mu and slides when above.
double slide_distance(double tan_theta, double friction) {
  const double theta = std::atan(tan_theta);
  BulletScene scene(Eigen::Vector3d(9.81 * std::sin(theta), 0.0, -9.81 * std::cos(theta)));
  bullet::SoftBodySettings settings = block({8, 6, 2}, kCell, tissue(1e5));
  settings.lattice.model = CellModel::kExactBending;
  settings.contact.friction = friction;
  bullet::SoftBody* soft = scene.add_soft(settings);
  EXPECT_NE(soft, nullptr);
  EXPECT_TRUE(
      soft->constraints().fix_box(soft->model(), Eigen::Vector3d(-1, -1, -1e-9), Eigen::Vector3d(1, 1, 1e-9)).ok());
  btRigidBody* box = scene.add_rigid(new btBoxShape(btVector3(0.015f, 0.015f, 0.005f)), 0.02, at(-0.01, 0, 0.0251));
  scene.run(0.3);
  const double start = static_cast<double>(box->getWorldTransform().getOrigin().x());
  scene.run(0.5);
  return static_cast<double>(box->getWorldTransform().getOrigin().x()) - start;
}

TEST(BulletContacts, FrictionHoldsBelowTheCoulombAngle) {
  const double mu = 0.5;
  EXPECT_LT(std::abs(slide_distance(0.8 * mu, mu)), 0.05 * kCell);
}

struct Slide {
  double distance;      ///< [m]
  double acceleration;  ///< fitted to the path, x = x0 + v0 t + a t^2 / 2 [m/s^2]
};

// Gravity on a floor tilted by theta about y, tan(theta) given [m/s^2].
btVector3 tilted_gravity(double tan_theta) {
  const double theta = std::atan(tan_theta);
  return btVector3(static_cast<btScalar>(9.81 * std::sin(theta)), 0, static_cast<btScalar>(-9.81 * std::cos(theta)));
}

// The box of slide_distance on a slab long enough to slide along: it settles where it holds
// (tan = 0.8 mu), then the slab is tilted to tan(theta) and the box's path is sampled every step.
Slide slide_after_tilting(double tan_theta, double friction, double seconds) {
  BulletScene scene;
  scene.world().setGravity(tilted_gravity(0.8 * friction));
  bullet::SoftBodySettings settings = block({24, 6, 2}, kCell, tissue(1e5));
  settings.lattice.model = CellModel::kExactBending;
  settings.contact.friction = friction;
  bullet::SoftBody* soft = scene.add_soft(settings);
  EXPECT_NE(soft, nullptr);
  EXPECT_TRUE(
      soft->constraints().fix_box(soft->model(), Eigen::Vector3d(-1, -1, -1e-9), Eigen::Vector3d(1, 1, 1e-9)).ok());
  btRigidBody* box = scene.add_rigid(new btBoxShape(btVector3(0.015f, 0.015f, 0.005f)), 0.02, at(-0.08, 0, 0.0251));
  scene.run(0.3);
  scene.world().setGravity(tilted_gravity(tan_theta));  // the world passes it on to the box
  const double start = static_cast<double>(box->getWorldTransform().getOrigin().x());
  const double step = 1.0 / 60.0;
  const int steps = static_cast<int>(seconds / step + 0.5);
  Eigen::MatrixXd powers(steps, 3);
  Eigen::VectorXd path(steps);
  for (int i = 0; i < steps; ++i) {
    scene.run(step);
    const double t = (i + 1) * step;
    powers.row(i) << 1.0, t, 0.5 * t * t;
    path(i) = static_cast<double>(box->getWorldTransform().getOrigin().x()) - start;
  }
  EXPECT_TRUE(scene.world().getSoftBodyError().empty()) << scene.world().getSoftBodyError();
  const Eigen::Vector3d fit = powers.colPivHouseholderQr().solve(path);
  return {path(steps - 1), fit(2)};
}

// Above the angle the box slides as a block on a rigid incline would, a = g (sin - mu cos): the
// tissue adds its shear and the vertices the leading edge presses down, which may cost a little.
TEST(BulletContacts, FrictionSlidesAboveTheCoulombAngle) {
  const double mu = 0.5;
  const double tan_theta = 1.25 * mu;
  const double theta = std::atan(tan_theta);
  const double coulomb = 9.81 * (std::sin(theta) - mu * std::cos(theta));  // 1.04 m/s^2
  const Slide slide = slide_after_tilting(tan_theta, mu, 0.5);
  RecordProperty("acceleration_over_coulomb", std::to_string(slide.acceleration / coulomb));
  std::printf("slid %.1f cells in 0.5 s; acceleration %.3f m/s^2, Coulomb's %.3f m/s^2\n", slide.distance / kCell,
              slide.acceleration, coulomb);
  EXPECT_GT(slide.distance, 5 * kCell);
  EXPECT_NEAR(slide.acceleration, coulomb, 0.1 * coulomb);
}

// A soft block standing on a floor tilted by theta (gravity tilted; the floor's friction mu): the
// mean of its nodes' x, sampled every step over `seconds` after `settle` s at tan = 0.8 mu, the
// floor then tilted to tan(theta).
Eigen::VectorXd soft_block_path(double tan_theta, double friction, const Material& material, double settle,
                                double seconds) {
  BulletScene scene;
  scene.world().setGravity(tilted_gravity(0.8 * friction));
  scene.add_floor();
  bullet::SoftBodySettings settings = block({4, 4, 4}, kCell, material);
  settings.lattice.model = CellModel::kExactBending;
  settings.contact.friction = friction;
  bullet::SoftBody* soft = scene.add_soft(settings);
  EXPECT_NE(soft, nullptr);
  if (soft == nullptr) return {};
  scene.run(settle);
  scene.world().setGravity(tilted_gravity(tan_theta));
  const double step = 1.0 / 60.0;
  Eigen::VectorXd path(static_cast<int>(seconds / step + 0.5) + 1);
  path(0) = soft->state().positions.row(0).mean();
  for (int i = 1; i < path.size(); ++i) {
    scene.run(step);
    path(i) = soft->state().positions.row(0).mean();
  }
  EXPECT_TRUE(scene.world().getSoftBodyError().empty()) << scene.world().getSoftBodyError();
  return path;
}

// Coulomb's law holds the block still below its angle. Friction stopped the sliding only in the
// velocities, after the sub-step's drift had moved the nodes by dt^2 times their tangential
// acceleration, until 2026-12-06: the block crept 24 mm down in this second.
TEST(BulletContacts, FrictionHoldsASoftBlockStillBelowTheCoulombAngle) {
  const double mu = 0.5;
  const Eigen::VectorXd path = soft_block_path(0.8 * mu, mu, soft_tissue(1e4), 0.5, 1.0);
  ASSERT_GT(path.size(), 1);
  const double creep = path(path.size() - 1) - path(0);
  std::printf("crept %.4f mm in 1 s\n", 1e3 * creep);
  EXPECT_LT(std::abs(creep), 1e-4);
}

// Above the angle every node on the floor slides, and the block's centre of mass accelerates as a
// block on a rigid incline does, g (sin - mu cos) (no mass damping, which would brake it).
TEST(BulletContacts, FrictionLetsASoftBlockSlideAboveTheCoulombAngle) {
  const double mu = 0.5;
  const double tan_theta = 1.25 * mu;
  const double theta = std::atan(tan_theta);
  const double coulomb = 9.81 * (std::sin(theta) - mu * std::cos(theta));
  Material material = soft_tissue(1e4);
  material.mass_damping = 0.0;
  material.stiffness_damping = 0.005;
  const double seconds = 0.5;
  const Eigen::VectorXd path = soft_block_path(tan_theta, mu, material, 0.5, seconds);
  ASSERT_GT(path.size(), 2);
  Eigen::MatrixXd powers(path.size(), 3);
  for (int i = 0; i < path.size(); ++i) {
    const double t = seconds * i / static_cast<double>(path.size() - 1);
    powers.row(i) << 1.0, t, 0.5 * t * t;
  }
  const Eigen::Vector3d fit = powers.colPivHouseholderQr().solve(path);
  std::printf("slid %.1f mm in %.1f s; acceleration %.3f m/s^2, Coulomb's %.3f m/s^2\n",
              1e3 * (path(path.size() - 1) - path(0)), seconds, fit(2), coulomb);
  EXPECT_NEAR(fit(2), coulomb, 0.05 * coulomb);
}

TEST(BulletContacts, BlockHangingFromASwingingDynamicBodyStaysStable) {
  BulletScene scene;
  btRigidBody* carrier = scene.add_rigid(new btBoxShape(btVector3(0.02f, 0.02f, 0.005f)), 0.1, at(0.03, 0, 0.1));
  btPoint2PointConstraint pivot(*carrier, btVector3(-0.03f, 0, 0.0f));
  scene.world().addConstraint(&pivot);
  Material material = tissue(1e5);
  material.stiffness_damping = 0.0;
  bullet::SoftBodySettings settings = block({2, 2, 4}, kCell, material, 0.055);
  settings.lattice.origin.x() += 0.03;  // under the carrier
  bullet::SoftBody* soft = scene.add_soft(settings);
  ASSERT_NE(soft, nullptr);
  const Result<int> anchor = soft->anchor_box(carrier, Eigen::Vector3d(-1, -1, 0.0949), Eigen::Vector3d(1, 1, 1));
  ASSERT_TRUE(anchor.ok()) << anchor.message();
  // total energy: the soft body's kinetic, elastic and potential, the carrier's kinetic and potential
  const auto energy = [&] {
    const Eigen::Vector3d g(0, 0, -9.81);
    double e = kinetic_energy(soft->model(), soft->state()) + elastic_energy(soft->model(), soft->state().positions);
    for (int n = 0; n < soft->model().num_nodes(); ++n)
      e -= soft->model().mass[n] * g.dot(soft->state().positions.col(n));
    const double v = static_cast<double>(carrier->getLinearVelocity().length());
    e += 0.5 * 0.1 * v * v + 0.1 * 9.81 * static_cast<double>(carrier->getWorldTransform().getOrigin().z());
    return e;
  };
  carrier->setLinearVelocity(btVector3(0, 0.2f, 0));  // a push to swing it
  scene.run(5.0);
  const double at_five = energy();
  scene.run(5.0);
  ASSERT_TRUE(scene.world().getSoftBodyError().empty()) << scene.world().getSoftBodyError();
  EXPECT_TRUE(soft->state().positions.allFinite());
  EXPECT_LE(energy(), at_five + 1e-6);
  // the anchored nodes still sit near where the carrier holds them: a dynamic body pulls them by
  // a spring as stiff as the sub-step allows, which lags the swing by a few millimetres at
  // Bullet's 1/60 s step (docs/bullet-plugin.md section 5)
  const bullet::Anchor& held = *soft->anchors()[static_cast<std::size_t>(*anchor)];
  for (std::size_t i = 0; i < held.nodes.size(); ++i) {
    const btVector3 target =
        carrier->getWorldTransform() * btVector3(static_cast<btScalar>(held.local(0, static_cast<Eigen::Index>(i))),
                                                 static_cast<btScalar>(held.local(1, static_cast<Eigen::Index>(i))),
                                                 static_cast<btScalar>(held.local(2, static_cast<Eigen::Index>(i))));
    const Eigen::Vector3d x = soft->state().positions.col(held.nodes[i]);
    EXPECT_LT((x - Eigen::Vector3d(static_cast<double>(target.x()), static_cast<double>(target.y()),
                                   static_cast<double>(target.z())))
                  .norm(),
              0.5 * kCell);
  }
  scene.world().removeConstraint(&pivot);
}

}  // namespace
}  // namespace cubespring

namespace cubespring {
namespace {

// A kinematic capsule a quarter cell thick, pressed half a cell into a block and swept 10 cells
// along it at 1 m/s in 1 ms steps: the tip must not pass between the surface's vertices.
double deepest_sweep_penetration(bool face_contacts) {
  BulletScene scene(Eigen::Vector3d::Zero());
  scene.add_floor();
  bullet::SoftBodySettings settings = block({14, 4, 3}, kCell, tissue(1e5));
  settings.lattice.model = CellModel::kExactBending;
  settings.contact.face_contacts = face_contacts;
  bullet::SoftBody* soft = scene.add_soft(settings);
  EXPECT_NE(soft, nullptr);
  EXPECT_TRUE(
      soft->constraints().fix_box(soft->model(), Eigen::Vector3d(-1, -1, -1e-9), Eigen::Vector3d(1, 1, 1e-9)).ok());
  const double radius = 0.25 * kCell;
  const double half_height = 0.01;
  btRigidBody* tool =
      scene.add_rigid(new btCapsuleShapeZ(static_cast<btScalar>(radius), static_cast<btScalar>(2 * half_height)), 0.0,
                      at(-0.055, 0.0012, 0.03 + radius + half_height), true);
  const double top = 3 * kCell;
  const double step = 1e-3;
  double deepest = 0.0;
  for (int i = 1; i <= 150; ++i) {
    const double t = i * step;
    // press half a cell over 50 ms, then sweep 10 cells at 1 m/s
    const double depth = 0.5 * kCell * std::min(1.0, t / 0.05);
    const double x = -0.055 + std::max(0.0, t - 0.05) * 1.0;
    const double tip = top - depth;
    tool->setWorldTransform(at(x, 0.0012, tip + radius + half_height));
    scene.world().stepSimulation(static_cast<btScalar>(step), 1, static_cast<btScalar>(step));
    // how far the tip is below the tissue surface right under it: the surface triangle above
    // the tip, by a vertical ray from high above
    const auto hit = soft->ray_test(Eigen::Vector3d(x, 0.0012, 1.0), Eigen::Vector3d(x, 0.0012, -1.0));
    if (hit) deepest = std::max(deepest, hit->point.z() - tip);
  }
  return deepest;
}

TEST(BulletContacts, ThinToolSweptAcrossTheSurfaceDoesNotSlipBetweenVertices) {
  const double with_faces = deepest_sweep_penetration(true);
  RecordProperty("deepest_penetration_cells", std::to_string(with_faces / kCell));
  std::printf("deepest penetration of the swept capsule: %.3f cell (vertex contacts alone: %.3f cell)\n",
              with_faces / kCell, deepest_sweep_penetration(false) / kCell);
  EXPECT_LT(with_faces, 0.1 * kCell);
}

}  // namespace
}  // namespace cubespring

namespace cubespring {
namespace {

// A slab between the floor and a kinematic plate wider than it, held by friction alone (mu = 2, so
// that nothing slides): the plate presses it by 1% of its height, then moves sideways by 1% and
// holds. Stuck top and bottom, the slab is in simple shear. Returns the plate's sideways force
// 0.5 s and 2 s after the shear [N].
std::pair<double, double> sheared_slab_forces() {
  BulletScene scene(Eigen::Vector3d::Zero());
  scene.add_floor();
  Material material = tissue(1e5);
  material.mass_damping = 50.0;
  material.stiffness_damping = 0.0;
  bullet::SoftBodySettings settings = block({8, 8, 2}, kCell, material);
  settings.lattice.model = CellModel::kExactBending;
  settings.contact.friction = 2.0;
  bullet::SoftBody* soft = scene.add_soft(settings);
  EXPECT_NE(soft, nullptr);
  const double height = 2 * kCell;
  const double half = 0.005;
  btRigidBody* plate =
      scene.add_rigid(new btBoxShape(btVector3(0.06f, 0.06f, btScalar(half))), 0.0, at(0, 0, height + half), true);
  const double step = 1.0 / 60.0;
  const double press = 0.01 * height;
  const double shear = 0.01 * height;
  double early = 0.0;
  for (int i = 1; i <= 30 + 30 + 120; ++i) {
    const double down = press * std::min(1.0, i / 30.0);
    const double side = shear * std::clamp((i - 30) / 30.0, 0.0, 1.0);
    plate->setWorldTransform(at(side, 0, height + half - down));
    scene.world().stepSimulation(static_cast<btScalar>(step), 1, static_cast<btScalar>(step));
    if (i == 60 + 30) early = scene.world().getContactWrench(plate).force.x();
  }
  EXPECT_TRUE(scene.world().getSoftBodyError().empty()) << scene.world().getSoftBodyError();
  return {early, scene.world().getContactWrench(plate).force.x()};
}

// It carries G A gamma (the shear of a slab 4 times wider than high; its free sides and bending
// take a few percent) and keeps it. While friction acted on the velocities alone, the contacts
// crept until the slab carried no shear: 0.0000 N.
TEST(BulletContacts, FrictionHoldsASlabInSimpleShear) {
  const auto [early, late] = sheared_slab_forces();
  const double shear_modulus = 1e5 / (2 * 1.3);
  const double gamma = 0.01 / 0.99;  // the sideways move over the pressed height
  const double expected = shear_modulus * (8 * kCell) * (8 * kCell) * gamma;
  std::printf("plate force x %.4f N after 0.5 s, %.4f N after 2 s; G A gamma %.4f N\n", early, late, expected);
  EXPECT_NEAR(-late, expected, 0.1 * expected);
  EXPECT_NEAR(late, early, 0.01 * std::abs(early)) << "it holds";
}

}  // namespace
}  // namespace cubespring
