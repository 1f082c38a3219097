// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "contact_projector.h"

#include <algorithm>
#include <optional>

#include "contact_surface.h"
#include "conversions.h"
#include "cubespring/embedding.h"
#include "rigid_distance.h"
#include "round_tool_contact.h"

namespace cubespring::bullet {
namespace {

// How deep a tool may reach behind a surface triangle, between its corners, for a face contact
// [cells]: a tip passing between vertices in one sub-step is far shallower.
constexpr double kFaceContactDepthCells = 0.5;

// How far a round tool's contact points may stay inside it after a sub-step [of its radius].
constexpr double kRoundToolTolerance = 1e-4;

}  // namespace

void ContactProjector::resolve(std::vector<RigidTrack>& tracks) {
  const ContactSettings& settings = body_.contact_;
  ContactReach reach;
  reach.offset = settings.offset;
  reach.thickness = settings.max_depth > 0.0 ? settings.max_depth : 2.0 * body_.model_.cell_size.maxCoeff();
  std::vector<char> touched;
  for (RigidTrack& track : tracks) {
    // the tissue's outward normals, which tell a rigid edge's faces apart; once per track, when
    // a vertex is near it
    Eigen::Matrix3Xd normals;
    const btCollisionShape& shape = *track.object->getCollisionShape();
    const bool uses_normals = push_uses_surface_normal(shape);
    btVector3 low;
    btVector3 high;
    shape.getAabb(track.transform, low, high);
    // a flat triangle mesh has a flat box: reach as deep as a vertex may be behind it
    const Eigen::Array3d lower = to_eigen(low).array() - (reach.thickness + reach.offset);
    const Eigen::Array3d upper = to_eigen(high).array() + (reach.thickness + reach.offset);
    touched.assign(static_cast<std::size_t>(body_.surface_positions_.cols()), 0);
    const std::vector<char> held = vertices_held_by(track.object);
    // a round tool meets the whole surface, its corners included (resolve_round_tool): pushing
    // the vertices first, each to the nearest way out of the tool, fought that
    const std::optional<RoundCore> core = round_core(shape, track.transform);
    if (core) {
      resolve_round_tool(track, *core, held);
      continue;
    }
    points_.clear();
    for (int v = 0; v < body_.surface_positions_.cols(); ++v) {
      const Eigen::Vector3d x = body_.surface_positions_.col(v);
      if ((x.array() < lower).any() || (x.array() > upper).any()) continue;
      if (!held.empty() && held[static_cast<std::size_t>(v)]) continue;
      if (uses_normals && normals.cols() == 0) {
        vertex_normals(body_.surface_positions_, body_.surface_triangles_, normals);
      }
      const std::optional<Eigen::Vector3d> push = penetration_push(
          shape, track.transform, x, uses_normals ? Eigen::Vector3d(normals.col(v)) : Eigen::Vector3d::Zero(), reach);
      if (!push || push->squaredNorm() == 0.0) continue;
      add_vertex_point(v, *push);
      touched[static_cast<std::size_t>(v)] = 1;
    }
    apply_points(track);
    body_.update_moved_surface();
    // a tool that reaches deeper than half a cell behind a triangle is not passing between its
    // corners: it is inside the tissue, or its shaft pierces the surface, and pushing the
    // triangle that far along its normal in one sub-step crushed the cells under it (the demo's
    // probe turned a cell inside out); the vertex contacts hold such a tool
    ContactReach face_reach = reach;
    face_reach.thickness = std::min(reach.thickness, kFaceContactDepthCells * body_.model_.cell_size.maxCoeff());
    // then tool tips reaching through a triangle between its corners (a triangle whose corners
    // already met this body is held by them)
    points_.clear();
    for (Eigen::Index t = 0; body_.contact_.face_contacts && t < body_.surface_triangles_.cols(); ++t) {
      if (touched[static_cast<std::size_t>(body_.surface_triangles_(0, t))] ||
          touched[static_cast<std::size_t>(body_.surface_triangles_(1, t))] ||
          touched[static_cast<std::size_t>(body_.surface_triangles_(2, t))]) {
        continue;
      }
      if (!held.empty() && (held[static_cast<std::size_t>(body_.surface_triangles_(0, t))] ||
                            held[static_cast<std::size_t>(body_.surface_triangles_(1, t))] ||
                            held[static_cast<std::size_t>(body_.surface_triangles_(2, t))])) {
        continue;  // a point of it would move held nodes too
      }
      const Eigen::Vector3d a = body_.surface_positions_.col(body_.surface_triangles_(0, t));
      const Eigen::Vector3d b = body_.surface_positions_.col(body_.surface_triangles_(1, t));
      const Eigen::Vector3d c = body_.surface_positions_.col(body_.surface_triangles_(2, t));
      const Eigen::Array3d tri_low = a.cwiseMin(b).cwiseMin(c).array();
      const Eigen::Array3d tri_high = a.cwiseMax(b).cwiseMax(c).array();
      if ((tri_high < lower).any() || (tri_low > upper).any()) continue;
      const std::optional<FacePenetration> through = face_penetration(shape, track.transform, a, b, c, face_reach);
      if (!through) continue;
      const Eigen::Vector3d normal = (b - a).cross(c - a).normalized();
      add_face_point(static_cast<int>(t), through->barycentric, -through->depth * normal);
    }
    apply_points(track);
    body_.update_moved_surface();
  }
}

void ContactProjector::resolve_round_tool(RigidTrack& track, const RoundCore& core, const std::vector<char>& held) {
  const double cell = body_.model_.cell_size.maxCoeff();
  const double reach = core.radius + body_.contact_.offset;
  const std::vector<int> near = outer_triangles_near(core, body_.surface_positions_, body_.surface_triangles_,
                                                     *body_.surface_topology_, reach + cell);
  // the points of a pass share nodes (a tool thinner than a cell touches the surface within one
  // cell from several sides), so one pass takes each only part of the way: passes are repeated,
  // each from where the last left the surface, until every point is within the tolerance
  constexpr int kMaxPasses = 8;
  const double tolerance = kRoundToolTolerance * core.radius;
  double budget = kFaceContactDepthCells * cell;
  for (int pass = 0; pass < kMaxPasses && budget > 0.0; ++pass) {
    points_.clear();
    double deepest = 0.0;
    for (const CoreContact& contact : core_contacts(core, body_.surface_positions_, body_.surface_triangles_,
                                                    *body_.surface_topology_, near, reach)) {
      // a point an earlier pass or sub-step left on the tool's surface, a rounding error inside,
      // is not resolved again: it would dilute the others' corrections in apply_points()
      const double gap = contact.signed_distance - reach;
      if (gap >= -tolerance) continue;
      const int t = contact.surface.triangle;
      if (!held.empty() && (held[static_cast<std::size_t>(body_.surface_triangles_(0, t))] ||
                            held[static_cast<std::size_t>(body_.surface_triangles_(1, t))] ||
                            held[static_cast<std::size_t>(body_.surface_triangles_(2, t))])) {
        continue;
      }
      // a core found deep inside (a tool placed in the tissue) comes out over several sub-steps:
      // pushing the surface a cell in one crushed the cells under it
      add_face_point(t, contact.surface.barycentric, -std::min(-gap, budget) * contact.normal);
      deepest = std::max(deepest, -gap);
    }
    if (points_.empty()) break;
    budget -= deepest;
    apply_points(track, pass == 0);  // a point counts as a contact once
    body_.update_moved_surface();
  }
}

double ContactProjector::penetration(const SoftBody& body, const RigidTrack& track) {
  const btCollisionShape& shape = *track.object->getCollisionShape();
  const double cell = body.model_.cell_size.maxCoeff();
  if (const std::optional<RoundCore> core = round_core(shape, track.transform)) {
    const std::vector<int> near = outer_triangles_near(*core, body.surface_positions_, body.surface_triangles_,
                                                       *body.surface_topology_, core->radius + cell);
    double deepest = 0.0;
    for (const CoreContact& contact : core_contacts(*core, body.surface_positions_, body.surface_triangles_,
                                                    *body.surface_topology_, near, core->radius)) {
      deepest = std::max(deepest, core->radius - contact.signed_distance);
    }
    return deepest;
  }
  ContactReach reach;
  reach.thickness = body.contact_.max_depth > 0.0 ? body.contact_.max_depth : 2.0 * cell;
  btVector3 low;
  btVector3 high;
  shape.getAabb(track.transform, low, high);
  const Eigen::Array3d lower = to_eigen(low).array() - reach.thickness;
  const Eigen::Array3d upper = to_eigen(high).array() + reach.thickness;
  double deepest = 0.0;
  for (int v = 0; v < body.surface_positions_.cols(); ++v) {
    const Eigen::Vector3d x = body.surface_positions_.col(v);
    if ((x.array() < lower).any() || (x.array() > upper).any()) continue;
    if (const std::optional<Eigen::Vector3d> push =
            penetration_push(shape, track.transform, x, Eigen::Vector3d::Zero(), reach)) {
      deepest = std::max(deepest, push->norm());
    }
  }
  return deepest;
}

std::vector<char> ContactProjector::vertices_held_by(const btCollisionObject* object) const {
  std::vector<char> anchored;  // per node
  for (const std::optional<Anchor>& anchor : body_.anchors_) {
    if (!anchor || anchor->body != object) continue;
    anchored.resize(static_cast<std::size_t>(body_.model_.num_nodes()), 0);
    for (int node : anchor->nodes) anchored[static_cast<std::size_t>(node)] = 1;
  }
  if (anchored.empty()) return {};
  std::vector<char> held(static_cast<std::size_t>(body_.surface_positions_.cols()), 1);
  for (std::size_t v = 0; v < held.size(); ++v) {
    for (int e = body_.surface_offset_[v]; e < body_.surface_offset_[v + 1]; ++e) {
      if (body_.surface_weight_[static_cast<std::size_t>(e)] != 0.0 &&
          !anchored[static_cast<std::size_t>(body_.surface_node_[static_cast<std::size_t>(e)])]) {
        held[v] = 0;
      }
    }
  }
  return held;
}

void ContactProjector::add_vertex_point(int vertex, const Eigen::Vector3d& push) {
  ContactPoint& point = new_point(push);
  add_vertex(point, vertex, 1.0);
}

void ContactProjector::add_face_point(int triangle, const Eigen::Vector3d& barycentric, const Eigen::Vector3d& push) {
  ContactPoint& point = new_point(push);
  for (int corner = 0; corner < 3; ++corner) add_vertex(point, body_.surface_triangles_(corner, triangle), barycentric[corner]);
}

ContactProjector::ContactPoint& ContactProjector::new_point(const Eigen::Vector3d& push) {
  points_.emplace_back();
  ContactPoint& point = points_.back();
  point.push = push;
  point.first_node = static_cast<int>(point_nodes_.size());
  return point;
}

void ContactProjector::add_vertex(ContactPoint& point, int vertex, double scale) {
  for (int e = body_.surface_offset_[static_cast<std::size_t>(vertex)];
       e < body_.surface_offset_[static_cast<std::size_t>(vertex) + 1]; ++e) {
    const int node = body_.surface_node_[static_cast<std::size_t>(e)];
    const double weight = scale * body_.surface_weight_[static_cast<std::size_t>(e)];
    const auto first = point_nodes_.begin() + point.first_node;
    auto same = std::find_if(first, point_nodes_.end(), [node](const auto& entry) { return entry.first == node; });
    if (same != point_nodes_.end()) {
      same->second += weight;
    } else {
      point_nodes_.emplace_back(node, weight);
    }
  }
  point.end_node = static_cast<int>(point_nodes_.size());
}

// All points of one pass at once (Jacobi): each point finds the move and the impulse that would
// take it out of the body and stop its approach (and, within Coulomb's cone, its sliding) on its
// own, from the state before the pass; a node that several points reach takes the mean of what
// they give it, weighted by how much it carries of each. Applied one point after another, each
// point moved its nodes fully although its neighbours had moved them already: a flat face
// resting on a table was pushed out too far and too fast at every sub-step, which pumped energy
// into the tissue until it blew up (a 12 cm cube of 5 kPa). A dynamic body's effective mass is
// shared among the points that touch it (mass splitting), as they all push it at once.
void ContactProjector::apply_points(RigidTrack& track, bool count) {
  if (points_.empty()) {
    point_nodes_.clear();
    return;
  }
  const auto& mass = body_.model_.mass;
  // the nodes a point moves: those it has a positive weight on, unless driven (a vertex embedded
  // by extrapolation has negative weights on some; they are left alone)
  const auto movable = [&](int node, double w) { return w > 0.0 && !body_.constraints_.is_driven(node); };
  int touching = 0;
  for (ContactPoint& point : points_) {
    point.inverse_mass = 0.0;
    for (int e = point.first_node; e < point.end_node; ++e) {
      const auto [node, w] = point_nodes_[static_cast<std::size_t>(e)];
      if (movable(node, w)) point.inverse_mass += w * w / mass[node];
    }
    touching += point.inverse_mass > 0.0;
  }
  const double rigid_share = touching;
  if (node_position_.cols() != body_.model_.num_nodes()) {
    node_position_.setZero(3, body_.model_.num_nodes());
    node_velocity_.setZero(3, body_.model_.num_nodes());
    node_weight_.assign(static_cast<std::size_t>(body_.model_.num_nodes()), 0.0);
  }
  for (ContactPoint& point : points_) {
    const double inverse_mass = point.inverse_mass;
    if (inverse_mass <= 0.0) continue;
    Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
    for (int e = point.first_node; e < point.end_node; ++e) {
      const auto [node, w] = point_nodes_[static_cast<std::size_t>(e)];
      velocity += w * body_.state_.velocities.col(node);
      position += w * body_.state_.positions.col(node);
    }
    point.contact = position + point.push;
    const Eigen::Vector3d normal = point.push.normalized();
    const Eigen::Vector3d relative = velocity - track.velocity_at(point.contact);
    const double approach = relative.dot(normal);
    const double normal_impulse =
        approach < 0.0 ? -approach / (inverse_mass + rigid_share * track.inverse_mass_along(point.contact, normal)) : 0.0;
    point.impulse = normal_impulse * normal;
    const Eigen::Vector3d sliding = relative - approach * normal;
    const double speed = sliding.norm();
    if (speed > 0.0) {
      const Eigen::Vector3d direction = sliding / speed;
      const double stop = speed / (inverse_mass + rigid_share * track.inverse_mass_along(point.contact, direction));
      point.impulse -= std::min(stop, body_.contact_.friction * normal_impulse) * direction;
    }
    for (int e = point.first_node; e < point.end_node; ++e) {
      const auto [node, w] = point_nodes_[static_cast<std::size_t>(e)];
      if (!movable(node, w)) continue;
      double& weight = node_weight_[static_cast<std::size_t>(node)];
      if (weight == 0.0) moved_nodes_.push_back(node);
      weight += w;
    }
  }
  // each node's mean correction; what a point delivered is its impulse times the share of it
  // its nodes took (a node's momentum change from it is share w J), and the rigid body receives
  // exactly that
  for (const ContactPoint& point : points_) {
    if (point.inverse_mass <= 0.0) continue;
    double delivered = 0.0;
    for (int e = point.first_node; e < point.end_node; ++e) {
      const auto [node, w] = point_nodes_[static_cast<std::size_t>(e)];
      if (!movable(node, w)) continue;
      const double share = w / node_weight_[static_cast<std::size_t>(node)];
      node_position_.col(node) += share * (w / mass[node]) / point.inverse_mass * point.push;
      node_velocity_.col(node) += share * (w / mass[node]) * point.impulse;
      delivered += share * w;
    }
    track.receive(-delivered * point.impulse, point.contact, count);
  }
  for (int node : moved_nodes_) {
    body_.state_.positions.col(node) += node_position_.col(node);
    body_.state_.velocities.col(node) += node_velocity_.col(node);
    node_position_.col(node).setZero();
    node_velocity_.col(node).setZero();
    node_weight_[static_cast<std::size_t>(node)] = 0.0;
    body_.mark_moved(node);
  }
  moved_nodes_.clear();
  points_.clear();
  point_nodes_.clear();
}

}  // namespace cubespring::bullet
