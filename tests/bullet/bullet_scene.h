// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// A Bullet world with cubespring soft bodies, owning everything it creates: the fixture of the
// plugin's tests.
#pragma once

#include <memory>
#include <vector>

#include <btBulletDynamicsCommon.h>
#include <gtest/gtest.h>

#include "cubespring/bullet/world.h"

namespace cubespring::test {

class BulletScene {
 public:
  explicit BulletScene(const Eigen::Vector3d& gravity = Eigen::Vector3d(0, 0, -9.81))
      : dispatcher_(&configuration_), world_(&dispatcher_, &broadphase_, &solver_, &configuration_) {
    world_.setGravity(btVector3(static_cast<btScalar>(gravity.x()), static_cast<btScalar>(gravity.y()),
                                static_cast<btScalar>(gravity.z())));
  }
  ~BulletScene() {
    for (auto& body : rigid_bodies_) world_.removeRigidBody(body.get());
    for (auto& body : soft_bodies_) world_.removeSoftBody(body.get());
  }

  bullet::World& world() { return world_; }

  /// A rigid body of the given shape: mass 0 for static; kinematic when asked.
  btRigidBody* add_rigid(btCollisionShape* shape, double mass, const btTransform& transform, bool kinematic = false) {
    shapes_.emplace_back(shape);
    btVector3 inertia(0, 0, 0);
    if (mass > 0) shape->calculateLocalInertia(static_cast<btScalar>(mass), inertia);
    btRigidBody::btRigidBodyConstructionInfo info(static_cast<btScalar>(mass), nullptr, shape, inertia);
    info.m_startWorldTransform = transform;
    info.m_friction = 0;
    rigid_bodies_.push_back(std::make_unique<btRigidBody>(info));
    btRigidBody* body = rigid_bodies_.back().get();
    if (kinematic) {
      body->setCollisionFlags(body->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
      body->setActivationState(DISABLE_DEACTIVATION);
    }
    if (mass > 0) body->setActivationState(DISABLE_DEACTIVATION);
    world_.addRigidBody(body);
    return body;
  }

  /// The static plane z = height, normal +z.
  btRigidBody* add_floor(double height = 0.0) {
    return add_rigid(new btStaticPlaneShape(btVector3(0, 0, 1), static_cast<btScalar>(height)), 0.0,
                     btTransform::getIdentity());
  }

  bullet::SoftBody* add_soft(const bullet::SoftBodySettings& settings) {
    Result<std::unique_ptr<bullet::SoftBody>> body = bullet::SoftBody::create(settings);
    EXPECT_TRUE(body.ok()) << body.message();
    if (!body.ok()) return nullptr;
    soft_bodies_.push_back(std::move(body).value());
    world_.addSoftBody(soft_bodies_.back().get());
    return soft_bodies_.back().get();
  }

  /// Steps at Bullet's usual 1/60 s for a simulated duration.
  void run(double seconds, double step = 1.0 / 60.0) {
    const int steps = static_cast<int>(seconds / step + 0.5);
    for (int i = 0; i < steps; ++i) world_.stepSimulation(static_cast<btScalar>(step), 1, static_cast<btScalar>(step));
  }

 private:
  btDefaultCollisionConfiguration configuration_;
  btCollisionDispatcher dispatcher_;
  btDbvtBroadphase broadphase_;
  btSequentialImpulseConstraintSolver solver_;
  bullet::World world_;
  std::vector<std::unique_ptr<btCollisionShape>> shapes_;
  std::vector<std::unique_ptr<btRigidBody>> rigid_bodies_;
  std::vector<std::unique_ptr<bullet::SoftBody>> soft_bodies_;
};

inline btTransform at(double x, double y, double z) {
  return btTransform(btQuaternion::getIdentity(),
                     btVector3(static_cast<btScalar>(x), static_cast<btScalar>(y), static_cast<btScalar>(z)));
}

/// A block of cells of size h [m] from z = base up, centred on x = y = 0.
inline bullet::SoftBodySettings block(const Eigen::Vector3i& cells, double h, const Material& material,
                                      double base = 0.0) {
  bullet::SoftBodySettings settings;
  settings.lattice = box_lattice(cells, Eigen::Vector3d::Constant(h), material);
  settings.lattice.origin = Eigen::Vector3d(-0.5 * cells.x() * h, -0.5 * cells.y() * h, base);
  return settings;
}

/// The contact issue's block on the ground: 10 x 10 x 5 cm of 5 kPa tissue (nu = 0.45, density
/// 1060, mass damping 40/s) in exact-bending cells of 5 mm, centred on x = y = 0, its base at z = 0.
inline bullet::SoftBody* add_tissue_block(BulletScene& scene, double friction = 0.3) {
  Material tissue;
  tissue.young_modulus = 5e3;
  tissue.poisson_ratio = 0.45;
  tissue.density = 1060;
  tissue.mass_damping = 40;
  bullet::SoftBodySettings settings = block({20, 20, 10}, 0.005, tissue);
  settings.lattice.model = CellModel::kExactBending;
  settings.contact.friction = friction;
  scene.add_floor();
  return scene.add_soft(settings);
}

}  // namespace cubespring::test
