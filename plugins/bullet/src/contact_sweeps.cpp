// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The contact points of a pass solved together (docs/bullet-plugin.md, section 2.3): the
// positions' and the velocities' projected Gauss-Seidel sweeps, each started from what the points
// took in the last sub-step. contact_projector.cpp finds the points.
#include "contact_projector.h"

#include <algorithm>
#include <cmath>

namespace cubespring::bullet {
namespace {

// The Gauss-Seidel sweeps of a pass (apply_points): at most this many, and no more once a sweep
// moves no point by more than this fraction of a cell (or changes no velocity by more than that
// over a sub-step). Started from the last sub-step's impulses, 4 rest bodies as well as 16 from
// zero did (the shared sphere, liver and torus on a table at 1e-5 m/s), at 5% more of the demo's
// time than the Jacobi mean took, where 16 from zero took 1.5 times as long.
constexpr int kMaxSweeps = 4;
constexpr double kSweepTolerance = 1e-4;

}  // namespace

// The points of one pass by projected Gauss-Seidel: sweeps over the points, each taking its own
// point to the rigid surface (or, of the velocities, stopping its approach and within Coulomb's
// cone its sliding) from where the points before it left the nodes, with the point's total
// correction kept non-negative, so that a point its neighbours lifted clear is let go again. This
// is the mass-weighted least move that meets all the points together, and the least impulse that
// stops them all: a node shared by several points takes the sum of what they need, not a mean
// (the mean left nodes with velocities the next sub-step's forces took back, 0.4 m/s at a sphere
// resting on a table, which never came to rest). A dynamic body takes each impulse at once.
void ContactProjector::apply_points(RigidTrack& track, bool count, LastImpulses* last) {
  solve_points(track, 0, count, last);
  if (last != nullptr) remember(*last, 0, points_.size());
  points_.clear();
  point_nodes_.clear();
}

// A pass after another against the same body (box edges after the vertices) shares nodes with it:
// solved on its own, the second pass's impulses pushed nodes the first had just stopped, and the
// tissue under a resting 200 g box kept 8 cm/s at every sub-step's end though it stood still. So
// the impulses of both passes are swept once more together.
void ContactProjector::solve_points(RigidTrack& track, std::size_t from, bool count, const LastImpulses* last) {
  if (from == points_.size()) return;
  prepare_points(track, count, from);
  project_positions(from, last);
  resolve_impulses(track, last, from);
  if (from == 0) return;
  resolve_impulses(track, nullptr, 0);
  // that moved the earlier pass's nodes again (against a static or kinematic body their positions
  // too, friction's drift): their vertices are stale again, and the window counts the move
  for (std::size_t i = 0; i < from; ++i) {
    const ContactPoint& point = points_[i];
    for (int e = point.first_node; e < point.end_node; ++e) {
      const PointNode& entry = point_nodes_[static_cast<std::size_t>(e)];
      if (entry.share_per_mass != 0.0) body_.mark_moved(entry.node);
    }
  }
}

// The nodes a point moves: those it has a positive weight on, unless driven (a vertex embedded by
// extrapolation has negative weights on some: moving them too made the tissue unstable).
bool ContactProjector::movable(int node, double weight) const {
  return weight > 0.0 && !body_.constraints_.is_driven(node);
}

Eigen::Vector3d ContactProjector::at_point(const ContactPoint& point, const Eigen::Matrix3Xd& field) const {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int e = point.first_node; e < point.end_node; ++e) {
    const PointNode& entry = point_nodes_[static_cast<std::size_t>(e)];
    sum += entry.weight * field.col(entry.node);
  }
  return sum;
}

void ContactProjector::move_nodes(const ContactPoint& point, Eigen::Matrix3Xd& field,
                                  const Eigen::Vector3d& change) const {
  for (int e = point.first_node; e < point.end_node; ++e) {
    const PointNode& entry = point_nodes_[static_cast<std::size_t>(e)];
    if (entry.share_per_mass != 0.0) field.col(entry.node) += entry.share_per_mass * change;
  }
}

void ContactProjector::move_nodes(const ContactPoint& point, Eigen::Matrix3Xd& field, const Eigen::Vector3d& change,
                                  Eigen::Matrix3Xd& second_field, const Eigen::Vector3d& second_change) const {
  for (int e = point.first_node; e < point.end_node; ++e) {
    const PointNode& entry = point_nodes_[static_cast<std::size_t>(e)];
    if (entry.share_per_mass == 0.0) continue;
    field.col(entry.node) += entry.share_per_mass * change;
    second_field.col(entry.node) += entry.share_per_mass * second_change;
  }
}

void ContactProjector::prepare_points(RigidTrack& track, bool count, std::size_t from) {
  const Eigen::VectorXd& inertia = body_.model_.inertia();
  for (std::size_t i = from; i < points_.size(); ++i) {
    ContactPoint& point = points_[i];
    double inverse_mass = 0.0;  // summed in locals: the calls below may write any memory
    double share = 0.0;
    for (int e = point.first_node; e < point.end_node; ++e) {
      PointNode& entry = point_nodes_[static_cast<std::size_t>(e)];
      const int node = entry.node;
      const double w = entry.weight;
      entry.share_per_mass = 0.0;
      if (!movable(node, w)) continue;
      const double per_mass = w / inertia[node];  // one division a node
      entry.share_per_mass = per_mass;
      inverse_mass += w * per_mass;
      share += w;
      body_.mark_moved(node);
    }
    point.inverse_mass = inverse_mass;
    point.share = share;
    point.contact = at_point(point, body_.state_.positions) + point.push;
    point.normal = point.push.normalized();
    point.lift = 0.0;
    point.impulse.setZero();
    if (count && point.inverse_mass > 0.0) ++track.substep_contacts;
  }
}

void ContactProjector::project_positions(std::size_t from, const LastImpulses* last) {
  Eigen::Matrix3Xd& x = body_.state_.positions;
  const double tolerance = kSweepTolerance * body_.model_.cell_size.minCoeff();
  if (last != nullptr) {
    for (std::size_t i = from; i < points_.size(); ++i) {
      ContactPoint& point = points_[i];
      if (point.inverse_mass <= 0.0 || point.key < 0) continue;
      point.lift = last->lift_by_key[static_cast<std::size_t>(point.key)];
      move_nodes(point, x, point.lift * point.normal);
    }
  }
  for (int sweep = 0; sweep < kMaxSweeps; ++sweep) {
    double largest = 0.0;
    for (std::size_t i = from; i < points_.size(); ++i) {
      ContactPoint& point = points_[i];
      if (point.inverse_mass <= 0.0) continue;
      const double gap = point.normal.dot(at_point(point, x) - point.contact);
      const double lift = std::max(point.lift - gap / point.inverse_mass, 0.0);
      move_nodes(point, x, (lift - point.lift) * point.normal);
      largest = std::max(largest, std::abs(lift - point.lift) * point.inverse_mass);
      point.lift = lift;
    }
    if (largest < tolerance) break;
  }
}

void ContactProjector::resolve_impulses(RigidTrack& track, const LastImpulses* last, std::size_t from) {
  Eigen::Matrix3Xd& v = body_.state_.velocities;
  // the point's inverse mass along a direction, the rigid body's included
  const auto effective = [&](const ContactPoint& point, const Eigen::Vector3d& direction) {
    return point.inverse_mass + point.share * track.inverse_mass_along(point.contact, direction);
  };
  // each impulse has the form the sweeps give: normal part >= 0, tangential within Coulomb's disc
  const auto admissible = [&](const Eigen::Vector3d& impulse, const Eigen::Vector3d& n) {
    const double along = impulse.dot(n);
    const double normal = std::max(along, 0.0);
    Eigen::Vector3d tangential = impulse - along * n;
    const double limit = body_.contact_.friction * normal;
    const double squared = tangential.squaredNorm();  // a square root only where the disc clips it
    if (squared > limit * limit) tangential *= limit / std::sqrt(squared);
    return Eigen::Vector3d(normal * n + tangential);
  };
  // an impulse's change at a point: its nodes take it, the rigid body the momentum they took.
  // Friction acts as it would in the sub-step's kick: against a static or kinematic body its
  // tangential change also takes back the drift it would have prevented, dt times itself. On the
  // velocities alone a sticking contact slid by dt^2 times its tangential acceleration at every
  // sub-step: a soft block crept 24 mm down a slope it should stand on in a second, and a slab
  // sheared between a plate and the floor carried no shear at all (section 2.3).
  Eigen::Matrix3Xd& x = body_.state_.positions;
  const double dt = body_.step_settings_.time_step;  // this sub-step's
  // a dynamic body's velocity takes each change at once; a static or kinematic body only counts
  // them, so it is given each point's whole change once the sweeps end
  const auto deliver = [&](ContactPoint& point, const Eigen::Vector3d& impulse) {
    const Eigen::Vector3d change = impulse - point.impulse;
    if (track.dynamic) {
      move_nodes(point, v, change);
      track.receive(-point.share * change, point.contact, false);
    } else {
      move_nodes(point, v, change, x, dt * (change - change.dot(point.normal) * point.normal));
    }
    point.impulse = impulse;
    return change;
  };
  impulses_before_.clear();
  if (!track.dynamic) {
    for (std::size_t i = from; i < points_.size(); ++i) impulses_before_.push_back(points_[i].impulse);
  }
  if (last != nullptr) {
    for (std::size_t i = from; i < points_.size(); ++i) {
      ContactPoint& point = points_[i];
      if (point.inverse_mass <= 0.0 || point.key < 0) continue;
      deliver(point, admissible(last->by_key[static_cast<std::size_t>(point.key)], point.normal));
    }
  }
  const double tolerance = kSweepTolerance * body_.model_.cell_size.minCoeff() / body_.sub_step_;
  for (int sweep = 0; sweep < kMaxSweeps; ++sweep) {
    double largest = 0.0;  // squared
    for (std::size_t i = from; i < points_.size(); ++i) {
      ContactPoint& point = points_[i];
      if (point.inverse_mass <= 0.0) continue;
      const Eigen::Vector3d relative = at_point(point, v) - track.velocity_at(point.contact);
      const Eigen::Vector3d& n = point.normal;
      const double normal_before = point.impulse.dot(n);
      const double normal_after = std::max(normal_before - relative.dot(n) / effective(point, n), 0.0);
      Eigen::Vector3d impulse = point.impulse + (normal_after - normal_before) * n;
      // friction: the tangential impulse that stops the sliding left, within mu times the normal one
      const Eigen::Vector3d sliding = relative - relative.dot(n) * n;
      if (!track.dynamic) {
        impulse -= sliding / point.inverse_mass;  // a static or kinematic body adds no inverse mass
      } else if (const double speed = sliding.norm(); speed > 0.0) {
        const Eigen::Vector3d direction = sliding / speed;
        impulse -= speed / effective(point, direction) * direction;
      }
      const double changed =
          deliver(point, admissible(impulse, n)).squaredNorm() * point.inverse_mass * point.inverse_mass;
      largest = std::max(largest, changed);
    }
    if (largest < tolerance * tolerance) break;
  }
  if (!track.dynamic) {
    for (std::size_t i = from; i < points_.size(); ++i) {
      const ContactPoint& point = points_[i];
      track.receive(-point.share * (point.impulse - impulses_before_[i - from]), point.contact, false);
    }
  }
}

void ContactProjector::LastImpulses::resize(std::size_t size) {
  by_key.resize(size, Eigen::Vector3d::Zero());
  lift_by_key.resize(size, 0.0);
}

void ContactProjector::remember(LastImpulses& last, std::size_t from, std::size_t to) const {
  for (const int key : last.keys) {
    last.by_key[static_cast<std::size_t>(key)].setZero();
    last.lift_by_key[static_cast<std::size_t>(key)] = 0.0;
  }
  last.keys.clear();
  for (std::size_t i = from; i < to; ++i) {
    const ContactPoint& point = points_[i];
    if (point.key < 0 || (point.impulse.isZero() && point.lift == 0.0)) continue;
    last.by_key[static_cast<std::size_t>(point.key)] = point.impulse;
    last.lift_by_key[static_cast<std::size_t>(point.key)] = point.lift;
    last.keys.push_back(point.key);
  }
}

}  // namespace cubespring::bullet
