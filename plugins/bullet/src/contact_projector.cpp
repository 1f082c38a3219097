// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "contact_projector.h"

#include <algorithm>
#include <optional>

#include "contact_surface.h"
#include "conversions.h"
#include "cubespring/embedding.h"
#include "rigid_distance.h"

namespace cubespring::bullet {
namespace {

// How deep a tool may reach behind a surface triangle, between its corners, for a face contact
// [cells]: a tip passing between vertices in one sub-step is far shallower.
constexpr double kFaceContactDepthCells = 0.5;

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
      apply_vertex(v, *push, track);
      touched[static_cast<std::size_t>(v)] = 1;
    }
    body_.update_moved_surface();
    // a tool that reaches deeper than half a cell behind a triangle is not passing between its
    // corners: it is inside the tissue, or its shaft pierces the surface, and pushing the
    // triangle that far along its normal in one sub-step crushed the cells under it (the demo's
    // probe turned a cell inside out); the vertex contacts hold such a tool
    ContactReach face_reach = reach;
    face_reach.thickness = std::min(reach.thickness, kFaceContactDepthCells * body_.model_.cell_size.maxCoeff());
    // then tool tips reaching through a triangle between its corners (a triangle whose corners
    // already met this body is held by them)
    for (Eigen::Index t = 0; body_.contact_.face_contacts && t < body_.surface_triangles_.cols(); ++t) {
      if (touched[static_cast<std::size_t>(body_.surface_triangles_(0, t))] ||
          touched[static_cast<std::size_t>(body_.surface_triangles_(1, t))] ||
          touched[static_cast<std::size_t>(body_.surface_triangles_(2, t))]) {
        continue;
      }
      if (!held.empty() && held[static_cast<std::size_t>(body_.surface_triangles_(0, t))] &&
          held[static_cast<std::size_t>(body_.surface_triangles_(1, t))] &&
          held[static_cast<std::size_t>(body_.surface_triangles_(2, t))]) {
        continue;
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
      apply_face(static_cast<int>(t), through->barycentric, -through->depth * normal, track);
    }
    body_.update_moved_surface();
  }
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

Eigen::Vector3d ContactProjector::apply_vertex(int vertex, const Eigen::Vector3d& push, RigidTrack& track) {
  nodes_.clear();
  add_vertex(vertex, 1.0);
  return apply(push, track);
}

Eigen::Vector3d ContactProjector::apply_face(int triangle, const Eigen::Vector3d& barycentric,
                                             const Eigen::Vector3d& push, RigidTrack& track) {
  nodes_.clear();
  for (int corner = 0; corner < 3; ++corner) add_vertex(body_.surface_triangles_(corner, triangle), barycentric[corner]);
  return apply(push, track);
}

void ContactProjector::add_vertex(int vertex, double scale) {
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

Eigen::Vector3d ContactProjector::apply(const Eigen::Vector3d& push, RigidTrack& track) {
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
    body_.mark_moved(node);
  }
  track.receive(-impulse, contact);
  return impulse;
}

}  // namespace cubespring::bullet
