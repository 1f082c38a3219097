// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "contact_projector.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "contact_surface.h"
#include "cubespring/bullet/conversions.h"
#include "rigid_distance.h"
#include "round_tool_contact.h"
#include "surface_topology.h"

namespace cubespring::bullet {
namespace {

// How deep a tool may reach behind a surface triangle, between its corners, for a face contact
// [cells]: a tip passing between vertices in one sub-step is far shallower.
constexpr double kFaceContactDepthCells = 0.5;

// How much farther than the nearest face of a flat-faced shape the face the tissue presses on may
// be [cells] (rigid_distance.h): a contact point enters a shape by a small fraction of a cell per
// sub-step, so a face farther than this is not the one it came through. Two cells let a node
// under a 200 g box dropped on 5 kPa tissue be thrown out through the box's side (10 mm in one
// sub-step), which turned a cell inside out.
constexpr double kPressedFaceDetourCells = 0.5;

// How deep behind a one-sided surface a point still counts as inside, and how far beyond the
// nearest face the pressed one may be, for a body of cells `cell` [m] across (rigid_distance.h).
ContactReach reach_for(const ContactSettings& settings, double cell) {
  ContactReach reach;
  reach.thickness = settings.max_depth > 0.0 ? settings.max_depth : 2.0 * cell;
  reach.detour = kPressedFaceDetourCells * cell;
  return reach;
}

// How far a round tool's contact points may stay inside it after a sub-step [of its radius].
constexpr double kRoundToolTolerance = 1e-4;

// How deep a round tool's core may be found inside the tissue when it was outside at the last pass
// or sub-step, `clearance` from the nearest surface point then, and the two can have come
// `closing` closer since (the core's motion and the surface's): a core enters the tissue through
// its surface, its signed distance falling through 0, so no deeper than they closed beyond the
// clearance. A deeper verdict is a fold's: where the surface cannot wrap a probe thinner than a
// cell, its walls cross, and the nearest triangle may be one seen from behind. Believed, the
// surface was pushed past the core, through the probe: the demo's 2.5 mm probe dragged 1 cm deep
// through the liver at 4 mm cells turned the cells around inside out within 3 ms, and a 2.5 mm
// probe dragged at 10 cm/s through a block of 2.7 mm cells threw nodes at 4 m/s and blew it up
// while the bound was half the radius beyond the core's motion.
double believed_entry(double clearance, double closing) { return std::max(0.0, closing - clearance); }

// How far around the rigid bodies the window reaches beyond where contacts look [cells]: a
// choice holds until nodes or bodies have moved about this far, which a resting organ or a probe
// dragged at a few cm/s takes hundreds of sub-steps to do.
constexpr double kWindowMarginCells = 0.5;

// The most a contact-surface vertex moves per unit of node motion: the sum of its weights'
// magnitudes (1 where all are >= 0; more for a vertex extrapolated beyond its cell).
double largest_spread(const std::vector<int>& offset, const std::vector<double>& weight) {
  double spread = 1.0;
  for (std::size_t v = 0; v + 1 < offset.size(); ++v) {
    double sum = 0.0;
    for (int e = offset[v]; e < offset[v + 1]; ++e) sum += std::abs(weight[static_cast<std::size_t>(e)]);
    spread = std::max(spread, sum);
  }
  return spread;
}

// Whether any corner of triangle t is flagged in `flags` (per surface vertex; empty: none is).
bool any_corner(const std::vector<char>& flags, const Eigen::Matrix3Xi& triangles, int t) {
  if (flags.empty()) return false;
  for (int k = 0; k < 3; ++k) {
    if (flags[static_cast<std::size_t>(triangles(k, t))] != 0) return true;
  }
  return false;
}

// A rigid body that left the world (or changed its kind of contact) keeps nothing in `kept`:
// another may take its address.
template <class Map>
void drop_unseen(Map& kept) {
  for (auto entry = kept.begin(); entry != kept.end();)
    entry = entry->second.seen ? std::next(entry) : kept.erase(entry);
}

}  // namespace

ContactProjector::ContactProjector(SoftBody& body)
    : body_(body),
      model_revision_(body.model_.revision),
      window_(kWindowMarginCells * body.model_.cell_size.maxCoeff(),
              largest_spread(body.surface_offset_, body.surface_weight_)) {}

void ContactProjector::refresh_surface(const std::vector<RigidTrack>& tracks) {
  const std::vector<ContactBox> boxes = contact_boxes(tracks);
  window_.note_moved(body_.state_.positions);
  if (!window_.holds(boxes)) {
    choose_window(boxes);
    return;
  }
  // a round tool's part at once (its odometer's vertices); the rest as the tests read it: an
  // organ resting on a table has a band of vertices within the table's window, and only those at
  // its top are tested
  body_.mark_surface_stale();
  double farthest = 0.0;  // squared
  for (const int v : whole_read_vertices_) farthest = std::max(farthest, body_.refresh_vertex(v));
  surface_travel_ += std::sqrt(farthest);
}

std::vector<ContactBox> ContactProjector::contact_boxes(const std::vector<RigidTrack>& tracks) const {
  const double cell = body_.model_.cell_size.maxCoeff();
  ContactReach reach = reach_for(body_.contact_, cell);
  reach.offset = body_.contact_.offset;
  std::vector<ContactBox> boxes;
  for (const RigidTrack& track : tracks) {
    const btCollisionShape& shape = *track.object->getCollisionShape();
    btVector3 low;
    btVector3 high;
    shape.getAabb(track.transform, low, high);
    // a round tool's triangles are looked for a cell beyond its radius (which its box holds); other
    // shapes' vertices as far as penetration_push() finds them, and the faces a tool (or a box's
    // edge) reaches through half a cell
    const bool round = round_core(shape, track.transform).has_value();
    double beyond = reach.offset + cell;
    if (!round) {
      beyond = std::max(push_reach_beyond_bounds(shape, reach), reach.offset + kFaceContactDepthCells * cell);
    }
    boxes.push_back({track.object, Eigen::AlignedBox3d(to_eigen(low), to_eigen(high)), beyond, round});
  }
  return boxes;
}

void ContactProjector::choose_window(const std::vector<ContactBox>& boxes) {
  // the odometer follows the round tools' vertices of the window that ends (the others were far
  // from any round tool)
  std::vector<Eigen::Vector3d> before;
  for (const int v : whole_read_vertices_) before.emplace_back(body_.surface_positions_.col(v));
  body_.update_surface();
  double farthest = 0.0;
  for (std::size_t i = 0; i < before.size(); ++i) {
    farthest = std::max(farthest, (body_.surface_positions_.col(whole_read_vertices_[i]) - before[i]).norm());
  }
  surface_travel_ += farthest;
  window_.choose(body_.state_.positions, body_.surface_positions_, body_.surface_triangles_, *body_.surface_topology_,
                 boxes);
  for (const int v : whole_read_vertices_) whole_read_[static_cast<std::size_t>(v)] = 0;
  whole_read_.resize(static_cast<std::size_t>(body_.surface_positions_.cols()), 0);
  whole_read_vertices_.clear();
  for (const ContactBox& box : boxes) {
    if (!box.read_whole) continue;
    for (const int v : window_.vertices_near(box.object)) whole_read_[static_cast<std::size_t>(v)] = 1;
  }
  for (const int v : window_.vertices()) {
    if (whole_read_[static_cast<std::size_t>(v)]) whole_read_vertices_.push_back(v);
  }
}

void ContactProjector::refresh_moved() {
  window_.note_moved(body_.state_.positions, body_.moved_nodes_);
  surface_travel_ += body_.update_moved_surface(whole_read_);
  // the boxes have not moved within a sub-step's contacts
  if (!window_.holds(window_.boxes())) choose_window(window_.boxes());
}

void ContactProjector::resolve(std::vector<RigidTrack>& tracks) {
  const ContactSettings& settings = body_.contact_;
  ContactReach reach = reach_for(settings, body_.model_.cell_size.maxCoeff());
  reach.offset = settings.offset;
  std::vector<char> touched;
  for (auto& [object, last] : last_impulses_) last.seen = false;
  for (auto& [object, last] : last_edge_impulses_) last.seen = false;
  for (auto& [object, last] : last_cores_) last.seen = false;
  for (RigidTrack& track : tracks) {
    const btCollisionShape& shape = *track.object->getCollisionShape();
    btVector3 low;
    btVector3 high;
    shape.getAabb(track.transform, low, high);
    // only surface points near the shape's box are tested: a vertex is inside a solid shape only
    // within its box grown by the offset (a flat triangle mesh has a flat box, and a vertex may be
    // behind it as deep as the reach's thickness); a triangle a tool reaches through is within a
    // face contact's depth of the box
    const double vertex_margin = push_reach_beyond_bounds(shape, reach);
    const Eigen::Array3d vertex_lower = to_eigen(low).array() - vertex_margin;
    const Eigen::Array3d vertex_upper = to_eigen(high).array() + vertex_margin;
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
    // a vertex that was farther from the box at the window's choice than it can have moved since
    // is not refreshed to be tested
    const double travel = window_.vertex_travel();
    for (const int v : window_.vertices_near(track.object)) {
      const Eigen::Array3d then = window_.chosen_position(v).array();
      if ((then < vertex_lower - travel).any() || (then > vertex_upper + travel).any()) continue;
      const Eigen::Vector3d x = body_.fresh_vertex(v);
      if ((x.array() < vertex_lower).any() || (x.array() > vertex_upper).any()) continue;
      if (!held.empty() && held[static_cast<std::size_t>(v)]) continue;
      // the tissue's outward normal tells a rigid edge's faces apart
      const auto normal_at_v = [&] {
        freshen_triangles_around(v);
        return vertex_normal(*body_.surface_topology_, body_.surface_positions_, body_.surface_triangles_, v);
      };
      const std::optional<Eigen::Vector3d> push =
          penetration_push(shape, track.transform, x, SurfaceNormal::when_asked(normal_at_v), reach);
      if (!push || push->squaredNorm() == 0.0) continue;
      add_vertex_point(v, *push);
      touched[static_cast<std::size_t>(v)] = 1;
    }
    LastImpulses& last = last_impulses_[track.object];
    last.seen = true;
    last.resize(static_cast<std::size_t>(body_.surface_positions_.cols()));
    solve_points(track, 0, true, &last);
    refresh_moved();
    const std::size_t vertex_points = points_.size();
    // a tool that reaches deeper than half a cell behind a triangle is not passing between its
    // corners: it is inside the tissue, or its shaft pierces the surface, and pushing the
    // triangle that far along its normal in one sub-step crushed the cells under it (the demo's
    // probe turned a cell inside out); the vertex contacts hold such a tool
    ContactReach face_reach = reach;
    face_reach.thickness = std::min(reach.thickness, kFaceContactDepthCells * body_.model_.cell_size.maxCoeff());
    resolve_box_edges(track, face_reach.thickness, held);  // its impulses settle with the vertices'
    remember(last, 0, vertex_points);
    points_.clear();
    point_nodes_.clear();
    if (!body_.contact_.face_contacts) continue;
    // then tool tips reaching through a triangle between its corners (a triangle whose corners
    // already met this body is held by them)
    const Eigen::AlignedBox3d face_region = face_test_region(track, face_reach);
    if (face_region.isEmpty()) continue;
    freshen_part(track.object);
    for (const int t : window_.triangles_near(track.object)) {
      if (any_corner(touched, body_.surface_triangles_, t)) continue;
      if (any_corner(held, body_.surface_triangles_, t)) continue;  // a point of it would move held nodes too
      const Eigen::Vector3d a = body_.surface_positions_.col(body_.surface_triangles_(0, t));
      const Eigen::Vector3d b = body_.surface_positions_.col(body_.surface_triangles_(1, t));
      const Eigen::Vector3d c = body_.surface_positions_.col(body_.surface_triangles_(2, t));
      if (!face_region.intersects(Eigen::AlignedBox3d(a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c)))) continue;
      const std::optional<FacePenetration> through = face_penetration(shape, track.transform, a, b, c, face_reach);
      if (!through) continue;
      const Eigen::Vector3d normal = (b - a).cross(c - a).normalized();
      add_face_point(t, through->barycentric, -through->depth * normal);
    }
    apply_points(track);
    refresh_moved();
  }
  drop_unseen(last_impulses_);
  drop_unseen(last_edge_impulses_);
  drop_unseen(last_cores_);
}

void ContactProjector::freshen_part(const void* object) {
  for (const int v : window_.vertices_near(object)) body_.fresh_vertex(v);
}

void ContactProjector::freshen_triangles_around(int v) {
  const SurfaceTopology& topology = *body_.surface_topology_;
  for (int k = topology.vertex_offset[static_cast<std::size_t>(v)];
       k < topology.vertex_offset[static_cast<std::size_t>(v) + 1]; ++k) {
    const int t = topology.vertex_triangle[static_cast<std::size_t>(k)];
    for (int corner = 0; corner < 3; ++corner) body_.fresh_vertex(body_.surface_triangles_(corner, t));
  }
}

Eigen::AlignedBox3d ContactProjector::face_test_region(const RigidTrack& track, const ContactReach& face_reach) const {
  const btCollisionShape& shape = *track.object->getCollisionShape();
  const double reach = face_reach.thickness + face_reach.offset;
  const std::optional<std::vector<Eigen::Vector3d>> points = face_penetration_points(shape, track.transform);
  Eigen::AlignedBox3d region;
  if (!points) {
    btVector3 low;
    btVector3 high;
    shape.getAabb(track.transform, low, high);
    region.extend(to_eigen(low)).extend(to_eigen(high));
    region.min().array() -= reach;
    region.max().array() += reach;
    return region;
  }
  const Eigen::AlignedBox3d surface = window_.bounds_near(track.object);
  for (const Eigen::Vector3d& point : *points) {
    const Eigen::AlignedBox3d around(point.array() - reach, point.array() + reach);
    if (around.intersects(surface)) region.extend(around);
  }
  return region;
}

void ContactProjector::resolve_box_edges(RigidTrack& track, double thickness, const std::vector<char>& held) {
  const std::vector<RigidEdge> edges =
      box_edges(*track.object->getCollisionShape(), track.transform, body_.contact_.offset);
  if (edges.empty()) return;
  // each edge meets only the triangles near it, and most edges none: a table's lie far from an
  // organ lying on it
  const Eigen::AlignedBox3d surface = window_.bounds_near(track.object);
  std::vector<RigidEdge> near_edges;
  std::vector<Eigen::AlignedBox3d> near_edge;
  Eigen::AlignedBox3d near_any;
  for (const RigidEdge& edge : edges) {
    Eigen::AlignedBox3d box(edge.from.cwiseMin(edge.to), edge.from.cwiseMax(edge.to));
    box.min().array() -= thickness;
    box.max().array() += thickness;
    if (!box.intersects(surface)) continue;
    near_edges.push_back(edge);
    near_edge.push_back(box);
    near_any.extend(box);
  }
  if (near_edges.empty()) return;
  freshen_part(track.object);
  const std::size_t from = points_.size();  // after the vertex points against the same body
  for (const int t : window_.triangles_near(track.object)) {
    const auto corner = [&](int k) { return static_cast<std::size_t>(body_.surface_triangles_(k, t)); };
    const Eigen::Vector3d a = body_.surface_positions_.col(static_cast<Eigen::Index>(corner(0)));
    const Eigen::Vector3d b = body_.surface_positions_.col(static_cast<Eigen::Index>(corner(1)));
    const Eigen::Vector3d c = body_.surface_positions_.col(static_cast<Eigen::Index>(corner(2)));
    const Eigen::AlignedBox3d triangle_box(a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c));
    if (!near_any.intersects(triangle_box)) continue;
    if (any_corner(held, body_.surface_triangles_, t)) continue;  // a point of it would move held nodes too
    std::optional<FacePenetration> deepest;
    for (std::size_t e = 0; e < near_edges.size(); ++e) {
      if (!near_edge[e].intersects(triangle_box)) continue;
      const std::optional<FacePenetration> through = edge_penetration(near_edges[e], a, b, c, thickness);
      if (through && (!deepest || through->depth > deepest->depth)) deepest = through;
    }
    if (!deepest) continue;
    const Eigen::Vector3d normal = (b - a).cross(c - a).normalized();
    add_face_point(t, deepest->barycentric, -deepest->depth * normal);
    points_.back().key = t;  // its impulse starts the next sub-step's at this triangle
  }
  // a resting box needs about the same impulse at its edges every sub-step, as at its vertices:
  // started from zero, four sweeps left the tissue beside a tilted box on frictionless tissue
  // trembling (kinetic energy 2e-4 J after 5 s; 1.6e-5 J with the warm start)
  LastImpulses& last = last_edge_impulses_[track.object];
  last.seen = true;
  last.resize(static_cast<std::size_t>(body_.surface_triangles_.cols()));
  solve_points(track, from, true, &last);
  remember(last, from, points_.size());
  refresh_moved();
}

void ContactProjector::resolve_round_tool(RigidTrack& track, const RoundCore& core, const std::vector<char>& held) {
  const double cell = body_.model_.cell_size.maxCoeff();
  const double reach = core.radius + body_.contact_.offset;
  const std::vector<int> near =
      outer_triangles_near(core, body_.surface_positions_, body_.surface_triangles_, *body_.surface_topology_,
                           reach + cell, &window_.triangles_near(track.object));
  // a pass's points are found where the surface was, and it bends as they move it (a tool thinner
  // than a cell touches the surface within one cell from several sides): passes are repeated,
  // each from where the last left the surface, until every point is within the tolerance
  constexpr int kMaxPasses = 8;
  const double tolerance = kRoundToolTolerance * core.radius;
  double budget = kFaceContactDepthCells * cell;
  LastCore& last = last_cores_[track.object];
  bool outside = last.outside;  // a tool met for the first time may have been placed anywhere
  double clearance = last.clearance;
  double travel = last.travel;
  double moved = last.outside ? std::max((core.from - last.from).norm(), (core.to - last.to).norm()) : 0.0;
  for (int pass = 0; pass < kMaxPasses && budget > 0.0; ++pass) {
    points_.clear();
    double deepest = 0.0;
    const double believed_depth = outside ? believed_entry(clearance, moved + (surface_travel_ - travel))
                                          : std::numeric_limits<double>::infinity();
    moved = 0.0;  // the tool stands still between the passes
    const std::vector<CoreContact> contacts = core_contacts(core, body_.surface_positions_, body_.surface_triangles_,
                                                            *body_.surface_topology_, near, reach, believed_depth);
    outside = contacts.empty() || contacts.front().signed_distance >= 0.0;
    clearance = reach + cell;  // no surface within the search
    for (const CoreContact& contact : contacts) clearance = std::min(clearance, contact.signed_distance);
    travel = surface_travel_;
    for (const CoreContact& contact : contacts) {
      // a point an earlier pass or sub-step left on the tool's surface, a rounding error inside,
      // is not resolved again: the result would follow the last bit of Bullet's float poses
      const double gap = contact.signed_distance - reach;
      if (gap >= -tolerance) continue;
      const int t = contact.surface.triangle;
      if (any_corner(held, body_.surface_triangles_, t)) continue;
      // a core found deep inside (a tool placed in the tissue) comes out over several sub-steps:
      // pushing the surface a cell in one crushed the cells under it
      add_face_point(t, contact.surface.barycentric, -std::min(-gap, budget) * contact.normal);
      deepest = std::max(deepest, -gap);
    }
    if (points_.empty()) break;
    budget -= deepest;
    apply_points(track, pass == 0);  // a point counts as a contact once
    refresh_moved();
  }
  last = {core.from, core.to, outside, clearance, travel, true};
}

double ContactProjector::penetration(const RigidTrack& track) const {
  const SoftBody& body = body_;
  const btCollisionShape& shape = *track.object->getCollisionShape();
  const double cell = body.model_.cell_size.maxCoeff();
  if (const std::optional<RoundCore> core = round_core(shape, track.transform)) {
    const std::vector<int> near = outer_triangles_near(*core, body.surface_positions_, body.surface_triangles_,
                                                       *body.surface_topology_, core->radius + cell);
    const auto last = last_cores_.find(track.object);
    const double believed_depth = last != last_cores_.end() && last->second.outside
                                      ? believed_entry(last->second.clearance, surface_travel_ - last->second.travel)
                                      : std::numeric_limits<double>::infinity();
    double deepest = 0.0;
    for (const CoreContact& contact : core_contacts(*core, body.surface_positions_, body.surface_triangles_,
                                                    *body.surface_topology_, near, core->radius, believed_depth)) {
      deepest = std::max(deepest, core->radius - contact.signed_distance);
    }
    return deepest;
  }
  const ContactReach reach = reach_for(body.contact_, cell);
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
            penetration_push(shape, track.transform, x, SurfaceNormal(Eigen::Vector3d::Zero()), reach)) {
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
  point.key = vertex;
  add_vertex(point, vertex, 1.0);
}

void ContactProjector::add_face_point(int triangle, const Eigen::Vector3d& barycentric, const Eigen::Vector3d& push) {
  ContactPoint& point = new_point(push);
  for (int corner = 0; corner < 3; ++corner)
    add_vertex(point, body_.surface_triangles_(corner, triangle), barycentric[corner]);
}

ContactProjector::ContactPoint& ContactProjector::new_point(const Eigen::Vector3d& push) {
  points_.emplace_back();
  ContactPoint& point = points_.back();
  point.push = push;
  point.first_node = static_cast<int>(point_nodes_.size());
  return point;
}

void ContactProjector::add_vertex(ContactPoint& point, int vertex, double scale) {
  // a vertex's own entries name distinct nodes (ContactSurface): only the point's earlier
  // vertices' entries may share one
  const std::size_t earlier = point_nodes_.size();
  for (int e = body_.surface_offset_[static_cast<std::size_t>(vertex)];
       e < body_.surface_offset_[static_cast<std::size_t>(vertex) + 1]; ++e) {
    const int node = body_.surface_node_[static_cast<std::size_t>(e)];
    const double weight = scale * body_.surface_weight_[static_cast<std::size_t>(e)];
    const auto first = point_nodes_.begin() + point.first_node;
    const auto end = point_nodes_.begin() + static_cast<std::ptrdiff_t>(earlier);
    auto same = std::find_if(first, end, [node](const PointNode& entry) { return entry.node == node; });
    if (same != end) {
      same->weight += weight;
    } else {
      // written field by field: a pushed temporary was stored in parts and read back whole, which
      // stalled (a fifth of the contact points' set-up)
      PointNode& entry = point_nodes_.emplace_back();
      entry.node = node;
      entry.weight = weight;
    }
  }
  point.end_node = static_cast<int>(point_nodes_.size());
}

}  // namespace cubespring::bullet
