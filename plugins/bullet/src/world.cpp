// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Soft bodies stepped inside a Bullet world (docs/bullet-plugin.md).
#include "cubespring/bullet/world.h"

#include <algorithm>
#include <cmath>
#include <set>

#include <LinearMath/btTransformUtil.h>

#include "conversions.h"
#include "rigid_distance.h"
#include "rigid_track.h"

namespace cubespring::bullet {

namespace {

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

// One contact between a surface vertex and a rigid body (docs/bullet-plugin.md, section 2): the
// vertex is moved out of the body, which changes no momentum, then the two exchange an inelastic
// impulse along the normal that stops their approach and, within Coulomb's cone, a tangential one
// that stops their sliding, both through their effective masses. Returns the impulse given to the
// tissue [N s]; the rigid track takes the opposite one at once, so that the next vertex against
// the same body sees its new velocity.
class ContactProjector {
 public:
  explicit ContactProjector(SoftBody& body) : body_(body) {}

  /// A contact at surface vertex v.
  Eigen::Vector3d apply_vertex(int vertex, const Eigen::Vector3d& push, RigidTrack& track) {
    nodes_.clear();
    add_vertex(vertex, 1.0);
    return apply(push, track);
  }

  /// A contact at a point of a surface triangle, by its barycentric coordinates.
  Eigen::Vector3d apply_face(int triangle, const Eigen::Vector3d& barycentric, const Eigen::Vector3d& push,
                             RigidTrack& track) {
    nodes_.clear();
    for (int corner = 0; corner < 3; ++corner) add_vertex(body_.surface_triangles_(corner, triangle), barycentric[corner]);
    return apply(push, track);
  }

 private:
  // the contact point as a weighted sum of nodes, each node once
  void add_vertex(int vertex, double scale) {
    for (int e = body_.surface_offset_[static_cast<std::size_t>(vertex)];
         e < body_.surface_offset_[static_cast<std::size_t>(vertex) + 1]; ++e) {
      const int node = body_.surface_node_[static_cast<std::size_t>(e)];
      const double weight = scale * body_.surface_weight_[static_cast<std::size_t>(e)];
      auto same = std::find_if(nodes_.begin(), nodes_.end(), [node](const auto& entry) { return entry.first == node; });
      if (same != nodes_.end()) {
        same->second += weight;
      } else {
        nodes_.emplace_back(node, weight);
      }
    }
  }

  Eigen::Vector3d apply(const Eigen::Vector3d& push, RigidTrack& track) {
    // the point's inverse mass over the nodes that may move (driven nodes do not)
    double inverse_mass = 0.0;
    Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
    for (const auto& [node, w] : nodes_) {
      velocity += w * body_.state_.velocities.col(node);
      position += w * body_.state_.positions.col(node);
      if (!body_.constraints_.is_driven(node)) inverse_mass += w * w / body_.model_.mass[node];
    }
    if (inverse_mass <= 0.0) return Eigen::Vector3d::Zero();
    const Eigen::Vector3d contact = position + push;
    const Eigen::Vector3d normal = push.normalized();
    const Eigen::Vector3d relative = velocity - track.velocity_at(contact);
    const double approach = relative.dot(normal);
    const double normal_impulse =
        approach < 0.0 ? -approach / (inverse_mass + track.inverse_mass_along(contact, normal)) : 0.0;
    Eigen::Vector3d impulse = normal_impulse * normal;
    const Eigen::Vector3d sliding = relative - approach * normal;
    const double speed = sliding.norm();
    if (speed > 0.0) {
      const Eigen::Vector3d direction = sliding / speed;
      const double stop = speed / (inverse_mass + track.inverse_mass_along(contact, direction));
      impulse -= std::min(stop, body_.contact_.friction * normal_impulse) * direction;
    }
    for (const auto& [node, w] : nodes_) {
      if (body_.constraints_.is_driven(node)) continue;
      const double share = w / body_.model_.mass[node];
      body_.state_.positions.col(node) += share / inverse_mass * push;
      body_.state_.velocities.col(node) += share * impulse;
    }
    track.receive(-impulse, contact);
    return impulse;
  }

  SoftBody& body_;
  std::vector<std::pair<int, double>> nodes_;
};

World::World(btDispatcher* dispatcher, btBroadphaseInterface* broadphase, btConstraintSolver* solver,
             btCollisionConfiguration* configuration)
    : btDiscreteDynamicsWorld(dispatcher, broadphase, solver, configuration) {}

World::~World() = default;

void World::addSoftBody(SoftBody* body) {
  if (body != nullptr && std::find(soft_bodies_.begin(), soft_bodies_.end(), body) == soft_bodies_.end()) {
    soft_bodies_.push_back(body);
  }
}

void World::removeSoftBody(SoftBody* body) {
  soft_bodies_.erase(std::remove(soft_bodies_.begin(), soft_bodies_.end(), body), soft_bodies_.end());
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
  for (SoftBody* body : soft_bodies_) advance_soft_body(*body, static_cast<double>(timeStep));
  btDiscreteDynamicsWorld::internalSingleStepSimulation(timeStep);
  time_ += static_cast<double>(timeStep);
}

void World::advance_soft_body(SoftBody& body, double step_length) {
  if (!body.last_report_.ok()) return;
  body.loads_.gravity = to_eigen(getGravity());
  {
    const std::lock_guard<std::mutex> lock(wrench_mutex_);
    for (auto& [object, by_body] : wrenches_) by_body.erase(&body);
  }

  // rigid objects near the body: its bounds grown by a cell and by how far its nodes may move
  const double speed = body.state_.velocities.colwise().norm().maxCoeff();
  const double reach = body.model_.cell_size.maxCoeff() + 2.0 * speed * step_length;
  OverlapCollector overlaps;
  getBroadphase()->aabbTest(to_bt(body.surface_positions_.rowwise().minCoeff().array() - reach),
                            to_bt(body.surface_positions_.rowwise().maxCoeff().array() + reach), overlaps);
  std::vector<RigidTrack> tracks;
  for (const btCollisionObject* object : overlaps.objects) track_of(tracks, object, constrained_);
  std::vector<int> anchor_track(body.anchors_.size(), -1);
  for (std::size_t a = 0; a < body.anchors_.size(); ++a) {
    if (body.anchors_[a]) anchor_track[a] = track_of(tracks, body.anchors_[a]->body, constrained_);
  }

  const int substeps = std::max(1, static_cast<int>(std::ceil(step_length / body.sub_step_ - 1e-9)));
  const double dt = step_length / substeps;
  const double thickness = 2.0 * body.model_.cell_size.maxCoeff();
  const Eigen::Matrix3Xd user_forces = body.loads_.nodal_forces;
  body.step_settings_.time_step = dt;
  for (int k = 0; k < substeps; ++k) {
    for (RigidTrack& track : tracks) {
      track.substep_impulse.setZero();
      track.substep_angular_impulse.setZero();
      track.substep_contacts = 0;
      advance_track(track, k * dt, dt, step_length);
    }
    // anchors: static and kinematic bodies drive their nodes; dynamic ones pull them by a spring
    // as stiff as the sub-step allows, and feel the pull back
    body.loads_.nodal_forces = user_forces;
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
        const double mass = body.model_.mass[node];
        const double stiffness = 0.25 * mass / (dt * dt);
        const double damping = 2.0 * std::sqrt(stiffness * mass);
        const Eigen::Vector3d pull = stiffness * (target - body.state_.positions.col(node)) +
                                     damping * (track.velocity_at(target) - body.state_.velocities.col(node));
        body.loads_.nodal_forces.col(node) += pull;
        track.receive(-pull * dt, target, false);
      }
    }
    const StepReport report = body.stepper_->step(body.model_, body.constraints_, body.loads_, body.step_settings_,
                                                  body.state_);
    body.last_report_ = report;
    if (!report.ok()) {
      soft_body_error_ = "soft body stopped at t = " + std::to_string(time_ + k * dt) + " s: " + report.message;
      break;
    }
    body.update_surface();

    // contacts: every surface vertex inside a nearby rigid shape is moved out
    ContactProjector projector(body);
    std::vector<char> touched;
    for (RigidTrack& track : tracks) {
      const btCollisionShape& shape = *track.object->getCollisionShape();
      btVector3 low;
      btVector3 high;
      shape.getAabb(track.transform, low, high);
      // a flat triangle mesh has a flat box: reach as deep as a vertex may be behind it
      const Eigen::Array3d lower = to_eigen(low).array() - thickness;
      const Eigen::Array3d upper = to_eigen(high).array() + thickness;
      touched.assign(static_cast<std::size_t>(body.surface_positions_.cols()), 0);
      for (int v = 0; v < body.surface_positions_.cols(); ++v) {
        const Eigen::Vector3d x = body.surface_positions_.col(v);
        if ((x.array() < lower).any() || (x.array() > upper).any()) continue;
        const std::optional<Eigen::Vector3d> push = penetration_push(shape, track.transform, x, 0.0, thickness);
        if (!push || push->squaredNorm() == 0.0) continue;
        projector.apply_vertex(v, *push, track);
        touched[static_cast<std::size_t>(v)] = 1;
      }
      body.update_surface();
      // then tool tips reaching through a triangle between its corners (a triangle whose corners
      // already met this body is held by them)
      for (Eigen::Index t = 0; body.contact_.face_contacts && t < body.surface_triangles_.cols(); ++t) {
        if (touched[static_cast<std::size_t>(body.surface_triangles_(0, t))] ||
            touched[static_cast<std::size_t>(body.surface_triangles_(1, t))] ||
            touched[static_cast<std::size_t>(body.surface_triangles_(2, t))]) {
          continue;
        }
        const Eigen::Vector3d a = body.surface_positions_.col(body.surface_triangles_(0, t));
        const Eigen::Vector3d b = body.surface_positions_.col(body.surface_triangles_(1, t));
        const Eigen::Vector3d c = body.surface_positions_.col(body.surface_triangles_(2, t));
        const Eigen::Array3d tri_low = a.cwiseMin(b).cwiseMin(c).array();
        const Eigen::Array3d tri_high = a.cwiseMax(b).cwiseMax(c).array();
        if ((tri_high < lower).any() || (tri_low > upper).any()) continue;
        const std::optional<FacePenetration> through = face_penetration(shape, track.transform, a, b, c, thickness);
        if (!through) continue;
        const Eigen::Vector3d normal = (b - a).cross(c - a).normalized();
        projector.apply_face(static_cast<int>(t), through->barycentric, -through->depth * normal, track);
      }
      body.update_surface();
    }
    for (RigidTrack& track : tracks) finish_substep(track);

    // the mean over the step so far: a single sub-step's impulse flickers as vertices touch and
    // leave, its mean over the step is the force that holds the body
    const std::lock_guard<std::mutex> lock(wrench_mutex_);
    for (const RigidTrack& track : tracks) {
      ContactWrench& wrench = wrenches_[track.object][&body];
      wrench.force = track.impulse / ((k + 1) * dt);
      wrench.torque = track.angular_impulse / ((k + 1) * dt);
      wrench.contacts = track.substep_contacts;
      wrench.time = time_ + (k + 1) * dt;
    }
  }
  body.loads_.nodal_forces = user_forces;

  // hand the dynamic bodies the tissue's impulses, and the motion they had in the sub-steps:
  // Bullet's own step (v += g T, then x += v T) is made to end where the sub-steps ended, which
  // applying the impulse alone would miss by a little each step and make a body rock
  for (RigidTrack& track : tracks) {
    if (!track.dynamic || (track.impulse.isZero() && track.angular_impulse.isZero())) continue;
    if (!track.free_flight) {
      track.body->applyCentralImpulse(to_bt(track.impulse));
      track.body->applyTorqueImpulse(to_bt(track.angular_impulse));
      track.body->activate(true);
      continue;
    }
    const btVector3 linear = to_bt(track.linear_velocity);
    const btVector3 angular = to_bt(track.angular_velocity);
    btTransform start;
    btTransformUtil::integrateTransform(track.transform, -linear, -angular, static_cast<btScalar>(step_length), start);
    track.body->setCenterOfMassTransform(start);
    track.body->setLinearVelocity(linear - track.body->getGravity() * static_cast<btScalar>(step_length));
    track.body->setAngularVelocity(angular);
    track.body->activate(true);
  }
}

}  // namespace cubespring::bullet
