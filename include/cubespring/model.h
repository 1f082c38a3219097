// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "cubespring/lattice.h"
#include "cubespring/result.h"

/// Units are SI throughout the API: metres, kilograms, seconds, newtons, pascals.
namespace cubespring {

/// Corner c of a cell sits at offset (c & 1, (c >> 1) & 1, (c >> 2) & 1) cells from its first corner.
/// Edges along axis a join corner c (bit a clear) to c | (1 << a); the 12 edges of a cell are stored
/// axis by axis (x edges 0-3, y edges 4-7, z edges 8-11), within an axis in ascending order of
/// their lower corner c.
inline constexpr int kCornersPerCell = 8;
inline constexpr int kEdgesPerCell = 12;
inline constexpr int kEdgesPerAxis = 4;

/// The constant part of a simulated body: topology, rest state, masses and stiffnesses. Built once
/// by build_model(); the time-varying part lives in State. Arrays are flat, one entry per item.
struct Model {
  CellModel cell_model = CellModel::kBaudet2007;
  /// The exact-bending parameters the cells were calibrated with (read for kExactBending), so that
  /// lattice_desc() gives back the description the model was built from.
  ExactBendingParameters exact_bending;
  /// kNeoHookean: each cell's correction and inversion recovery are replaced by the neo-Hookean
  /// cell term of law_constants (cell_correction and cell_inversion_stiffness are zero); both the
  /// spring lists and the grid passes have the term.
  CellLaw cell_law = CellLaw::kSprings;
  /// Per material: the neo-Hookean cell term's constants (empty for kSprings).
  std::vector<NeoHookeanConstants> law_constants;
  /// The split faces (LatticeDesc::split_faces), in the order of their cell's grid key and axis.
  /// Where any is split, nodes may share a grid index: cell_nodes says which copy a cell has.
  std::vector<CellFace> split_faces;
  Eigen::Vector3d cell_size{0, 0, 0};  ///< (hx, hy, hz) [m]
  Eigen::Vector3d origin{0, 0, 0};     ///< [m]
  /// The materials the arrays below were made from: read-only after build_model() (the masses,
  /// the springs' stiffness and damping and the corrections do not follow a change; to change a
  /// material, build the model again).
  std::vector<Material> materials;

  /// Nodes (and cells) are numbered in the order of their grid index along major_axis, slowest,
  /// then the axis after the next, then the axis after major_axis, fastest ((major_axis + 1) % 3;
  /// the order keeps the axes' handedness): z-major with x fastest unless the body's bounding box
  /// has more nodes along x or y than along z and its layers across that axis hold at least
  /// kMinMajorLayerNodes nodes. The grid passes sweep their layers along it (docs/data-layout.md).
  /// Set by build_model(), read-only after it: node_at(), the forces and the grid follow it.
  /// Find nodes by node_at() or node_grid_index, not by a formula of the grid index.
  int major_axis = 2;

  // nodes (num_nodes)
  Eigen::Matrix3Xd rest_positions;               ///< (3 x num_nodes) [m]
  std::vector<Eigen::Vector3i> node_grid_index;  ///< grid index of each node
  Eigen::VectorXd mass;                          ///< [kg], lumped: each cell gives 1/8 of its mass to each corner
  Eigen::VectorXd mass_damping;                  ///< Rayleigh alpha times mass [kg/s]
  /// What resists acceleration at each node [kg], where it differs from `mass`: selective mass
  /// scaling (add_mass_for_time_step(), mass_scaling.h) gives the nodes that limit the explicit
  /// step inertia that does not weigh, so that the step can be longer. Gravity and mass damping
  /// act on `mass`; the steps, the stable step and contact impulses on inertia(). Empty (the
  /// default): `mass`.
  Eigen::VectorXd inertial_mass;
  /// The nodes' inertia [kg]: inertial_mass when it is set, else mass.
  const Eigen::VectorXd& inertia() const { return inertial_mass.size() > 0 ? inertial_mass : mass; }

  // springs (num_springs); spring s pulls spring_nodes[s][0] and [1] together when stretched
  std::vector<std::array<int, 2>> spring_nodes;
  std::vector<double> spring_rest_length;  ///< [m]
  std::vector<double> spring_stiffness;    ///< [N/m], summed over the cells that share the spring
  std::vector<double> spring_damping;      ///< beta times stiffness, summed over cells [N s/m]
  /// Cells whose correction acts on spring s: entries spring_cell_offset[s] .. [s+1]-1 of
  /// spring_cell_tension, each cell * 3 + the edge's axis in that cell, where that cell's
  /// correction tension for it is (edges only; diagonals have none).
  std::vector<int> spring_cell_offset;
  std::vector<int> spring_cell_tension;

  // cells (num_cells)
  std::vector<Eigen::Vector3i> cell_grid_index;
  std::vector<std::array<int, kCornersPerCell>> cell_nodes;
  std::vector<std::array<int, kEdgesPerCell>> cell_edges;  ///< spring index of each edge
  std::vector<int> cell_material;
  /// Correction stiffness D [Pa] of each cell (symmetric 3x3): the correction energy is
  /// 1/2 V0 eps^T D eps with eps the mean edge strains (docs/model-baudet2007.md, section 3).
  std::vector<Eigen::Matrix3d> cell_correction;
  std::vector<double> cell_inversion_stiffness;  ///< [Pa], see docs/model-baudet2007.md section 5
  /// Twist stiffness zeta G [Pa] of each cell (exact-bending model, docs/model-exact-bending.md);
  /// zero for the paper's model.
  std::vector<double> cell_twist_stiffness;
  bool has_twist = false;  ///< some cell has a twist term

  /// Springs are sorted by their first node: those with spring_nodes[s][0] == n are
  /// node_first_spring[n] .. node_first_spring[n+1]-1 (num_nodes + 1 entries).
  std::vector<int> node_first_spring;
  /// The 4 body diagonals of each cell, between corner c and corner 7 - c for c = 0..3; each
  /// spring runs from its end with the lower node index, corner c when major_axis is z.
  std::vector<std::array<int, 4>> cell_diagonals;
  bool has_stiffness_damping = false;  ///< some material has beta > 0
  bool has_mass_damping = false;       ///< some material has alpha > 0

  /// Which version of these arrays this is: each model made (by build_model() or by hand) and
  /// each mark_changed() gets a number no other model of this process has had. Whoever steps
  /// the model keeps a force engine built from it (its thread blocks and, for a body that fills
  /// its box, its grid with its own copy of the stiffnesses: forces.h, ForceWorkspace) and
  /// rebuilds it when the revision or the node, spring or cell count changes. A copy keeps the
  /// revision: its arrays are the same.
  std::uint64_t revision = next_revision();
  /// After changing a model's arrays in place once an engine may have been built from it
  /// (stiffnesses, damping, corrections, twist, law constants, cell_law, has_twist,
  /// has_stiffness_damping), call this once so that every such engine is rebuilt.
  void mark_changed();

  int num_nodes() const { return static_cast<int>(rest_positions.cols()); }
  int num_springs() const { return static_cast<int>(spring_nodes.size()); }
  int num_cells() const { return static_cast<int>(cell_nodes.size()); }
  double rest_cell_volume() const { return cell_size.prod(); }
  double total_mass() const { return mass.sum(); }
  /// Index of the node at a grid index, or -1 when no cell uses it. Where split faces made copies
  /// of it (split_faces), the first copy: find a cell's own by cell_nodes.
  int node_at(const Eigen::Vector3i& grid_index) const;

  /// Nodes whose rest position lies in the closed box [lower, upper] [m].
  std::vector<int> nodes_in_box(const Eigen::Vector3d& lower, const Eigen::Vector3d& upper) const;

 private:
  friend Result<Model> build_model(const LatticeDesc& desc);
  static std::uint64_t next_revision();
  std::vector<std::int64_t> sorted_node_keys_;  // grid key of each node, ascending (= node order)
};

/// The description `model` was built from: its cells (in the model's order), materials, cell
/// model and law, so that build_model() of it gives the same arrays; a cut body is rebuilt from it
/// without the cells it lost (cell_removal.h). Arrays changed in place after build_model() (a
/// stiffness, say) are not in it.
LatticeDesc lattice_desc(const Model& model);

/// Inversion recovery stiffness as a multiple of the cell material's Young's modulus
/// (Model::cell_inversion_stiffness; the recovery acts in the force passes, forces.h).
inline constexpr double kInversionStiffnessFactor = 10.0;

/// Validates the description (cell size, materials, cell indices, the model's validity for the
/// cell shape, at most kMaxCells cells) and builds the model. Errors name the value at fault and the allowed range.
Result<Model> build_model(const LatticeDesc& desc);

/// The fraction of its bounding box's cells a body fills at least for the force passes to put it
/// on the grid passes (ForceOptions::min_grid_fill's default): from it the grid stepped every
/// benched body faster, below it the spring lists stepped some faster (`cubespring bench-layout`,
/// docs/data-layout.md).
inline constexpr double kDefaultMinGridFill = 0.45;

/// The fewest nodes a layer across the box's longest axis holds for build_model() to number the
/// nodes along that axis (Model::major_axis): the grid passes split their layers between threads,
/// and more, smaller layers balance them better, but a layer's loops cost a fixed time each, which
/// shorter layers cannot repay (`docs/data-layout.md`).
inline constexpr int kMinMajorLayerNodes = 256;

/// Deprecated: the force engine (the grid layout among it) is no longer part of the model but
/// is built by whoever steps it, and rebuilt when the model's revision changes. This calls
/// model.mark_changed(); min_fill is ignored (the grid's fill is ForceOptions::min_grid_fill and
/// StepSettings::min_grid_fill now).
[[deprecated("call model.mark_changed(); choose the grid with ForceOptions::min_grid_fill")]] void update_grid_layout(
    Model& model, double min_fill = kDefaultMinGridFill);

/// Per-cell spring stiffnesses and correction of one material and cell shape
/// (docs/model-baudet2007.md, sections 2-4).
struct CellCalibration {
  Eigen::Vector3d edge_stiffness;  ///< per-cell share of each edge along x, y, z [N/m]
  double diagonal_stiffness = 0;   ///< each of the 4 body diagonals [N/m]
  Eigen::Matrix3d correction;      ///< D [Pa]
  double twist_stiffness = 0;      ///< zeta G [Pa]; 0 for the paper's model
};
Result<CellCalibration> calibrate_cell(CellModel model, const Material& material, const Eigen::Vector3d& cell_size,
                                       const ExactBendingParameters& parameters = {});

}  // namespace cubespring
