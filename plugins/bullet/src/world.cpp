// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Soft bodies stepped inside a Bullet world (docs/bullet-plugin.md).
#include "cubespring/bullet/world.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <set>
#include <sstream>

#include <LinearMath/btTransformUtil.h>

#include "contact_projector.h"
#include "cubespring/bullet/conversions.h"
#include "cubespring/stable_time_step.h"
#include "instability_causes.h"
#include "rigid_track.h"

namespace cubespring::bullet {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// Collision objects whose broadphase bounds overlap a box.
class OverlapCollector : public btBroadphaseAabbCallback {
 public:
  bool process(const btBroadphaseProxy* proxy) override {
    const auto* object = static_cast<const btCollisionObject*>(proxy->m_clientObject);
    if (object != nullptr && !(object->getCollisionFlags() & btCollisionObject::CF_NO_CONTACT_RESPONSE)) {
      objects.push_back(object);
    }
    return true;
  }
  std::vector<const btCollisionObject*> objects;
};

int track_of(std::vector<RigidTrack>& tracks, const btCollisionObject* object,
             const std::set<const btCollisionObject*>& constrained) {
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    if (tracks[i].object == object) return static_cast<int>(i);
  }
  tracks.push_back(start_track(object, constrained.count(object) != 0));
  return static_cast<int>(tracks.size()) - 1;
}

}  // namespace

World::World(btDispatcher* dispatcher, btBroadphaseInterface* broadphase, btConstraintSolver* solver,
             btCollisionConfiguration* configuration)
    : btDiscreteDynamicsWorld(dispatcher, broadphase, solver, configuration) {}

World::~World() = default;

void World::addSoftBody(SoftBody* body) {
  if (body != nullptr && std::find(soft_bodies_.begin(), soft_bodies_.end(), body) == soft_bodies_.end()) {
    soft_bodies_.push_back(body);
  }
}

const std::string& World::getSoftBodyError() const {
  static const std::string kNone;
  for (const SoftBody* body : soft_bodies_) {
    if (!body->stop_message().empty()) return body->stop_message();
  }
  return kNone;
}

void World::removeSoftBody(SoftBody* body) {
  soft_bodies_.erase(std::remove(soft_bodies_.begin(), soft_bodies_.end(), body), soft_bodies_.end());
  projectors_.erase(body);
  const std::lock_guard<std::mutex> lock(wrench_mutex_);
  for (auto& [object, by_body] : wrenches_) by_body.erase(body);
}

ContactWrench World::getContactWrench(const btCollisionObject* object) const {
  const std::lock_guard<std::mutex> lock(wrench_mutex_);
  ContactWrench total;
  const auto found = wrenches_.find(object);
  if (found == wrenches_.end()) return total;
  for (const auto& [body, wrench] : found->second) {
    total.force += wrench.force;
    total.torque += wrench.torque;
    total.contacts += wrench.contacts;
    total.time = std::max(total.time, wrench.time);
    total.penetration = std::max(total.penetration, wrench.penetration);
  }
  return total;
}

void World::internalSingleStepSimulation(btScalar timeStep) {
  constrained_.clear();
  for (int c = 0; c < getNumConstraints(); ++c) {
    const btTypedConstraint* constraint = getConstraint(c);
    if (!constraint->isEnabled()) continue;
    constrained_.insert(&constraint->getRigidBodyA());
    constrained_.insert(&constraint->getRigidBodyB());
  }
  // kinematic bodies stand where they are at the end of the stepSimulation() call; this internal
  // step ends `kinematic_pose_time` before that (relative to its own start: when they stand there)
  const double step = static_cast<double>(timeStep);
  const bool inside_call = kinematic_elapsed_ + step <= kinematic_span_ * (1 + 1e-6);
  const double kinematic_pose_time = inside_call ? kinematic_span_ - kinematic_elapsed_ : step;
  add_carried_velocities();
  for (SoftBody* body : soft_bodies_) advance_soft_body(*body, step, kinematic_pose_time);
  btDiscreteDynamicsWorld::internalSingleStepSimulation(timeStep);
  note_velocities_left();
  time_ += step;
  kinematic_elapsed_ += step;
}

// Both look the bodies up among the world's objects, so that one removed since is not touched.
void World::add_carried_velocities() {
  if (carried_velocities_.empty()) return;
  for (int i = 0; i < getNumCollisionObjects(); ++i) {
    const auto carried = carried_velocities_.find(getCollisionObjectArray()[i]);
    btRigidBody* body = btRigidBody::upcast(getCollisionObjectArray()[i]);
    if (carried == carried_velocities_.end() || body == nullptr) continue;
    const CarriedVelocity& change = carried->second;
    if (body->getLinearVelocity() != change.left_linear || body->getAngularVelocity() != change.left_angular ||
        !(body->getCenterOfMassTransform() == change.left_transform))
      continue;  // the user set its velocity or moved it: theirs stands
    body->setLinearVelocity(body->getLinearVelocity() + to_bt(change.linear));
    body->setAngularVelocity(body->getAngularVelocity() + to_bt(change.angular));
  }
  carried_velocities_.clear();
}

void World::note_velocities_left() {
  if (carried_velocities_.empty()) return;
  for (int i = 0; i < getNumCollisionObjects(); ++i) {
    const auto carried = carried_velocities_.find(getCollisionObjectArray()[i]);
    const btRigidBody* body = btRigidBody::upcast(getCollisionObjectArray()[i]);
    if (carried == carried_velocities_.end() || body == nullptr) continue;
    carried->second.left_linear = body->getLinearVelocity();
    carried->second.left_angular = body->getAngularVelocity();
    carried->second.left_transform = body->getCenterOfMassTransform();
  }
}

void World::saveKinematicState(btScalar timeStep) {
  btDiscreteDynamicsWorld::saveKinematicState(timeStep);
  kinematic_span_ = static_cast<double>(timeStep);
  kinematic_elapsed_ = 0.0;
}

// Anchors: static and kinematic bodies drive their nodes; dynamic ones pull them by a spring as
// stiff as the sub-step allows (k = m / (2 dt)^2, critically damped), and feel the pull back.
void World::drive_anchors(SoftBody& body, std::vector<RigidTrack>& tracks, const std::vector<int>& anchor_track,
                          double dt) {
  for (std::size_t a = 0; a < body.anchors_.size(); ++a) {
    if (!body.anchors_[a]) continue;
    const Anchor& anchor = *body.anchors_[a];
    RigidTrack& track = tracks[static_cast<std::size_t>(anchor_track[a])];
    for (std::size_t i = 0; i < anchor.nodes.size(); ++i) {
      const int node = anchor.nodes[i];
      const Eigen::Vector3d target = to_eigen(track.transform * to_bt(anchor.local.col(static_cast<Eigen::Index>(i))));
      if (!track.dynamic) {
        (void)body.constraints_.prescribe_position(node, target);
        continue;
      }
      const double mass = body.model_.inertia()[node];
      const double stiffness = 0.25 * mass / (dt * dt);
      const double damping = 2.0 * std::sqrt(stiffness * mass);
      const Eigen::Vector3d pull = stiffness * (target - body.state_.positions.col(node)) +
                                   damping * (track.velocity_at(target) - body.state_.velocities.col(node));
      body.loads_.nodal_forces.col(node) += pull;
      track.receive(-pull * dt, target, false);
    }
  }
}

bool World::has_held_anchors(const SoftBody& body, const std::vector<RigidTrack>& tracks,
                             const std::vector<int>& anchor_track) {
  for (std::size_t a = 0; a < body.anchors_.size(); ++a) {
    if (body.anchors_[a] && !tracks[static_cast<std::size_t>(anchor_track[a])].dynamic) return true;
  }
  return false;
}

// A static or kinematic anchor drives its nodes; what held them over the sub-step is their
// momentum change less the impulse of the forces on them, and the tissue pulls the anchor's body
// by the opposite: dt f - m dv per node (exact for symplectic Euler, whose kick used f).
void World::report_held_anchors(const SoftBody& body, std::vector<RigidTrack>& tracks,
                                const std::vector<int>& anchor_track, const Eigen::Matrix3Xd& velocities_before,
                                double dt) {
  const Eigen::Matrix3Xd& forces = body.stepper_->last_forces();
  for (std::size_t a = 0; a < body.anchors_.size(); ++a) {
    RigidTrack& track = tracks[static_cast<std::size_t>(anchor_track[a])];
    if (!body.anchors_[a] || track.dynamic) continue;
    for (const int node : body.anchors_[a]->nodes) {
      const Eigen::Vector3d momentum_change =
          body.model_.inertia()[node] * (body.state_.velocities.col(node) - velocities_before.col(node));
      track.receive(dt * forces.col(node) - momentum_change, body.state_.positions.col(node), false);
    }
  }
}

void World::advance_soft_body(SoftBody& body, double step_length, double kinematic_pose_time) {
  if (!body.last_report_.ok()) return;
  body.loads_.gravity = to_eigen(getGravity());
  {
    const std::lock_guard<std::mutex> lock(wrench_mutex_);
    for (auto& [object, by_body] : wrenches_) by_body.erase(&body);
  }

  // rigid objects near the body: its bounds grown by a cell, the contact offset and how far its
  // nodes may move
  const double speed = body.state_.velocities.colwise().norm().maxCoeff();
  const double reach = body.model_.cell_size.maxCoeff() + body.contact_.offset + 2.0 * speed * step_length;
  OverlapCollector overlaps;
  getBroadphase()->aabbTest(to_bt(body.surface_positions_.rowwise().minCoeff().array() - reach),
                            to_bt(body.surface_positions_.rowwise().maxCoeff().array() + reach), overlaps);
  std::vector<RigidTrack> tracks;
  for (const btCollisionObject* object : overlaps.objects) track_of(tracks, object, constrained_);
  std::vector<int> anchor_track(body.anchors_.size(), -1);
  for (std::size_t a = 0; a < body.anchors_.size(); ++a) {
    if (body.anchors_[a]) anchor_track[a] = track_of(tracks, body.anchors_[a]->body, constrained_);
  }
  // a body that another soft body's sub-steps already moved in this step starts with what they left
  for (RigidTrack& track : tracks) {
    const auto carried = carried_velocities_.find(track.object);
    if (carried == carried_velocities_.end()) continue;
    track.linear_velocity += carried->second.linear;
    track.angular_velocity += carried->second.angular;
  }

  // a world step so long against the body's sub-step that it would run for hours (or pass int)
  // stops the body instead, saying why
  constexpr double kMaxSubsteps = 1e6;
  const double needed = std::ceil(step_length / body.sub_step_ - 1e-9);
  if (!(needed <= kMaxSubsteps)) {
    std::ostringstream message;
    message << "a world step of " << step_length << " s needs " << needed << " sub-steps of " << body.sub_step_
            << " s, more than " << kMaxSubsteps << ": step the world in shorter steps";
    body.last_report_ = {StepStatus::kInvalidInput, message.str()};
    body.stop_message_ = "soft body stopped at t = " + std::to_string(time_) + " s: " + message.str();
    return;
  }
  // explicit sub-steps follow the body's state: a cell squeezed thin takes a shorter step than at
  // rest, from its own rest step without added inertia (planned_sub_step); what is left of the
  // world step is planned again every few sub-steps, at equal sub-steps (the same ones as at rest
  // while no cell is thin)
  const bool explicit_steps = body.step_settings_.integrator != Integrator::kImplicitEuler;
  constexpr int kReplanEvery = 4;
  int remaining = std::max(1, static_cast<int>(needed));
  double plan_start = 0.0;  // the plan's sub-steps run from here
  int planned = 0;          // sub-steps of the plan taken
  double dt = step_length / remaining;
  const Eigen::Matrix3Xd user_forces = body.loads_.nodal_forces;
  const bool held_anchors = has_held_anchors(body, tracks, anchor_track);
  std::unique_ptr<ContactProjector>& kept = projectors_[&body];
  if (!kept || kept->model_revision() != body.model_.revision) kept = std::make_unique<ContactProjector>(body);
  ContactProjector& projector = *kept;
  Eigen::Matrix3Xd velocities_before;
  for (int k = 0; remaining > 0; ++k) {
    if (explicit_steps && k % kReplanEvery == 0) {
      const Clock::time_point planning = Clock::now();
      const double left = step_length - (plan_start + planned * dt);
      const double allowed = body.planned_sub_step();
      body.times_.planning += seconds_since(planning);
      const int wanted = std::max(1, static_cast<int>(std::ceil(left / allowed - 1e-9)));
      if (wanted != remaining) {
        plan_start += planned * dt;
        planned = 0;
        remaining = wanted;
        dt = left / remaining;
      }
    }
    const double elapsed = plan_start + planned * dt;  // before this sub-step
    body.step_settings_.time_step = dt;
    for (RigidTrack& track : tracks) {
      track.substep_impulse.setZero();
      track.substep_angular_impulse.setZero();
      track.substep_contacts = 0;
      advance_track(track, elapsed, dt, kinematic_pose_time);
    }
    body.loads_.nodal_forces = user_forces;
    drive_anchors(body, tracks, anchor_track, dt);
    if (held_anchors) velocities_before = body.state_.velocities;
    Clock::time_point part = Clock::now();
    const StepReport report =
        body.stepper_->step(body.model_, body.constraints_, body.loads_, body.step_settings_, body.state_);
    body.times_.elastic += seconds_since(part);
    body.last_report_ = report;
    if (!report.ok()) {
      std::string causes;
      if (explicit_steps && report.status == StepStatus::kUnstable) {
        // (the step left the state as it was: the thin cells the plan saw)
        const double squeezed = body.planned_sub_step() / body.sub_step_;
        causes = instability_causes(
            body.model_, {dt, body.sub_step_, body.time_step_safety_, squeezed, body.mass_scaling_.added_fraction},
            tracks);
      }
      body.stop_message_ =
          "soft body stopped at t = " + std::to_string(time_ + elapsed) + " s: " + report.message + causes;
      break;
    }
    if (held_anchors) report_held_anchors(body, tracks, anchor_track, velocities_before, dt);
    part = Clock::now();
    projector.refresh_surface(tracks);  // where the contacts below look
    body.times_.surface += seconds_since(part);

    // contacts: the surface is moved out of every nearby rigid shape (its vertices; a round
    // tool's whole surface)
    part = Clock::now();
    projector.resolve(tracks);
    for (RigidTrack& track : tracks) finish_substep(track);
    body.times_.contact += seconds_since(part);
    ++body.times_.sub_steps;
    ++planned;
    --remaining;
    const double done = plan_start + planned * dt;

    // the mean over the step so far: a single sub-step's impulse flickers as vertices touch and
    // leave, its mean over the step is the force that holds the body
    const std::lock_guard<std::mutex> lock(wrench_mutex_);
    for (const RigidTrack& track : tracks) {
      ContactWrench& wrench = wrenches_[track.object][&body];
      wrench.force = track.impulse / done;
      wrench.torque = track.angular_impulse / done;
      wrench.contacts = track.substep_contacts;
      wrench.time = time_ + done;
    }
  }
  body.loads_.nodal_forces = user_forces;
  // the whole surface, for readers between steps (the sub-steps refreshed only the contacts' part)
  const Clock::time_point refresh = Clock::now();
  body.update_surface();
  body.times_.surface += seconds_since(refresh);
  if (body.last_report_.ok()) {
    // measured before the lock is taken: a haptic thread reading the wrench does not wait on it
    std::vector<double> depths;
    for (const RigidTrack& track : tracks) depths.push_back(projector.penetration(track));
    const std::lock_guard<std::mutex> lock(wrench_mutex_);
    for (std::size_t i = 0; i < tracks.size(); ++i) wrenches_[tracks[i].object][&body].penetration = depths[i];
  }

  // hand the dynamic bodies the tissue's impulses (and the motion they had in the sub-steps)
  for (RigidTrack& track : tracks) {
    const PendingVelocity pending = hand_over(track, step_length);
    if (pending.linear.isZero() && pending.angular.isZero()) continue;
    CarriedVelocity& carried = carried_velocities_[track.object];
    carried.linear = pending.linear;
    carried.angular = pending.angular;
  }
}

}  // namespace cubespring::bullet
