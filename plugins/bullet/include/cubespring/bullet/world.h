// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#pragma once

#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <vector>

#include <btBulletDynamicsCommon.h>
#include <Eigen/Core>

#include "cubespring/bullet/soft_body.h"

/// Units are SI throughout the API: metres, kilograms, seconds, newtons, pascals.
namespace cubespring::bullet {

/// What the tissue does to one rigid body: the mean over the current Bullet step's sub-steps so
/// far (the whole last step once it is over), refreshed every sub-step: for a haptic device.
struct ContactWrench {
  Eigen::Vector3d force{0, 0, 0};   ///< on the rigid body, world frame [N]
  Eigen::Vector3d torque{0, 0, 0};  ///< about the body's centre of mass, world frame [N m]
  int contacts = 0;                 ///< contact-surface vertices pushed out of it in the last sub-step
  double time = 0.0;                ///< simulated time at the end of that sub-step [s]
  /// How deep the soft bodies' contact surface reaches into it at the end of the last step [m]:
  /// for spheres and capsules anywhere on the surface's triangles (the distance from the tool's
  /// core, a centre or an axis, short of its radius), for other shapes at the surface's vertices.
  double penetration = 0.0;
};

/// A Bullet dynamics world that also steps cubespring soft bodies: rigid bodies, constraints, ray
/// tests and the user's code work as in btDiscreteDynamicsWorld. Each Bullet step first advances
/// every soft body over the step in sub-steps, against the rigid bodies that Bullet's broadphase
/// finds near it (dynamic ones integrated alongside, so contacts stay stable), then gives those
/// bodies the contact impulses and runs Bullet's own step. Method names follow Bullet's.
/// A free body touching tissue reads, between steps, the velocity it moved at in the step's last
/// sub-step, as Bullet's own contacts leave it (0 for a body at rest on the tissue); the tissue's
/// push in that sub-step is kept for the next step, and dropped if the user sets the body's
/// velocity or moves it.
class ContactProjector;

class World : public btDiscreteDynamicsWorld {
 public:
  World(btDispatcher* dispatcher, btBroadphaseInterface* broadphase, btConstraintSolver* solver,
        btCollisionConfiguration* configuration);
  ~World() override;

  /// Adds a soft body (not owned: it must outlive its membership). Gravity is the world's.
  void addSoftBody(SoftBody* body);
  void removeSoftBody(SoftBody* body);
  const std::vector<SoftBody*>& getSoftBodies() const { return soft_bodies_; }

  /// The wrench the tissue applies to a rigid body (zero when not in contact). Safe to call from
  /// another thread while the world steps (a 1 kHz haptic loop).
  ContactWrench getContactWrench(const btCollisionObject* object) const;

  /// Empty while every soft body steps normally; else what stopped the first one that stopped
  /// (it is then left as it was at the start of the failing sub-step, and no longer advanced
  /// until SoftBody::reset()).
  const std::string& getSoftBodyError() const;

 protected:
  void internalSingleStepSimulation(btScalar timeStep) override;
  /// Bullet calls it once per stepSimulation() with the time of all its internal steps: kinematic
  /// bodies then stand at the call's end, and the internal steps count their poses back from it.
  void saveKinematicState(btScalar timeStep) override;

 private:
  void advance_soft_body(SoftBody& body, double time_step, double kinematic_pose_time);
  void add_carried_velocities();
  static void drive_anchors(SoftBody& body, std::vector<struct RigidTrack>& tracks,
                            const std::vector<int>& anchor_track, double dt);
  static bool has_held_anchors(const SoftBody& body, const std::vector<struct RigidTrack>& tracks,
                               const std::vector<int>& anchor_track);
  static void report_held_anchors(const SoftBody& body, std::vector<struct RigidTrack>& tracks,
                                  const std::vector<int>& anchor_track, const Eigen::Matrix3Xd& velocities_before,
                                  double dt);

  std::vector<SoftBody*> soft_bodies_;
  mutable std::mutex wrench_mutex_;
  // per rigid object, what each soft body did to it; read summed
  std::map<const btCollisionObject*, std::map<const SoftBody*, ContactWrench>> wrenches_;
  std::set<const btCollisionObject*> constrained_;  // bodies a joint holds, this step
  // each soft body's contact resolution, kept from sub-step to sub-step with its per-node buffers
  std::map<const SoftBody*, std::unique_ptr<ContactProjector>> projectors_;
  // A free dynamic body's velocity change from the tissue's push in the last sub-step of a step,
  // which its motion has not shown yet and so Bullet's reading of its velocity leaves out
  // (rigid_track.h, hand_over). The next step adds it back first, unless the user has set the
  // body's velocity or moved it in between (they then differ from what the step left).
  struct CarriedVelocity {
    Eigen::Vector3d linear{0, 0, 0};   // [m/s]
    Eigen::Vector3d angular{0, 0, 0};  // [rad/s]
    btVector3 left_linear{0, 0, 0};    // the body's velocities when the step ended
    btVector3 left_angular{0, 0, 0};
    btTransform left_transform = btTransform::getIdentity();
  };
  void note_velocities_left();
  std::map<const btCollisionObject*, CarriedVelocity> carried_velocities_;
  double time_ = 0.0;
  // the current stepSimulation() call: its length, and how much of it the internal steps took
  double kinematic_span_ = 0.0;
  double kinematic_elapsed_ = 0.0;
};

}  // namespace cubespring::bullet
