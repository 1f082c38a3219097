// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#pragma once

#include <array>
#include <cstdint>
#include <memory>
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

struct GridLayout;  // internal: src/forces/grid/grid_layout.h

/// The constant part of a simulated body: topology, rest state, masses and stiffnesses. Built once
/// by build_model(); the time-varying part lives in State. Arrays are flat, one entry per item.
struct Model {
  CellModel cell_model = CellModel::kBaudet2007;
  /// kNeoHookean: each cell's correction and inversion recovery are replaced by the neo-Hookean
  /// cell term of law_constants (cell_correction and cell_inversion_stiffness are zero); such a
  /// body steps on the spring lists (the grid passes have no neo-Hookean term yet).
  CellLaw cell_law = CellLaw::kSprings;
  /// Per material: the neo-Hookean cell term's constants (empty for kSprings).
  std::vector<NeoHookeanConstants> law_constants;
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
  Eigen::Matrix3Xd rest_positions;       ///< (3 x num_nodes) [m]
  std::vector<Eigen::Vector3i> node_grid_index;  ///< grid index of each node
  Eigen::VectorXd mass;                  ///< [kg], lumped: each cell gives 1/8 of its mass to each corner
  Eigen::VectorXd mass_damping;          ///< Rayleigh alpha times mass [kg/s]

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

  /// Blocks of the force pass (docs/data-layout.md): block b holds the springs whose first node is
  /// in force_block_nodes[b] .. [b+1]-1; their second nodes stay below force_block_reach[b], which
  /// is at most the end of block b+1. Threads take whole blocks, and the count depends on the body
  /// alone, so forces do not depend on the thread count. Empty: one block of every node.
  std::vector<int> force_block_nodes;
  std::vector<int> force_block_reach;

  /// The body on the dense grid of its bounding box, which the explicit force passes use instead
  /// of the spring lists when the body fills at least kDefaultMinGridFill of the box
  /// (docs/data-layout.md); null otherwise. Built by build_model() from the arrays above, it
  /// keeps its own copy of the stiffnesses: after changing them, call update_grid_layout().
  std::shared_ptr<const GridLayout> grid_layout;

  int num_nodes() const { return static_cast<int>(rest_positions.cols()); }
  int num_springs() const { return static_cast<int>(spring_nodes.size()); }
  int num_cells() const { return static_cast<int>(cell_nodes.size()); }
  double rest_cell_volume() const { return cell_size.prod(); }
  double total_mass() const { return mass.sum(); }
  /// Index of the node at a grid index, or -1 when no cell uses it.
  int node_at(const Eigen::Vector3i& grid_index) const;

  /// Nodes whose rest position lies in the closed box [lower, upper] [m].
  std::vector<int> nodes_in_box(const Eigen::Vector3d& lower, const Eigen::Vector3d& upper) const;

 private:
  friend Result<Model> build_model(const LatticeDesc& desc);
  std::vector<std::int64_t> sorted_node_keys_;  // grid key of each node, ascending (= node order)
};

/// Validates the description (cell size, materials, cell indices, the model's validity for the
/// cell shape, at most kMaxCells cells) and builds the model. Errors name the value at fault and the allowed range.
Result<Model> build_model(const LatticeDesc& desc);

/// The fraction of its bounding box's cells a body fills at least for build_model() to put it on
/// the grid passes: from it the grid stepped every benched body faster, below it the spring lists
/// stepped some faster (`cubespring bench-layout`, docs/data-layout.md).
inline constexpr double kDefaultMinGridFill = 0.45;

/// The fewest nodes a layer across the box's longest axis holds for build_model() to number the
/// nodes along that axis (Model::major_axis): the grid passes split their layers between threads,
/// and more, smaller layers balance them better, but a layer's loops cost a fixed time each, which
/// shorter layers cannot repay (`docs/data-layout.md`).
inline constexpr int kMinMajorLayerNodes = 256;

/// Rebuilds model.grid_layout from the model's arrays, after a change to a built model's
/// stiffnesses, damping or corrections. The grid is built when the cells fill at least min_fill
/// of their bounding box (0: whenever the lattice allows; above 1, or NaN: never) and the
/// spring lists are used otherwise; both give the same forces to rounding. The grid costs about
/// 280 bytes per point of the box, however few of them the body holds; a box of more than 2^31
/// points gets no grid. A grid forced with a small min_fill is dropped again by a later call
/// with the default.
void update_grid_layout(Model& model, double min_fill = kDefaultMinGridFill);

/// Per-cell spring stiffnesses and correction of one material and cell shape
/// (docs/model-baudet2007.md, sections 2-4).
struct CellCalibration {
  Eigen::Vector3d edge_stiffness;  ///< per-cell share of each edge along x, y, z [N/m]
  double diagonal_stiffness = 0;   ///< each of the 4 body diagonals [N/m]
  Eigen::Matrix3d correction;      ///< D [Pa]
  double twist_stiffness = 0;      ///< zeta G [Pa]; 0 for the paper's model
};
Result<CellCalibration> calibrate_cell(CellModel model, const Material& material,
                                       const Eigen::Vector3d& cell_size,
                                       const ExactBendingParameters& parameters = {});

}  // namespace cubespring
