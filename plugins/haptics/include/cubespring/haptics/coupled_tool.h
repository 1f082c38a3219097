// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// A rigid tool in a cubespring::bullet::World that a haptic device drives through a virtual
// coupling: each world step it takes the coupling's force and torque towards the device's last
// pose, and the tissue and Bullet's bodies stop it where they stand in its way. Units are SI.
#pragma once

#include <btBulletDynamicsCommon.h>

#include "cubespring/haptics/virtual_coupling.h"
#include "cubespring/result.h"

namespace cubespring::haptics {

class CoupledTool {
 public:
  /// Makes `body`, already in `world` (a scripted, kinematic tool or a dynamic body), a dynamic
  /// body of `mass` [kg] with its collision shape's inertia, that never sleeps and has no weight:
  /// the hand holding the device carries it. `tip` is the tool's frame (the device's point) in the
  /// body's centre-of-mass frame. Its collision groups stay. A body a Bullet joint holds is moved
  /// by Bullet's step alone (the soft sub-steps leave jointed bodies to it), so its coupling acts
  /// there only. Errors name the setting at fault.
  static Result<CoupledTool> create(btDiscreteDynamicsWorld& world, btRigidBody& body, double mass,
                                    const Eigen::Isometry3d& tip, const CouplingSettings& settings);

  /// Before a world step: gives the body the coupling's force and torque towards `device` for the
  /// step (Bullet clears them after it), and returns them (on the tool, torque about its centre
  /// of mass).
  Wrench couple(const DeviceState& device);
  /// Puts the tool where the device is, at the device's velocity: at the start of a session.
  void place_at(const DeviceState& device);

  BodyState state() const;
  /// The world pose of the tool's frame (its tip) now.
  Eigen::Isometry3d tool_frame() const;
  const VirtualCoupling& coupling() const { return coupling_; }
  btRigidBody& body() { return *body_; }

 private:
  CoupledTool(btRigidBody& body, const VirtualCoupling& coupling) : body_(&body), coupling_(coupling) {}
  btRigidBody* body_;
  VirtualCoupling coupling_;
};

}  // namespace cubespring::haptics
