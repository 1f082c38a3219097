// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "cubespring/haptics/coupled_tool.h"

#include <cstdio>

#include "cubespring/bullet/conversions.h"

namespace cubespring::haptics {

using bullet::to_bt;
using bullet::to_eigen;

Result<CoupledTool> CoupledTool::create(btDiscreteDynamicsWorld& world, btRigidBody& body, double mass,
                                        const Eigen::Isometry3d& tip, const CouplingSettings& settings) {
  if (body.getCollisionShape() == nullptr) return Status::error("the tool's body has no collision shape");
  if (!(mass >= 1e-6 && mass <= 1e6)) {
    char text[96];
    std::snprintf(text, sizeof text, "tool mass %.4g kg: must be a number from 1e-06 to 1e+06 kg", mass);
    return Status::error(text);
  }
  btVector3 inertia(0, 0, 0);
  body.getCollisionShape()->calculateLocalInertia(static_cast<btScalar>(mass), inertia);
  ToolInertia tool;
  tool.mass = mass;
  tool.principal_inertia = to_eigen(inertia);
  tool.tip = tip;
  Result<VirtualCoupling> coupling = VirtualCoupling::create(settings, tool);
  if (!coupling) return coupling.status();

  // Bullet sorts bodies into static, kinematic and dynamic when they are added: take it out
  // first, and put it back into the same collision groups
  const btBroadphaseProxy* proxy = body.getBroadphaseHandle();
  const int group = proxy != nullptr ? proxy->m_collisionFilterGroup : int(btBroadphaseProxy::DefaultFilter);
  const int mask = proxy != nullptr ? proxy->m_collisionFilterMask : int(btBroadphaseProxy::AllFilter);
  world.removeRigidBody(&body);
  body.setCollisionFlags(body.getCollisionFlags() & ~btCollisionObject::CF_KINEMATIC_OBJECT &
                         ~btCollisionObject::CF_STATIC_OBJECT);
  body.setMassProps(static_cast<btScalar>(mass), inertia);
  body.updateInertiaTensor();
  body.setFlags(body.getFlags() | BT_DISABLE_WORLD_GRAVITY);
  world.addRigidBody(&body, group, mask);
  body.setGravity(btVector3(0, 0, 0));
  body.setLinearVelocity(btVector3(0, 0, 0));
  body.setAngularVelocity(btVector3(0, 0, 0));
  body.forceActivationState(DISABLE_DEACTIVATION);
  return CoupledTool(body, *coupling);
}

BodyState CoupledTool::state() const {
  BodyState state;
  state.pose = to_eigen(body_->getCenterOfMassTransform());
  state.linear_velocity = to_eigen(body_->getLinearVelocity());
  state.angular_velocity = to_eigen(body_->getAngularVelocity());
  return state;
}

Eigen::Isometry3d CoupledTool::tool_frame() const { return state().pose * coupling_.tool().tip; }

Wrench CoupledTool::couple(const DeviceState& device) {
  const Wrench wrench = coupling_.on_tool(device, state());
  body_->applyCentralForce(to_bt(wrench.force));
  body_->applyTorque(to_bt(wrench.torque));
  return wrench;
}

void CoupledTool::place_at(const DeviceState& device) {
  const Eigen::Isometry3d pose = coupling_.body_pose_for(device.pose);
  body_->setCenterOfMassTransform(to_bt(pose));
  body_->setLinearVelocity(to_bt(Eigen::Vector3d(
      device.linear_velocity + device.angular_velocity.cross(pose.translation() - device.pose.translation()))));
  body_->setAngularVelocity(to_bt(device.angular_velocity));
  body_->clearForces();
}

}  // namespace cubespring::haptics
