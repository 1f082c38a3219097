// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "cubespring/bullet/soft_body.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <btBulletDynamicsCommon.h>

#include "contact_surface.h"
#include "cubespring/bullet/conversions.h"
#include "cubespring/stiffness_row_sums.h"
#include "surface_refinement.h"
#include "surface_topology.h"

namespace cubespring::bullet {
namespace {

// The longest edge of the contact surface [cells]: a 12 cm cube whose visual surface is its 8
// corners rests on the ground with its lowest node 0.03 mm below it (3.3 mm at 2 cells, and it
// blew up unsplit), and the demo's liver, whose edges reach 1.5 cells, is not split (at 1 cell
// its run took 16% longer).
constexpr double kContactEdgeCells = 1.5;

}  // namespace

Result<std::unique_ptr<SoftBody>> SoftBody::create(const SoftBodySettings& settings) {
  if (!(settings.contact.friction >= 0.0)) {
    return Status::error("contact friction " + std::to_string(settings.contact.friction) + " must be >= 0");
  }
  if (!(settings.contact.offset >= 0.0 && std::isfinite(settings.contact.offset))) {
    return Status::error("contact offset " + std::to_string(settings.contact.offset) +
                         " m must be a finite length >= 0");
  }
  if (!(settings.contact.max_depth >= 0.0 && std::isfinite(settings.contact.max_depth))) {
    return Status::error("contact max_depth " + std::to_string(settings.contact.max_depth) +
                         " m must be a finite length >= 0 (0: two cells)");
  }
  if (!(settings.time_step_safety > 0.0 && settings.time_step_safety <= 1.0)) {
    return Status::error("time step safety " + std::to_string(settings.time_step_safety) + " must be in (0, 1]");
  }
  if (!(settings.max_added_mass >= 0.0 && settings.max_added_mass <= 1.0)) {
    return Status::error("max added mass " + std::to_string(settings.max_added_mass) +
                         " (a fraction of the body's mass) must be in [0, 1]");
  }
  if (settings.integrator == Integrator::kImplicitEuler && !(settings.max_implicit_step > 0.0)) {
    return Status::error("max implicit step " + std::to_string(settings.max_implicit_step) + " s must be > 0");
  }
  LatticeDesc lattice = settings.lattice;
  lattice.law = settings.law;
  // the paper's cells have zero-energy modes that frictionless contacts set free
  if (settings.law == CellLaw::kNeoHookean) lattice.model = CellModel::kExactBending;
  Result<Model> model = build_model(lattice);
  if (!model) return model.status();
  Result<std::unique_ptr<SoftBody>> body = assemble(settings, std::move(model).value());
  if (body) (*body)->uncut_visual_mesh_ = settings.visual_mesh;
  return body;
}

Result<std::unique_ptr<SoftBody>> SoftBody::assemble(const SoftBodySettings& settings, Model model,
                                                     std::optional<Eigen::VectorXd> row_sums) {
  std::unique_ptr<SoftBody> body(new SoftBody());
  body->settings_ = settings;
  body->model_ = std::move(model);
  body->state_ = rest_state(body->model_);
  body->constraints_ = Constraints(body->model_);
  body->loads_.nodal_forces.setZero(3, body->model_.num_nodes());
  body->stepper_ = std::make_unique<Stepper>(body->model_);
  body->step_settings_.integrator = settings.integrator;
  body->step_settings_.threads = settings.threads;
  // the sub-step is the plugin's choice: a blow-up is explained by the world (instability_causes)
  body->step_settings_.caller_chose_time_step = false;
  body->time_step_safety_ = settings.time_step_safety;
  // explicit: the stable step of the body at rest, which its contacts do not stiffen (they move
  // vertices, they add no springs)
  try {
    const bool implicit = settings.integrator == Integrator::kImplicitEuler;
    const bool scaled = !implicit && settings.max_added_mass > 0.0;
    if (!implicit) {
      // one set of stiffness row sums serves the scaling, each cell's step and the body's
      // (Gershgorin's bound): the scaling at 0 adds nothing and gives the body's step
      body->row_sums_ = row_sums ? std::move(*row_sums) : stiffness_row_sums(body->model_);
      body->mass_scaling_ =
          add_mass_for_time_step(body->model_, scaled ? settings.max_added_mass : 0.0, body->row_sums_);
    }
    // thin cells shorten it (for the law whose thin cells stiffen), each from its own rest step;
    // without added inertia the least of those is the body's
    if (!implicit && body->model_.cell_law != CellLaw::kSprings) {
      body->cell_rest_steps_ = settings.time_step_safety * cell_stable_time_steps(body->model_, body->row_sums_);
    }
    body->sub_step_ = implicit ? settings.max_implicit_step
                      : scaled ? settings.time_step_safety * body->mass_scaling_.time_step_after
                      : body->cell_rest_steps_.size() > 0
                          ? body->cell_rest_steps_.minCoeff()
                          : settings.time_step_safety * body->mass_scaling_.time_step_before;
  } catch (const std::length_error& too_large) {
    return Status::error(too_large.what());
  }
  body->contact_ = settings.contact;

  ContactSurface surface;
  if (settings.visual_mesh) {
    const TriangleMesh& visual = *settings.visual_mesh;
    if (Status valid = validate(visual); !valid) return valid;  // before its triangles are split
    // contact acts on a surface about as fine as the cells, whatever the visual mesh's
    // tessellation (surface_refinement.h); the visual mesh's own vertices come first, so its
    // embedding is the first of the contact surface's
    const TriangleMesh contact_mesh = split_long_edges(visual, kContactEdgeCells * body->model_.cell_size.minCoeff());
    Result<Embedding> contact_embedding = embed_mesh(body->model_, contact_mesh);
    if (!contact_embedding) return contact_embedding.status();
    surface = embedded_surface(body->model_, *contact_embedding);
    body->embedding_.vertex_cell.assign(contact_embedding->vertex_cell.begin(),
                                        contact_embedding->vertex_cell.begin() + visual.num_vertices());
    body->embedding_.vertex_local = contact_embedding->vertex_local.leftCols(visual.num_vertices());
    body->embedding_.triangles = visual.triangles;
  } else {
    surface = lattice_boundary_surface(body->model_);
  }
  body->surface_offset_ = std::move(surface.offset);
  body->surface_node_ = std::move(surface.node);
  body->surface_weight_ = std::move(surface.weight);
  body->surface_triangles_ = std::move(surface.triangles);
  body->index_vertices_by_node();
  body->update_surface();
  body->surface_topology_ =
      std::make_shared<const SurfaceTopology>(surface_topology(body->surface_positions_, body->surface_triangles_));
  return body;
}

Status SoftBody::set_threads(int threads) {
  if (threads < 1 || threads > kMaxThreads) {
    return Status::error("soft body threads must be 1 to " + std::to_string(kMaxThreads) + ", got " +
                         std::to_string(threads));
  }
  step_settings_.threads = threads;
  return {};
}

double SoftBody::unscaled_sub_step() const {
  if (mass_scaling_.nodes == 0) return sub_step_;
  return std::min(sub_step_, time_step_safety_ * mass_scaling_.time_step_before);
}

double SoftBody::planned_sub_step() const {
  if (cell_rest_steps_.size() == 0) return sub_step_;
  return std::min(sub_step_, compressed_time_step(model_, state_.positions, cell_rest_steps_));
}

void SoftBody::index_vertices_by_node() {
  const auto num_nodes = static_cast<std::size_t>(model_.num_nodes());
  node_vertex_offset_.assign(num_nodes + 1, 0);
  for (const int node : surface_node_) ++node_vertex_offset_[static_cast<std::size_t>(node) + 1];
  for (std::size_t n = 0; n < num_nodes; ++n) node_vertex_offset_[n + 1] += node_vertex_offset_[n];
  node_vertex_.resize(surface_node_.size());
  std::vector<int> fill(node_vertex_offset_.begin(), node_vertex_offset_.end() - 1);
  for (std::size_t v = 0; v + 1 < surface_offset_.size(); ++v) {
    for (int e = surface_offset_[v]; e < surface_offset_[v + 1]; ++e) {
      node_vertex_[static_cast<std::size_t>(
          fill[static_cast<std::size_t>(surface_node_[static_cast<std::size_t>(e)])]++)] = static_cast<int>(v);
    }
  }
  node_moved_.assign(num_nodes, 0);
  vertex_stale_.assign(surface_offset_.size() - 1, 0);
  vertex_refreshed_at_.assign(surface_offset_.size() - 1, 0);
}

double SoftBody::refresh_vertex(int v) {
  // summed in a local (the compiler cannot keep a column of one matrix in registers while it reads
  // another); the same sums in the same order
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int e = surface_offset_[static_cast<std::size_t>(v)]; e < surface_offset_[static_cast<std::size_t>(v) + 1];
       ++e) {
    sum +=
        surface_weight_[static_cast<std::size_t>(e)] * state_.positions.col(surface_node_[static_cast<std::size_t>(e)]);
  }
  const double moved = (sum - surface_positions_.col(v)).squaredNorm();
  surface_positions_.col(v) = sum;
  vertex_refreshed_at_[static_cast<std::size_t>(v)] = surface_refreshes_;
  return moved;
}

void SoftBody::update_surface() {
  const int vertices = static_cast<int>(surface_offset_.size()) - 1;
  if (surface_positions_.cols() != vertices) surface_positions_.setZero(3, vertices);
  for (int v = 0; v < vertices; ++v) refresh_vertex(v);
  for (const int node : moved_nodes_) node_moved_[static_cast<std::size_t>(node)] = 0;
  moved_nodes_.clear();
}

void SoftBody::mark_moved(int node) {
  if (node_moved_[static_cast<std::size_t>(node)]) return;
  node_moved_[static_cast<std::size_t>(node)] = 1;
  moved_nodes_.push_back(node);
}

double SoftBody::update_moved_surface(const std::vector<char>& refresh_now) {
  // each stale vertex once (it may hang from several moved nodes)
  stale_vertices_.clear();
  for (const int node : moved_nodes_) {
    for (int k = node_vertex_offset_[static_cast<std::size_t>(node)];
         k < node_vertex_offset_[static_cast<std::size_t>(node) + 1]; ++k) {
      const int v = node_vertex_[static_cast<std::size_t>(k)];
      if (vertex_stale_[static_cast<std::size_t>(v)]) continue;
      vertex_stale_[static_cast<std::size_t>(v)] = 1;
      stale_vertices_.push_back(v);
    }
    node_moved_[static_cast<std::size_t>(node)] = 0;
  }
  moved_nodes_.clear();
  double farthest = 0.0;
  for (const int v : stale_vertices_) {
    const auto i = static_cast<std::size_t>(v);
    vertex_stale_[i] = 0;
    if (refresh_now[i]) {
      farthest = std::max(farthest, refresh_vertex(v));  // the same sums as update_surface(), so the same bits
    } else {
      vertex_refreshed_at_[i] = surface_refreshes_ - 1;  // stale: fresh_vertex() refreshes it if read
    }
  }
  return std::sqrt(farthest);
}

Status SoftBody::reset(const State& state) {
  const auto nodes = static_cast<Eigen::Index>(model_.num_nodes());
  if (state.positions.cols() != nodes || state.velocities.cols() != nodes) {
    return Status::error("SoftBody::reset: the state has " + std::to_string(state.positions.cols()) +
                         " positions and " + std::to_string(state.velocities.cols()) + " velocities; the body has " +
                         std::to_string(nodes) + " nodes");
  }
  if (!state.positions.allFinite() || !state.velocities.allFinite() || !std::isfinite(state.time)) {
    return Status::error("SoftBody::reset: the state has a NaN or infinite position, velocity or time");
  }
  state_ = state;
  last_report_ = StepReport{};
  stop_message_.clear();
  update_surface();
  return {};
}

Result<int> SoftBody::anchor(btRigidBody* body, const std::vector<int>& nodes) {
  if (body == nullptr) return Status::error("anchor: the rigid body is null");
  if (nodes.empty()) return Status::error("anchor: no nodes given");
  Anchor anchor;
  anchor.body = body;
  anchor.nodes = nodes;
  anchor.local.resize(3, static_cast<Eigen::Index>(nodes.size()));
  const btTransform inverse = body->getWorldTransform().inverse();
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const int node = nodes[i];
    if (node < 0 || node >= model_.num_nodes()) {
      return Status::error("anchor: node " + std::to_string(node) + " is not in 0.." +
                           std::to_string(model_.num_nodes() - 1));
    }
    anchor.local.col(static_cast<Eigen::Index>(i)) = to_eigen(inverse * to_bt(state_.positions.col(node)));
  }
  anchors_.push_back(std::move(anchor));
  return static_cast<int>(anchors_.size()) - 1;
}

Result<int> SoftBody::anchor_box(btRigidBody* body, const Eigen::Vector3d& lower, const Eigen::Vector3d& upper) {
  const std::vector<int> nodes = model_.nodes_in_box(lower, upper);
  if (nodes.empty()) {
    std::ostringstream out;
    out << "anchor: no node rests in the box (" << lower.transpose() << ") .. (" << upper.transpose() << ") m";
    return Status::error(out.str());
  }
  return anchor(body, nodes);
}

Status SoftBody::detach(int anchor_id) {
  if (anchor_id < 0 || anchor_id >= static_cast<int>(anchors_.size()) ||
      !anchors_[static_cast<std::size_t>(anchor_id)]) {
    return Status::error("detach: no anchor " + std::to_string(anchor_id));
  }
  // static and kinematic bodies drove their nodes through the constraints; dynamic ones pulled
  const Anchor& anchor = *anchors_[static_cast<std::size_t>(anchor_id)];
  if (anchor.body->isStaticOrKinematicObject()) {
    for (const int node : anchor.nodes) (void)constraints_.release(node);
  }
  anchors_[static_cast<std::size_t>(anchor_id)].reset();
  return {};
}

std::optional<SoftBody::RayHit> SoftBody::ray_test(const Eigen::Vector3d& from, const Eigen::Vector3d& to) const {
  // Moeller-Trumbore against every surface triangle; the nearest hit wins
  const Eigen::Vector3d direction = to - from;
  std::optional<RayHit> best;
  for (Eigen::Index t = 0; t < surface_triangles_.cols(); ++t) {
    const Eigen::Vector3d a = surface_positions_.col(surface_triangles_(0, t));
    const Eigen::Vector3d e1 = surface_positions_.col(surface_triangles_(1, t)) - a;
    const Eigen::Vector3d e2 = surface_positions_.col(surface_triangles_(2, t)) - a;
    const Eigen::Vector3d p = direction.cross(e2);
    const double determinant = e1.dot(p);
    if (std::abs(determinant) < std::numeric_limits<double>::min()) continue;
    const Eigen::Vector3d s = from - a;
    const double u = s.dot(p) / determinant;
    if (u < 0.0 || u > 1.0) continue;
    const Eigen::Vector3d q = s.cross(e1);
    const double v = direction.dot(q) / determinant;
    if (v < 0.0 || u + v > 1.0) continue;
    const double fraction = e2.dot(q) / determinant;
    if (fraction < 0.0 || fraction > 1.0 || (best && fraction >= best->fraction)) continue;
    RayHit hit;
    hit.triangle = static_cast<int>(t);
    hit.fraction = fraction;
    hit.point = from + fraction * direction;
    // the surface vertex nearest the hit, then its heaviest node
    const std::array<double, 3> barycentric{1.0 - u - v, u, v};
    int corner = 0;
    for (int k = 1; k < 3; ++k) {
      if (barycentric[static_cast<std::size_t>(k)] > barycentric[static_cast<std::size_t>(corner)]) corner = k;
    }
    const int vertex = surface_triangles_(corner, t);
    double heaviest = -std::numeric_limits<double>::infinity();
    for (int e = surface_offset_[static_cast<std::size_t>(vertex)];
         e < surface_offset_[static_cast<std::size_t>(vertex) + 1]; ++e) {
      if (surface_weight_[static_cast<std::size_t>(e)] > heaviest) {
        heaviest = surface_weight_[static_cast<std::size_t>(e)];
        hit.nearest_node = surface_node_[static_cast<std::size_t>(e)];
      }
    }
    best = hit;
  }
  return best;
}

}  // namespace cubespring::bullet
