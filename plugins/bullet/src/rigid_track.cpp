// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "rigid_track.h"

#include <LinearMath/btTransformUtil.h>

#include "cubespring/bullet/conversions.h"

namespace cubespring::bullet {

namespace {

Eigen::Matrix3d to_eigen(const btMatrix3x3& m) {
  Eigen::Matrix3d out;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) out(r, c) = static_cast<double>(m[r][c]);
  return out;
}

}  // namespace

Eigen::Vector3d RigidTrack::centre() const { return bullet::to_eigen(transform.getOrigin()); }

Eigen::Vector3d RigidTrack::velocity_at(const Eigen::Vector3d& point) const {
  return linear_velocity + angular_velocity.cross(point - centre());
}

void RigidTrack::receive(const Eigen::Vector3d& impulse_on_body, const Eigen::Vector3d& point, bool contact) {
  const Eigen::Vector3d angular = (point - centre()).cross(impulse_on_body);
  substep_impulse += impulse_on_body;
  substep_angular_impulse += angular;
  if (contact) ++substep_contacts;
  if (dynamic) {
    linear_velocity += inverse_mass * impulse_on_body;
    angular_velocity += inverse_inertia * angular;
  }
}

double RigidTrack::inverse_mass_along(const Eigen::Vector3d& point, const Eigen::Vector3d& direction) const {
  if (!dynamic) return 0.0;
  const Eigen::Vector3d arm = (point - centre()).cross(direction);
  return inverse_mass + arm.dot(inverse_inertia * arm);
}

RigidTrack start_track(const btCollisionObject* object, bool constrained) {
  RigidTrack track;
  track.object = object;
  track.transform = object->getWorldTransform();
  track.body = const_cast<btRigidBody*>(btRigidBody::upcast(object));
  if (track.body == nullptr) return track;
  // a kinematic body already stands at the step's end; its velocity says where it came from
  track.linear_velocity = bullet::to_eigen(track.body->getLinearVelocity());
  track.angular_velocity = bullet::to_eigen(track.body->getAngularVelocity());
  track.dynamic = !object->isStaticOrKinematicObject() && track.body->getInvMass() > 0;
  if (track.dynamic) {
    track.free_flight = !constrained;
    track.inverse_mass = static_cast<double>(track.body->getInvMass());
    track.inverse_inertia = to_eigen(track.body->getInvInertiaTensorWorld());
    if (track.free_flight) {
      track.gravity = bullet::to_eigen(track.body->getGravity());
      // Bullet added the weight to the total force before its steps (an active body's); what is
      // left is the user's, and a last bit's difference (setMassProps and setGravity compute the
      // weight differently) is none, so bodies nobody pushes step as they did before
      btVector3 user_force = track.body->getTotalForce();
      if (track.body->isActive()) {
        const btVector3 weight =
            track.body->getGravity() * (btScalar(1.0) / track.body->getInvMass()) * track.body->getLinearFactor();
        user_force -= weight;
        if (user_force.length() <= btScalar(1e-5) * weight.length()) user_force.setZero();
      }
      track.applied_acceleration = bullet::to_eigen(user_force) * track.inverse_mass;
      track.applied_angular_acceleration = track.inverse_inertia * bullet::to_eigen(track.body->getTotalTorque());
    }
  }
  return track;
}

void advance_track(RigidTrack& track, double t, double dt, double kinematic_pose_time) {
  if (track.body == nullptr) return;
  // kinematic first: Bullet marks a kinematic body of mass 0 (the usual way to make one) static too
  if (track.object->isKinematicObject()) {
    // pose at t + dt, counted back from where it stands at the call's end
    btTransformUtil::integrateTransform(track.object->getWorldTransform(), to_bt(track.linear_velocity),
                                        to_bt(track.angular_velocity),
                                        static_cast<btScalar>(t + dt - kinematic_pose_time), track.transform);
    return;
  }
  if (!track.dynamic) return;
  track.linear_velocity += (track.gravity + track.applied_acceleration) * dt;
  track.angular_velocity += track.applied_angular_acceleration * dt;
  btTransform next;
  btTransformUtil::integrateTransform(track.transform, to_bt(track.linear_velocity), to_bt(track.angular_velocity),
                                      static_cast<btScalar>(dt), next);
  track.transform = next;
  track.moved_linear_velocity = track.linear_velocity;
  track.moved_angular_velocity = track.angular_velocity;
}

void finish_substep(RigidTrack& track) {
  track.impulse += track.substep_impulse;
  track.angular_impulse += track.substep_angular_impulse;
}

PendingVelocity hand_over(RigidTrack& track, double step_length) {
  if (!track.dynamic || (track.impulse.isZero() && track.angular_impulse.isZero())) return {};
  track.body->activate(true);
  if (!track.free_flight) {
    track.body->applyCentralImpulse(to_bt(track.impulse));
    track.body->applyTorqueImpulse(to_bt(track.angular_impulse));
    return {};
  }
  const btVector3 linear = to_bt(track.moved_linear_velocity);
  const btVector3 angular = to_bt(track.moved_angular_velocity);
  btTransform start;
  btTransformUtil::integrateTransform(track.transform, -linear, -angular, static_cast<btScalar>(step_length), start);
  track.body->setCenterOfMassTransform(start);
  // Bullet's step adds what gravity and the user's forces do over its length
  track.body->setLinearVelocity(linear - track.body->getGravity() * static_cast<btScalar>(step_length) -
                                to_bt(track.applied_acceleration * step_length));
  track.body->setAngularVelocity(angular - to_bt(track.applied_angular_acceleration * step_length));
  return {track.linear_velocity - track.moved_linear_velocity, track.angular_velocity - track.moved_angular_velocity};
}

}  // namespace cubespring::bullet
