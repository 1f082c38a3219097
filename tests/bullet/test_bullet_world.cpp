// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// cubespring bodies in a Bullet world: reactions against weights and Hooke's law, momentum
// exchanged with rigid bodies, anchors, picking.
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

#include <gtest/gtest.h>

#include "bullet_scene.h"
#include "cubespring/bullet/conversions.h"
#include "cubespring/embedding.h"
#include "cubespring/shapes.h"

namespace cubespring {
namespace {

using test::at;
using test::block;
using test::BulletScene;

constexpr double kCell = 0.01;

Material tissue(double young = 1e5, double damping = 20.0) {
  Material m;
  m.young_modulus = young;
  m.poisson_ratio = 0.3;
  m.density = 1000.0;
  m.mass_damping = damping;
  return m;
}

double weight(const Model& model) { return model.total_mass() * 9.81; }

// The public conversions carry a pose to Bullet and back, and Bullet's own transform of a point
// agrees with Eigen's: the quaternion's order (x, y, z, w for Bullet, w first for Eigen) and the
// translation survive, to btScalar's precision.
TEST(BulletWorld, ConversionsCarryPosesAndVectorsBothWays) {
  const double tolerance = sizeof(btScalar) == sizeof(float) ? 1e-6 : 1e-12;
  const Eigen::Vector3d v(0.25, -1.5, 3.0);
  EXPECT_LT((bullet::to_eigen(bullet::to_bt(v)) - v).norm(), tolerance * v.norm());
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, -0.5).normalized()).toRotationMatrix();
  pose.translation() = Eigen::Vector3d(0.1, -0.2, 0.35);
  const btTransform transform = bullet::to_bt(pose);
  const Eigen::Vector3d point(0.03, 0.05, -0.02);
  EXPECT_LT((bullet::to_eigen(transform * bullet::to_bt(point)) - pose * point).norm(), 10 * tolerance);
  const Eigen::Isometry3d back = bullet::to_eigen(transform);
  EXPECT_LT((back.linear() - pose.linear()).norm(), 10 * tolerance);
  EXPECT_LT((back.translation() - pose.translation()).norm(), 10 * tolerance);
}

TEST(BulletWorld, PlaneCarriesTheWeightOfABlockResting) {
  BulletScene scene;
  btRigidBody* floor = scene.add_floor();
  bullet::SoftBody* soft = scene.add_soft(block({4, 4, 2}, kCell, tissue()));
  ASSERT_NE(soft, nullptr);
  scene.run(1.5);
  ASSERT_TRUE(scene.world().getSoftBodyError().empty()) << scene.world().getSoftBodyError();
  const bullet::ContactWrench wrench = scene.world().getContactWrench(floor);
  EXPECT_NEAR(wrench.force.z(), -weight(soft->model()), 0.01 * weight(soft->model()));
  EXPECT_NEAR(wrench.force.x(), 0.0, 1e-9);
  EXPECT_EQ(wrench.contacts, 25);  // the 5 x 5 nodes of the bottom face
  // nothing below the plane
  EXPECT_GE(soft->state().positions.row(2).minCoeff(), -1e-12);
}

// set_threads: two blocks on the plane, one given two threads between steps, keep the same bits;
// a count out of range is refused by name and changes nothing.
TEST(BulletWorld, ThreadsSetBetweenStepsKeepTheBits) {
  BulletScene one;
  BulletScene two;
  one.add_floor();
  two.add_floor();
  bullet::SoftBody* single = one.add_soft(block({8, 8, 4}, kCell, tissue(1e5)));
  bullet::SoftBody* paired = two.add_soft(block({8, 8, 4}, kCell, tissue(1e5)));
  ASSERT_NE(single, nullptr);
  ASSERT_NE(paired, nullptr);
  one.run(0.1);
  two.run(0.1);
  for (const int bad : {0, -1, bullet::SoftBody::kMaxThreads + 1}) {
    const Status refused = paired->set_threads(bad);
    EXPECT_FALSE(refused.ok());
    EXPECT_NE(refused.message().find("threads must be 1 to 256, got " + std::to_string(bad)), std::string::npos)
        << refused.message();
  }
  EXPECT_EQ(paired->threads(), 1);
  ASSERT_TRUE(paired->set_threads(2).ok());
  EXPECT_EQ(paired->threads(), 2);
  one.run(0.2);
  two.run(0.2);
  EXPECT_TRUE(single->state().positions == paired->state().positions);
  EXPECT_TRUE(single->state().velocities == paired->state().velocities);
  EXPECT_GT((single->state().positions - single->model().rest_positions).norm(), 1e-6) << "it moved";
}

// max_added_mass: a block with a stiff core takes the longer sub-step the added inertia buys, and
// rests on the plane carrying its weight, not its inertia; out of range, it is refused by name.
TEST(BulletWorld, AddedMassLengthensTheSubStepAndWeighsNothing) {
  bullet::SoftBodySettings settings = block({4, 4, 3}, kCell, tissue(2e4));
  settings.lattice.materials.push_back(tissue(2e5));  // a core 10 times as stiff
  settings.lattice.cell_material.assign(settings.lattice.cells.size(), 0);
  for (std::size_t c = 0; c < settings.lattice.cells.size(); ++c) {
    const Eigen::Vector3i& cell = settings.lattice.cells[c];
    if (cell.x() >= 1 && cell.x() <= 2 && cell.y() >= 1 && cell.y() <= 2 && cell.z() == 1) {
      settings.lattice.cell_material[c] = 1;
    }
  }
  settings.max_added_mass = 0.1;
  BulletScene scene;
  btRigidBody* floor = scene.add_floor();
  bullet::SoftBody* soft = scene.add_soft(settings);
  ASSERT_NE(soft, nullptr);
  const MassScaling& added = soft->mass_scaling();
  EXPECT_GT(added.nodes, 0);
  EXPECT_NEAR(added.added_fraction, 0.1, 1e-9);
  EXPECT_GT(added.time_step_after, 1.3 * added.time_step_before);
  EXPECT_DOUBLE_EQ(soft->sub_step(), settings.time_step_safety * added.time_step_after);
  EXPECT_DOUBLE_EQ(soft->unscaled_sub_step(), settings.time_step_safety * added.time_step_before);
  scene.run(1.5);
  ASSERT_TRUE(scene.world().getSoftBodyError().empty()) << scene.world().getSoftBodyError();
  EXPECT_NEAR(scene.world().getContactWrench(floor).force.z(), -weight(soft->model()), 0.01 * weight(soft->model()));

  settings.max_added_mass = 1.5;
  const Result<std::unique_ptr<bullet::SoftBody>> refused = bullet::SoftBody::create(settings);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.message().find("max added mass 1.5"), std::string::npos) << refused.message();
  // the implicit step is not limited by its stiffest nodes: nothing is added
  settings.max_added_mass = 0.1;
  settings.integrator = Integrator::kImplicitEuler;
  const Result<std::unique_ptr<bullet::SoftBody>> implicit = bullet::SoftBody::create(settings);
  ASSERT_TRUE(implicit.ok()) << implicit.message();
  EXPECT_EQ((*implicit)->mass_scaling().nodes, 0);
  EXPECT_EQ((*implicit)->model().inertial_mass.size(), 0);
}

TEST(BulletWorld, DroppedBoxComesToRestOnTheBlockCarriedByItsContactForce) {
  BulletScene scene;
  scene.add_floor();
  // stiffness damping: the box on the tissue is a mass on a spring that mass damping of the
  // tissue's own light nodes would hardly calm
  Material material = tissue(5e4);
  material.stiffness_damping = 0.005;
  bullet::SoftBody* soft = scene.add_soft(block({6, 6, 3}, kCell, material));
  ASSERT_NE(soft, nullptr);
  const double box_mass = 0.05;
  btRigidBody* box = scene.add_rigid(new btBoxShape(btVector3(0.015f, 0.015f, 0.005f)), box_mass, at(0, 0, 0.045));
  scene.run(2.0);
  ASSERT_TRUE(scene.world().getSoftBodyError().empty()) << scene.world().getSoftBodyError();
  const bullet::ContactWrench wrench = scene.world().getContactWrench(box);
  EXPECT_NEAR(wrench.force.z(), box_mass * 9.81, 0.02 * box_mass * 9.81);
  EXPECT_NEAR(static_cast<double>(box->getLinearVelocity().length()), 0.0, 1e-3);
  // the box's underside against the tissue's top nodes beneath it: no deeper than 10% of a cell
  const double underside = static_cast<double>(box->getWorldTransform().getOrigin().z()) - 0.005;
  double deepest = 0.0;
  for (int n = 0; n < soft->model().num_nodes(); ++n) {
    const Eigen::Vector3d x = soft->state().positions.col(n);
    if (std::abs(x.x()) < 0.0149 && std::abs(x.y()) < 0.0149) deepest = std::max(deepest, x.z() - underside);
  }
  EXPECT_LT(deepest, 0.1 * kCell);
  EXPECT_GT(underside, 0.02);  // it rests on top, 3 cells up, pressing in a little
}

// A frictionless kinematic plate wider than the block presses it by 1% of its height; the block
// stands on a frictionless plane: uniaxial stress. Returns the plate's and the floor's forces.
std::pair<double, double> flat_punch(CellModel model, CellLaw law = CellLaw::kNeoHookean) {
  BulletScene scene(Eigen::Vector3d::Zero());
  btRigidBody* floor = scene.add_floor();
  bullet::SoftBodySettings settings = block({4, 4, 4}, kCell, tissue(1e5, 50.0));
  settings.contact.friction = 0.0;
  settings.lattice.model = model;
  settings.law = law;
  bullet::SoftBody* soft = scene.add_soft(settings);
  EXPECT_NE(soft, nullptr);
  const double height = 4 * kCell;
  const double half_thickness = 0.005;
  btRigidBody* plate = scene.add_rigid(new btBoxShape(btVector3(0.05f, 0.05f, static_cast<btScalar>(half_thickness))),
                                       0.0, at(0, 0, height + half_thickness), true);
  const double strain = 0.01;
  const double step = 1.0 / 60.0;
  const int press_steps = 60;
  for (int i = 1; i <= press_steps + 60; ++i) {
    const double depth = strain * height * std::min(1.0, static_cast<double>(i) / press_steps);
    plate->setWorldTransform(at(0, 0, height + half_thickness - depth));
    scene.world().stepSimulation(static_cast<btScalar>(step), 1, static_cast<btScalar>(step));
  }
  EXPECT_TRUE(scene.world().getSoftBodyError().empty()) << scene.world().getSoftBodyError();
  return {scene.world().getContactWrench(plate).force.z(), scene.world().getContactWrench(floor).force.z()};
}

constexpr double kPunchForce = 1e5 * (4 * kCell) * (4 * kCell) * 0.01;  // E A strain [N]

TEST(BulletWorld, FlatPunchForceIsYoungsModulusTimesAreaTimesStrain) {
  const auto [plate, floor] = flat_punch(CellModel::kExactBending);
  EXPECT_NEAR(plate, kPunchForce, 0.03 * kPunchForce);
  EXPECT_NEAR(floor, -kPunchForce, 0.03 * kPunchForce);
}

// The paper's model has three zero-energy (checkerboard) modes; a face that slides freely on a
// frictionless support takes them up and the block gives way: its force comes out far below E A
// strain. The exact-bending model's twist term is there for this (docs/model-exact-bending.md).
TEST(BulletWorld, PaperModelOnFrictionlessSupportsGivesWayThroughItsZeroModes) {
  const auto [plate, floor] = flat_punch(CellModel::kBaudet2007, CellLaw::kSprings);
  EXPECT_LT(plate, 0.8 * kPunchForce);
  EXPECT_GT(plate, 0.3 * kPunchForce);
}

// The neo-Hookean law (the plugin's default) runs on exact-bending cells whatever lattice.model
// says: the paper's cells have zero-energy modes that frictionless supports set free. So a user
// who keeps LatticeDesc's default cell model gets a block that carries the punch.
TEST(BulletWorld, NeoHookeanLawRunsOnExactBendingCellsWhateverTheLatticeSays) {
  for (const CellLaw law : {CellLaw::kNeoHookean, CellLaw::kSprings}) {
    BulletScene scene(Eigen::Vector3d::Zero());
    bullet::SoftBodySettings settings = block({2, 2, 2}, kCell, tissue(1e5, 50.0));
    settings.lattice.model = CellModel::kBaudet2007;
    settings.law = law;
    bullet::SoftBody* soft = scene.add_soft(settings);
    ASSERT_NE(soft, nullptr);
    EXPECT_EQ(soft->model().cell_model,
              law == CellLaw::kNeoHookean ? CellModel::kExactBending : CellModel::kBaudet2007);
    EXPECT_EQ(soft->model().cell_law, law);
  }
  const auto [plate, floor] = flat_punch(CellModel::kBaudet2007);
  EXPECT_NEAR(plate, kPunchForce, 0.03 * kPunchForce);
}

TEST(BulletWorld, MomentumIsExchangedNotMadeWhenASphereHitsAFreeBlock) {
  BulletScene scene(Eigen::Vector3d::Zero());
  bullet::SoftBody* soft = scene.add_soft(block({4, 4, 4}, kCell, tissue(1e5, 0.0)));
  ASSERT_NE(soft, nullptr);
  const double sphere_mass = 0.02;
  btRigidBody* sphere = scene.add_rigid(new btSphereShape(0.01f), sphere_mass, at(-0.05, 0.001, 0.021));
  sphere->setDamping(0, 0);
  sphere->setLinearVelocity(btVector3(1.0f, 0, 0));
  const Eigen::Vector3d before(sphere_mass * 1.0, 0, 0);
  scene.run(0.2, 1.0 / 240.0);
  ASSERT_TRUE(scene.world().getSoftBodyError().empty()) << scene.world().getSoftBodyError();
  Eigen::Vector3d soft_momentum = Eigen::Vector3d::Zero();
  for (int n = 0; n < soft->model().num_nodes(); ++n)
    soft_momentum += soft->model().mass[n] * soft->state().velocities.col(n);
  const btVector3 v = sphere->getLinearVelocity();
  const Eigen::Vector3d after =
      soft_momentum +
      sphere_mass * Eigen::Vector3d(static_cast<double>(v.x()), static_cast<double>(v.y()), static_cast<double>(v.z()));
  EXPECT_GT(soft_momentum.x(), 0.2 * before.x());  // the hit happened
  EXPECT_LT((after - before).norm(), 0.01 * before.norm()) << "after " << after.transpose();
}

TEST(BulletWorld, AnchoredBlockHangsAndFallsWhenDetached) {
  BulletScene scene;
  btRigidBody* hook = scene.add_rigid(new btBoxShape(btVector3(0.05f, 0.05f, 0.005f)), 0.0, at(0, 0, 0.1));
  bullet::SoftBody* soft = scene.add_soft(block({2, 2, 4}, kCell, tissue(), 0.045));
  ASSERT_NE(soft, nullptr);
  // the top face's nodes, held by the hook
  const Result<int> anchor = soft->anchor_box(hook, Eigen::Vector3d(-1, -1, 0.0849), Eigen::Vector3d(1, 1, 1));
  ASSERT_TRUE(anchor.ok()) << anchor.message();
  scene.run(1.0);
  const double hanging = soft->state().positions.row(2).minCoeff();
  EXPECT_NEAR(hanging, 0.045, 0.002);  // it sags a little under its weight, no more
  // the hook carries the block's whole weight, straight down under its centre
  const bullet::ContactWrench held = scene.world().getContactWrench(hook);
  std::printf("hook: %.6f N for a weight of %.6f N\n", held.force.z(), weight(soft->model()));
  EXPECT_NEAR(held.force.z(), -weight(soft->model()), 0.01 * weight(soft->model()));
  EXPECT_NEAR(held.force.head<2>().norm(), 0.0, 1e-3 * weight(soft->model()));
  EXPECT_NEAR(held.torque.norm(), 0.0, 1e-3 * weight(soft->model()) * kCell);
  ASSERT_TRUE(soft->detach(*anchor).ok());
  scene.run(0.2);
  // a free fall against the mass damping alpha: x(t) = g / alpha (t - (1 - exp(-alpha t)) / alpha)
  const double alpha = 20.0;
  const double fall = 9.81 / alpha * (0.2 - (1.0 - std::exp(-alpha * 0.2)) / alpha);
  EXPECT_NEAR(hanging - soft->state().positions.row(2).minCoeff(), fall, 0.05 * fall);
  EXPECT_FALSE(soft->detach(*anchor).ok());
}

// One world step of 10^4 s would take about 10^8 of the block's sub-steps: the body stops at
// once, saying why, instead of stepping for hours.
TEST(BulletWorld, AWorldStepOfTooManySubStepsStopsTheBody) {
  BulletScene scene;
  bullet::SoftBody* soft = scene.add_soft(block({2, 2, 2}, kCell, tissue()));
  ASSERT_NE(soft, nullptr);
  ASSERT_LT(soft->sub_step(), 1e-2);
  const State before = soft->state();
  scene.world().stepSimulation(1e4, 0);  // no fixed steps: one step of the whole time
  const std::string error = scene.world().getSoftBodyError();
  EXPECT_NE(error.find("sub-steps of"), std::string::npos) << error;
  EXPECT_NE(error.find("step the world in shorter steps"), std::string::npos) << error;
  EXPECT_EQ(soft->last_report().status, StepStatus::kInvalidInput) << "the caller's step, not an instability";
  EXPECT_TRUE(soft->state() == before);
}

// The visual mesh is checked before its long edges are split for contact: a triangle naming a
// vertex the mesh does not have is refused by name, not read past the vertices.
TEST(BulletWorld, AVisualMeshWithABadTriangleIsRefusedByName) {
  Material material;
  material.young_modulus = 1e5;
  bullet::SoftBodySettings settings = block({2, 2, 2}, 0.01, material);
  TriangleMesh visual;
  visual.vertices.resize(3, 3);
  visual.vertices << 0, 0.02, 0, 0, 0, 0.02, 0, 0, 0;
  visual.triangles.resize(3, 1);
  visual.triangles << 0, 1, 7;
  settings.visual_mesh = visual;
  const Result<std::unique_ptr<bullet::SoftBody>> body = bullet::SoftBody::create(settings);
  ASSERT_FALSE(body.ok());
  EXPECT_NE(body.message().find("triangle 0 refers to vertex 7"), std::string::npos) << body.message();
}

TEST(BulletWorld, AnUnstableBodyStopsAndResetsToAStateSavedBefore) {
  BulletScene scene;
  scene.add_floor();
  bullet::SoftBody* soft = scene.add_soft(block({2, 2, 2}, kCell, tissue()));
  ASSERT_NE(soft, nullptr);
  scene.run(0.1);
  const State saved = soft->state();
  // a kick far beyond what the tissue can carry: the step reports it instead of running away
  soft->state().velocities.col(0).setConstant(1e6);
  scene.run(1.0 / 60.0);
  const std::string error = scene.world().getSoftBodyError();
  EXPECT_NE(error.find("soft body stopped at t = "), std::string::npos) << error;
  // the plugin chose the sub-step: the message says so, rather than asking the scene's author
  // whether their step is above the stable step
  EXPECT_NE(error.find("the plugin chose the sub-step of "), std::string::npos) << error;
  EXPECT_EQ(error.find("max_stable_time_step()"), std::string::npos) << error;
  EXPECT_EQ(error.find("mass damping"), std::string::npos) << "this tissue is damped: " << error;
  EXPECT_EQ(error, soft->stop_message());
  EXPECT_FALSE(soft->last_report().ok());
  ASSERT_TRUE(soft->state().positions.allFinite());
  const Eigen::Matrix3Xd stopped = soft->state().positions;
  scene.run(0.1);
  EXPECT_EQ(soft->state().positions, stopped);  // no longer advanced

  State wrong = saved;
  wrong.velocities.resize(3, 2);
  const Status refused = soft->reset(wrong);
  EXPECT_NE(refused.message().find("has 27 positions and 2 velocities; the body has 27 nodes"), std::string::npos)
      << refused.message();
  State not_finite = saved;
  not_finite.positions(2, 3) = std::nan("");
  EXPECT_NE(soft->reset(not_finite).message().find("NaN or infinite"), std::string::npos);
  EXPECT_EQ(soft->state().positions, stopped);  // refused resets change nothing

  ASSERT_TRUE(soft->reset(saved).ok());
  EXPECT_TRUE(scene.world().getSoftBodyError().empty());
  scene.run(0.5);
  EXPECT_TRUE(scene.world().getSoftBodyError().empty()) << scene.world().getSoftBodyError();
  EXPECT_GT(soft->state().time, saved.time + 0.45);  // it steps again, and rests where it rested
  EXPECT_LT((soft->state().positions - saved.positions).cwiseAbs().maxCoeff(), 0.05 * kCell);
}

// Tissue without mass damping keeps every vibration that contacts and tools feed it: when such a
// body goes unstable, the message names the damping and the value soft tissue needs, and a
// rigid body that outruns the contact, with its speed.
TEST(BulletWorld, AnUnstableUndampedBodyNamesItsDampingAndAFastTool) {
  BulletScene scene(Eigen::Vector3d::Zero());
  bullet::SoftBody* soft = scene.add_soft(block({2, 2, 2}, kCell, tissue(1e5, 0.0)));
  ASSERT_NE(soft, nullptr);
  // a kinematic ball flying at the block faster than a tenth of a cell per sub-step
  // (Bullet gives a kinematic body the velocity of its move over the step: 1 m in 1 ms)
  btRigidBody* ball = scene.add_rigid(new btSphereShape(btScalar(0.2 * kCell)), 0.0, at(-1.0, 0, 3 * kCell), true);
  scene.world().stepSimulation(btScalar(1e-3), 0);
  ASSERT_TRUE(scene.world().getSoftBodyError().empty());
  ball->setWorldTransform(at(0, 0, 3 * kCell));
  soft->state().velocities.col(0).setConstant(1e6);
  scene.world().stepSimulation(btScalar(1e-3), 0);
  const std::string error = scene.world().getSoftBodyError();
  EXPECT_NE(error.find("the tissue has no mass damping (Material::mass_damping = 0): soft tissue needs about 40/s"),
            std::string::npos)
      << error;
  EXPECT_NE(error.find("a rigid body near it moves at 1000 m/s"), std::string::npos) << error;
}

// A kinematic sphere pressed in and dragged at a steady speed, its pose set once per
// stepSimulation() call: returns the tissue's state after `calls` calls of `internal_steps`
// internal steps each, and its rest positions.
std::pair<State, Eigen::Matrix3Xd> dragged_sphere(int calls, int internal_steps) {
  BulletScene scene(Eigen::Vector3d::Zero());
  scene.add_floor();
  bullet::SoftBody* soft = scene.add_soft(block({4, 4, 2}, kCell, tissue()));
  EXPECT_NE(soft, nullptr);
  const double radius = 0.01;
  btRigidBody* sphere =
      scene.add_rigid(new btSphereShape(static_cast<btScalar>(radius)), 0.0, at(-0.01, 0, 0.02 + radius), true);
  const double internal = 1.0 / 256.0;  // exact in float: Bullet counts its internal steps in float
  const double call = internal_steps * internal;
  const Eigen::Vector3d velocity(0.15, 0.0, -0.06);  // [m/s]: 2.8 mm deep and 7 mm along in 47 ms
  for (int c = 1; c <= calls; ++c) {
    const Eigen::Vector3d centre = Eigen::Vector3d(-0.01, 0, 0.02 + radius) + velocity * (c * call);
    sphere->setWorldTransform(at(centre.x(), centre.y(), centre.z()));
    scene.world().stepSimulation(static_cast<btScalar>(call), internal_steps, static_cast<btScalar>(internal));
  }
  EXPECT_TRUE(scene.world().getSoftBodyError().empty()) << scene.world().getSoftBodyError();
  return {soft->state(), soft->model().rest_positions};
}

TEST(BulletWorld, AKinematicToolFollowsItsPathThroughEveryInternalStepOfACall) {
  // Bullet places a kinematic body at the call's end and gives it the mean velocity of the call;
  // the internal steps must see it where it was at their own times, as if called one by one
  const auto [one_by_one, rest] = dragged_sphere(12, 1);
  const State four_per_call = dragged_sphere(3, 4).first;
  EXPECT_NEAR(four_per_call.time, one_by_one.time, 1e-12);
  const double moved = (one_by_one.positions - rest).cwiseAbs().maxCoeff();
  EXPECT_GT(moved, 0.0015);  // the tool pressed in
  // single-precision Bullet poses: the two agree to far better than the tool's 1.25 mm per step
  EXPECT_LT((four_per_call.positions - one_by_one.positions).cwiseAbs().maxCoeff(), 1e-5);
}

TEST(BulletWorld, PickingFindsTheFaceAndNodeUnderARay) {
  BulletScene scene;
  bullet::SoftBody* soft = scene.add_soft(block({4, 4, 2}, kCell, tissue()));
  ASSERT_NE(soft, nullptr);
  const auto hit = soft->ray_test(Eigen::Vector3d(0.011, -0.009, 1.0), Eigen::Vector3d(0.011, -0.009, -1.0));
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->point.z(), 0.02, 1e-12);
  EXPECT_NEAR(hit->fraction, (1.0 - 0.02) / 2.0, 1e-12);
  // the node at (0.01, -0.01, 0.02) is the nearest corner of the hit face
  const Eigen::Vector3d node = soft->model().rest_positions.col(hit->nearest_node);
  EXPECT_LT((node - Eigen::Vector3d(0.01, -0.01, 0.02)).norm(), 1e-12);
  EXPECT_FALSE(soft->ray_test(Eigen::Vector3d(1, 1, 1), Eigen::Vector3d(1, 1, -1)).has_value());
}

// Contacts refresh only the vertices of the nodes they moved: after every step, with a visual
// mesh resting on a plane and a box pressed into it, the contact surface is where the embedding
// puts it from the nodes.
TEST(BulletWorld, ContactSurfaceFollowsTheNodesAfterEveryStep) {
  BulletScene scene;
  scene.add_floor();
  bullet::SoftBodySettings settings = block({6, 6, 6}, kCell, tissue());
  settings.visual_mesh = sphere_mesh(0.029, 3, Eigen::Vector3d(0, 0, 0.03));
  bullet::SoftBody* soft = scene.add_soft(settings);
  ASSERT_NE(soft, nullptr);
  btRigidBody* press = scene.add_rigid(new btBoxShape(btVector3(0.01f, 0.01f, 0.01f)), 0.0, at(0, 0, 0.068), true);
  Eigen::Matrix3Xd expected;
  double largest_gap = 0.0;
  for (int step = 0; step < 40; ++step) {
    const btTransform pose = at(0, 0, 0.068 - 0.0002 * step);  // 8 mm down into the top of the ball
    press->setWorldTransform(pose);
    scene.run(1.0 / 60.0);
    ASSERT_TRUE(scene.world().getSoftBodyError().empty()) << scene.world().getSoftBodyError();
    embedded_positions(soft->model(), soft->embedding(), soft->state().positions, expected);
    largest_gap = std::max(largest_gap, (soft->surface_vertices() - expected).cwiseAbs().maxCoeff());
  }
  EXPECT_LT(largest_gap, 1e-15 + 1e-12 * 0.03);
  EXPECT_GT(scene.world().getContactWrench(press).contacts, 0) << "the box presses on the ball";
}

// A ball's visual surface falls onto a table (a box, whose contacts refresh and test only the
// vertices that can have reached its top since the window around it was chosen): no vertex is
// ever found below the top by more than a sub-step's fall, though all of them were far above it
// when the window was chosen, and the table carries the ball.
TEST(BulletWorld, AVisualSurfaceFallingOntoABoxTableStaysOnItsTop) {
  BulletScene scene;
  const double top = 0.0;
  btRigidBody* table = scene.add_rigid(new btBoxShape(btVector3(0.2f, 0.2f, 0.05f)), 0.0, at(0, 0, top - 0.05));
  const double lift = 0.008;  // its lowest vertex 9 mm above the table
  bullet::SoftBodySettings settings = block({6, 6, 6}, kCell, tissue(), lift);
  settings.visual_mesh = sphere_mesh(0.029, 3, Eigen::Vector3d(0, 0, 0.03 + lift));
  bullet::SoftBody* soft = scene.add_soft(settings);
  ASSERT_NE(soft, nullptr);
  double lowest = 1.0;
  for (int step = 0; step < 600; ++step) {
    scene.run(0.001, 0.001);
    ASSERT_TRUE(scene.world().getSoftBodyError().empty()) << scene.world().getSoftBodyError();
    lowest = std::min(lowest, soft->surface_vertices().row(2).minCoeff());
  }
  EXPECT_GT(lowest, top - 1e-4);
  const bullet::ContactWrench wrench = scene.world().getContactWrench(table);
  EXPECT_NEAR(wrench.force.z(), -weight(soft->model()), 0.05 * weight(soft->model()));
}

}  // namespace
}  // namespace cubespring
