// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "cubespring/constraints.h"
#include "cubespring/embedding.h"
#include "cubespring/forces.h"
#include "cubespring/integrator.h"
#include "cubespring/lattice.h"
#include "cubespring/mass_scaling.h"
#include "cubespring/model.h"
#include "cubespring/result.h"
#include "cubespring/state.h"
#include "cubespring/triangle_mesh.h"

class btRigidBody;

/// Units are SI throughout the API: metres, kilograms, seconds, newtons, pascals.
namespace cubespring::bullet {

/// How the tissue meets rigid bodies (docs/bullet-plugin.md, section 2). Contacts are exact
/// non-penetration of the contact surface's vertices: a vertex that ends a sub-step inside a
/// rigid shape is moved back onto its surface, and the momentum that takes is the contact
/// impulse, given in equal and opposite measure to the rigid body.
struct ContactSettings {
  double friction = 0.5;  ///< Coulomb coefficient mu [-], >= 0: the tangential impulse is at most mu
                          ///< times the normal one
  /// Also test convex tools other than spheres and capsules against the inside of surface
  /// triangles whose corners they miss, so that a tip thinner than a cell cannot pass between
  /// vertices. Spheres and capsules meet the whole surface, and boxes' edges the triangles between
  /// vertices, whatever this says (docs/bullet-plugin.md sections 2.6 and 2.7). Off by default: on an asymmetric
  /// triangulation it pushed round bodies resting in a dimple sideways, and they rolled (docs/bullet-plugin.md section
  /// 5).
  bool face_contacts = false;
  /// Contact is a projection, not a penalty spring: it has no stiffness to tune, at any scale.
  /// Its one length is this skin [m], >= 0: the tissue is kept this far outside every rigid
  /// surface (0, the default: touching, whatever the scene's size).
  double offset = 0.0;
  /// How deep behind a one-sided surface (a triangle mesh) a vertex still counts as inside and
  /// is pushed out [m], >= 0; 0 (the default) means two cells of the body.
  double max_depth = 0.0;
};

/// What to build a soft body from.
struct SoftBodySettings {
  LatticeDesc lattice;  ///< cells, materials, cell model (see cubespring/lattice.h); its `law` is not read
  /// The cells' large-strain law, which replaces lattice.law: neo-Hookean by default, since tissue
  /// is soft and lives at large strain (a 5 kPa organ under its own weight crushes the springs
  /// law's cells; docs/model-neo-hookean.md). The neo-Hookean law runs on exact-bending cells
  /// whatever lattice.model says (lattice.exact_bending is read): the paper's cells have
  /// zero-energy modes that contacts on frictionless supports set free (docs/model-exact-bending.md).
  /// kSprings steps lattice.model as calibrated, the paper's model included, on the faster grid
  /// passes. model().cell_model tells which cells a body has.
  CellLaw law = CellLaw::kNeoHookean;
  /// The surface the user sees, embedded in the lattice; contact acts on it, its edges split to
  /// at most 1.5 cells (surface_vertices()). Without one, contact acts on the nodes of the
  /// lattice's boundary faces.
  std::optional<TriangleMesh> visual_mesh;
  /// kSymplecticEuler (default): sub-steps at the body's stable explicit step, which contact and
  /// tool forces need to be followed; kImplicitEuler: sub-steps of at most max_implicit_step.
  Integrator integrator = Integrator::kSymplecticEuler;
  double max_implicit_step = 1e-3;  ///< [s]
  double time_step_safety = 0.9;    ///< explicit sub-step as a fraction of the stable step (0, 1]
  /// Selective mass scaling for the explicit sub-step, in [0, 1]: the most inertia, as a fraction
  /// of the body's mass, that the nodes limiting the step (a stiff inclusion's) may take so that
  /// the sub-step is longer (add_mass_for_time_step(), mass_scaling.h; mass_scaling() tells what
  /// it did). It weighs nothing and equilibria do not change; those nodes' motion is slowed. 0
  /// (the default): none. Not used by the implicit integrator, whose step is not limited.
  double max_added_mass = 0.0;
  int threads = 1;  ///< force-pass threads; results do not depend on it
  ContactSettings contact;
};

/// A node or nodes held by a rigid body: they move with it.
struct Anchor {
  btRigidBody* body = nullptr;
  std::vector<int> nodes;
  Eigen::Matrix3Xd local;  ///< each node's position in the body's frame at attachment [m]
};

/// A calibrated cube lattice that lives in a cubespring::bullet::World. Its state can be read and
/// changed between world steps like any cubespring body's.
struct SurfaceTopology;

class SoftBody {
 public:
  static Result<std::unique_ptr<SoftBody>> create(const SoftBodySettings& settings);

  const Model& model() const { return model_; }
  State& state() { return state_; }
  const State& state() const { return state_; }
  /// Nodes fixed or driven by the user (anchored nodes are driven by the world).
  Constraints& constraints() { return constraints_; }
  /// External nodal forces [N] the user adds (gravity comes from the world).
  Loads& loads() { return loads_; }

  /// Contact surface: vertices at the current state, and their triangles (counter-clockwise from
  /// outside). The visual mesh when there is one, its edges longer than 1.5 cells split at their
  /// midpoints until none is (its vertices first, in their order, then the midpoints: contact does
  /// not depend on how coarse the visual mesh is); else the lattice's boundary faces.
  const Eigen::Matrix3Xd& surface_vertices() const { return surface_positions_; }
  const Eigen::Matrix3Xi& surface_triangles() const { return surface_triangles_; }
  /// The visual mesh's embedding (empty without a visual mesh).
  const Embedding& embedding() const { return embedding_; }

  /// Attaches nodes to a rigid body at their current positions; returns the anchor's id. A static
  /// or kinematic body drives the nodes; a dynamic body also feels the tissue's pull.
  Result<int> anchor(btRigidBody* body, const std::vector<int>& nodes);
  /// Attaches every node whose rest position lies in [lower, upper] [m].
  Result<int> anchor_box(btRigidBody* body, const Eigen::Vector3d& lower, const Eigen::Vector3d& upper);
  /// Releases an anchor's nodes; they move freely from the next step.
  Status detach(int anchor_id);
  const std::vector<std::optional<Anchor>>& anchors() const { return anchors_; }

  /// What remove_cells() took out, and where the remaining nodes and cells went.
  struct Cut {
    int removed_cells = 0;
    double removed_mass = 0.0;                        ///< [kg]
    Eigen::Vector3d removed_momentum{0.0, 0.0, 0.0};  ///< what left with the cells [kg m/s]
    int pieces = 0;             ///< pieces the body is in after the cut (cells sharing a node count as joined)
    std::vector<int> new_node;  ///< old node n is node new_node[n] now, or -1: it left
    std::vector<int> new_cell;  ///< old cell c is cell new_cell[c] now, or -1: removed
    /// With a visual mesh: which of its vertices before the cut each vertex of the new one is,
    /// or -1 (made by the cut); and how many of its triangles, the last ones, close the cut.
    std::vector<int> visual_vertex_source;
    int cap_triangles = 0;
  };
  /// Takes cells (indices into model()'s cells) out of the body between world steps, as a
  /// cautery tool burns tissue away (cubespring/cell_removal.h, docs/cutting.md). The body is
  /// rebuilt from its remaining cells with its settings: model, sub-step, added inertia and
  /// contact surface anew; its state, constraints, nodal loads and anchors carried node by node
  /// (an anchor whose nodes all left is detached; ids stay). A visual mesh is clipped where the
  /// cells left and capped there with their faces (cut_surface.h), so that it stays closed and
  /// shows the cut's inside; the visual mesh's vertex indices change (embedding()). Node, cell
  /// and vertex indices change: the result maps them. A body cut through keeps its pieces, each
  /// moving on its own. Errors, with nothing changed: a cell out of range, a cut that would leave
  /// no cell.
  Result<Cut> remove_cells(const std::vector<int>& cells);
  /// What split_faces() did.
  struct Split {
    int faces_split = 0;  ///< faces split by the call (those split before, or listed twice, once)
    int nodes_added = 0;  ///< copies of nodes the split parted
    int pieces = 0;       ///< pieces the body is in after the split
    /// Node n now was node source_node[n] before (a node's copies share it).
    std::vector<int> source_node;
  };
  /// Splits faces between the body's cells between world steps, as a blade separates tissue
  /// (cubespring/face_split.h, docs/cutting.md): nothing leaves, the nodes the split parts are
  /// duplicated, one for each side. The body is rebuilt with its settings as by remove_cells();
  /// its state, constraints, nodal loads (shared between copies by mass) and anchors (on every
  /// copy) carried. Only a body whose surface is its lattice's: a visual mesh does not follow a
  /// split yet, and a body with one is refused. A split body steps on the spring lists. Errors,
  /// with nothing changed: a face whose axis or cells are not the body's, a body with a visual
  /// mesh.
  Result<Split> split_faces(const std::vector<CellFace>& faces);
  /// The first surface triangle a segment from `from` to `to` [m] crosses: for picking.
  struct RayHit {
    int triangle = -1;
    int nearest_node = -1;  ///< lattice node with the largest weight at the hit point
    Eigen::Vector3d point{0, 0, 0};
    double fraction = 0.0;  ///< along the segment, 0 at `from`
  };
  std::optional<RayHit> ray_test(const Eigen::Vector3d& from, const Eigen::Vector3d& to) const;

  /// The sub-step the world takes for this body [s].
  double sub_step() const { return sub_step_; }
  /// What SoftBodySettings::max_added_mass added (nothing when it was 0 or the step implicit).
  const MassScaling& mass_scaling() const { return mass_scaling_; }
  /// The threads its sub-steps' force passes may take (SoftBodySettings::threads), changed between
  /// world steps; results do not depend on it. An error unless 1 to kMaxThreads.
  Status set_threads(int threads);
  int threads() const { return step_settings_.threads; }
  static constexpr int kMaxThreads = 256;
  /// The sub-step without the added mass [s]: time_step_safety times the stable step of the body
  /// at rest were no node given inertia.
  double unscaled_sub_step() const;
  /// The sub-step the world plans for the body's current state [s]: sub_step(), or shorter while
  /// some cell is squeezed thin, each thin cell allowing its thin-cell factor times its own rest
  /// step (compressed_time_step(), cell_stable_time_steps(): from the nodes of the cell and of the
  /// cells around it, without added inertia, times time_step_safety). A cell of 8 kPa tissue that
  /// a probe squeezes thin is held to its own step, not to that of a 40 kPa tumour elsewhere in
  /// the organ: the demo's story took 8,709 sub-steps, now 5,669. The inertia the nodes took is
  /// left out because the thin-cell factor counts on the margin a rest step leaves, which those
  /// nodes no longer leave (with it, a 4 mm liver blew up under a probe at 1.74x the step).
  double planned_sub_step() const;
  /// Wall time the world has spent on this body's sub-steps, by part, since it was created [s]:
  /// where a scene's physics time goes (`cubespring bench-render` prints it).
  struct Times {
    double elastic = 0.0;  ///< the lattice's own step: forces, kick and drift
    double surface = 0.0;  ///< the contact surface refreshed from the nodes: near the rigid bodies after that step, all
                           ///< of it once a world step
    double contact = 0.0;  ///< contacts with rigid bodies found and resolved
    double planning = 0.0;  ///< the sub-step's length chosen from the cells' thickness
    long sub_steps = 0;
  };
  const Times& times() const { return times_; }
  /// The last sub-step's report; a world step stops advancing a body that went unstable, or
  /// whose step would take more than 10^6 sub-steps (kInvalidInput: step the world in shorter
  /// steps).
  const StepReport& last_report() const { return last_report_; }
  /// Why the world stopped advancing this body, with when; empty while it steps normally.
  const std::string& stop_message() const { return stop_message_; }
  /// Puts the body in `state` (one saved before it went unstable, or rest_state(model())) and
  /// lets the world advance it again. A state of another size or with a non-finite value is
  /// refused with an error that says which, and nothing changes.
  Status reset(const State& state);

 private:
  friend class World;
  friend class ContactProjector;
  SoftBody() = default;
  /// The body of `model` (built from settings.lattice) with settings' sub-step, inertia and
  /// contact surface, at rest. An explicit body's stable step reads `model`'s stiffness row sums
  /// (stiffness_row_sums()): given, as a cut carries them, or else summed here.
  static Result<std::unique_ptr<SoftBody>> assemble(const SoftBodySettings& settings, Model model,
                                                    std::optional<Eigen::VectorXd> row_sums = std::nullopt);
  /// Becomes `rebuilt`, this body made again after a change of its cells, in `state` under
  /// `constraints` and `loads`, keeping of itself the user's step settings, its timers, reports
  /// and the mesh it started with, and its anchors, each node's on every node that came from it
  /// (new node n came from node source_node[n] of this body).
  void take_over(std::unique_ptr<SoftBody> rebuilt, State state, Constraints constraints, Loads loads,
                 const std::vector<int>& source_node);
  /// Builds node_vertex_offset_ / node_vertex_ from the surface's weights.
  void index_vertices_by_node();
  /// Contact-surface vertex v from its nodes; returns how far it moved, squared [m^2] (a square
  /// root per vertex would cost every refresh; callers take the root of the largest).
  double refresh_vertex(int v);
  /// Every contact-surface vertex from the nodes (after a step moved them all).
  void update_surface();
  /// The nodes have moved (a sub-step's elastic step): every vertex is stale until refreshed,
  /// which the contacts do only for the vertices they read (fresh_vertex).
  void mark_surface_stale() { ++surface_refreshes_; }
  /// Contact-surface vertex v [m], refreshed first if it is stale.
  Eigen::Vector3d fresh_vertex(int v) {
    if (vertex_refreshed_at_[static_cast<std::size_t>(v)] != surface_refreshes_) refresh_vertex(v);
    return surface_positions_.col(v);
  }
  /// Node n was moved by a contact: its vertices are stale until update_moved_surface().
  void mark_moved(int node);
  /// The vertices of the nodes marked since the last update: those flagged in `refresh_now` (per
  /// vertex) recomputed as update_surface() does, the others made stale (fresh_vertex() refreshes
  /// them if read); returns the farthest a recomputed one moved [m].
  double update_moved_surface(const std::vector<char>& refresh_now);

  SoftBodySettings settings_;  // what it was made of (a cut body is made again of its remaining cells)
  // cutting: the visual mesh as the user gave it, every cell removed (grid indices), and what each
  // vertex of the visual mesh as cut is (CutSurface::vertex_keys; empty before the first cut)
  std::optional<TriangleMesh> uncut_visual_mesh_;
  std::vector<Eigen::Vector3i> removed_cells_;
  std::vector<std::array<long long, 4>> visual_keys_;
  Model model_;
  State state_;
  Constraints constraints_;
  Loads loads_;
  std::unique_ptr<Stepper> stepper_;
  StepSettings step_settings_;
  ContactSettings contact_;
  double sub_step_ = 0.0;
  Eigen::VectorXd cell_rest_steps_;  // explicit steps: each cell's rest step times the safety [s]
  MassScaling mass_scaling_;
  Eigen::VectorXd row_sums_;  // explicit steps: the stiffness row sums at rest (stiffness_row_sums.h)
  Times times_;
  double time_step_safety_ = 0.0;  // SoftBodySettings::time_step_safety
  StepReport last_report_;
  std::string stop_message_;

  // contact surface: vertex v sits at sum over its entries of weight * node position
  std::vector<int> surface_offset_;  // num_vertices + 1
  std::vector<int> surface_node_;
  std::vector<double> surface_weight_;
  Eigen::Matrix3Xi surface_triangles_;
  Eigen::Matrix3Xd surface_positions_;
  // the other way round: the vertices each node enters, entries node_vertex_offset_[n] .. [n+1]-1
  std::vector<int> node_vertex_offset_;
  std::vector<int> node_vertex_;
  std::vector<int> moved_nodes_;
  std::vector<char> node_moved_;
  std::vector<int> stale_vertices_;
  std::vector<char> vertex_stale_;
  // mark_surface_stale() counts up; a vertex is fresh while its count is the current one
  std::uint64_t surface_refreshes_ = 0;  // (no wrap: a 32-bit count wraps after days of sub-steps)
  std::vector<std::uint64_t> vertex_refreshed_at_;
  // which triangles neighbour which, and which bound the tissue from outside (round tools' contact)
  std::shared_ptr<const SurfaceTopology> surface_topology_;
  Embedding embedding_;

  std::vector<std::optional<Anchor>> anchors_;
};

}  // namespace cubespring::bullet
