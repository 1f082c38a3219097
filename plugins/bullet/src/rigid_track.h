// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// A rigid body as a soft body's sub-steps see it during one Bullet step (docs/bullet-plugin.md,
// section 3): static bodies stay put, kinematic ones follow the velocity Bullet gave them for the
// step, dynamic ones are integrated alongside with gravity and the tissue's impulses, which are
// handed to Bullet at the end of the step.
#pragma once

#include <btBulletDynamicsCommon.h>
#include <Eigen/Core>

namespace cubespring::bullet {

struct RigidTrack {
  const btCollisionObject* object = nullptr;
  btRigidBody* body = nullptr;  ///< null for a collision object that is not a rigid body
  bool dynamic = false;
  /// No Bullet constraint holds it: the sub-steps may integrate it with gravity, and Bullet's
  /// step is made to end where they did. A constrained body is moved at its step-start velocity
  /// (its constraints are Bullet's to solve) and only receives the impulses.
  bool free_flight = false;
  btTransform transform;                      ///< at the end of the current sub-step
  Eigen::Vector3d linear_velocity{0, 0, 0};   ///< [m/s]
  Eigen::Vector3d angular_velocity{0, 0, 0};  ///< [rad/s]
  Eigen::Vector3d gravity{0, 0, 0};           ///< [m/s^2], dynamic bodies
  /// What the forces and torques the user applied before the step (applyCentralForce, applyTorque:
  /// a haptic coupling, a hand) do to a free body [m/s^2, rad/s^2]: Bullet's step applies them
  /// too, so the sub-steps must, or the tissue never feels them.
  Eigen::Vector3d applied_acceleration{0, 0, 0};
  Eigen::Vector3d applied_angular_acceleration{0, 0, 0};
  double inverse_mass = 0.0;
  Eigen::Matrix3d inverse_inertia = Eigen::Matrix3d::Zero();  ///< world frame, at the step's start

  Eigen::Vector3d impulse{0, 0, 0};          ///< from the tissue over the Bullet step [N s]
  Eigen::Vector3d angular_impulse{0, 0, 0};  ///< about the centre of mass [N m s]
  Eigen::Vector3d substep_impulse{0, 0, 0};
  Eigen::Vector3d substep_angular_impulse{0, 0, 0};
  /// A dynamic body's velocities when it moved in the last sub-step, before that sub-step's
  /// impulses (its motion shows them only in the next one)
  Eigen::Vector3d moved_linear_velocity{0, 0, 0};
  Eigen::Vector3d moved_angular_velocity{0, 0, 0};
  int substep_contacts = 0;

  Eigen::Vector3d centre() const;
  /// Velocity of the body's material point at `point` [m/s].
  Eigen::Vector3d velocity_at(const Eigen::Vector3d& point) const;
  /// An impulse from the tissue on the body at `point` during this sub-step; a dynamic body's
  /// velocities take it at once, and it counts as a contact unless `contact` is false.
  void receive(const Eigen::Vector3d& impulse_on_body, const Eigen::Vector3d& point, bool contact = true);
  /// 1 / (effective mass) of the body at `point` along a unit direction: 0 unless dynamic.
  double inverse_mass_along(const Eigen::Vector3d& point, const Eigen::Vector3d& direction) const;
};

/// The track of an object at the start of a Bullet step; `constrained` when a Bullet constraint
/// (a joint) holds it.
RigidTrack start_track(const btCollisionObject* object, bool constrained);

/// Moves the track to the end of a sub-step [t, t + dt] of a Bullet step (times from the step's
/// start [s]). A kinematic body stands at its world transform at `kinematic_pose_time`: the end of
/// the stepSimulation() call, which may hold several steps.
void advance_track(RigidTrack& track, double t, double dt, double kinematic_pose_time);

/// Adds the sub-step's impulses to the step's.
void finish_substep(RigidTrack& track);

/// What the tissue's impulses in a step's last sub-step changed of a body's velocities [m/s,
/// rad/s] and its motion has not yet taken.
struct PendingVelocity {
  Eigen::Vector3d linear{0, 0, 0};
  Eigen::Vector3d angular{0, 0, 0};
};

/// At the end of the soft sub-steps, gives a dynamic body the tissue's impulses over the step: a
/// free body also takes the motion it had in the sub-steps, so that Bullet's own step (v += g T,
/// then x += v T) ends where they did (the impulse alone misses by a little each step and makes a
/// resting body rock); a jointed one only the impulses, its joints being Bullet's to solve.
/// A free body leaves the step with the velocity it moved at in the last sub-step, which is what
/// its motion shows (a body resting on tissue: 0, where the velocity after the sub-step's
/// impulses reads about -g dt); the returned change is for the next step to add back first.
PendingVelocity hand_over(RigidTrack& track, double step_length);

}  // namespace cubespring::bullet
