// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The body laid out on the dense grid of its bounding box, for the structured force passes
// (grid_forces.h; docs/data-layout.md, "Dense bodies: the grid passes"). Springs are found by
// index arithmetic, so the passes run over contiguous ranges the compiler vectorises; points of
// the box outside the body carry zero stiffness.
#pragma once

#include <array>
#include <cstddef>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "cubespring/cell_law.h"
#include "cubespring/model.h"

namespace cubespring {

/// Consecutive points of a z-layer, [begin, end) from its first point.
struct PointSpan {
  int begin = 0, end = 0;
};

/// Springs of one direction: those from point g + from to point g + to, for the points g of
/// `slabs` z-layers, each its first `rows` y-rows of the grid (whole rows, every x; the passes
/// compute those in the layer's span, layer_spans).
/// Families 0-2 are the x, y and z edges (indexed by their first node), 3-6 the body diagonals
/// from corner k to corner 7 - k of the cell whose corner 0 is g.
struct SpringFamily {
  int from = 0, to = 0;
  Eigen::Vector3i from_corner{0, 0, 0}, to_corner{0, 0, 0};  ///< the same steps, in cells along x, y, z
  int rows = 0, slabs = 0;
  double rest_length = 0;         ///< the same for every spring of the family [m]
  std::vector<double> stiffness;  ///< per point [N/m]; 0 where the body has no such spring
  std::vector<double> damping;    ///< beta times stiffness [N s/m]; empty without stiffness damping
  /// A family of a body of one material: stiffness and damping are these times the number of
  /// the spring's cells in the body (a diagonal's 1, an edge's 1 to 4; GridLayout::edge_cells)
  /// at every point, and the passes count them from the cells' occupancy instead.
  bool uniform = false;
  double cell_stiffness = 0.0, cell_damping = 0.0;
};
inline constexpr int kEdgeFamilies = 3;
inline constexpr int kSpringFamilies = 7;

/// The grid's axes are the model's, turned so that the grid's z is Model::major_axis: the passes
/// sweep z-layers, and the points follow the model's node order. Everything below is along the
/// grid's x, y, z but for first_node, rest_points and the model's indices that point() takes.
struct GridLayout {
  Eigen::Vector3i model_axis{0, 1, 2};  ///< the model's axis along the grid's x, y, z (a cyclic turn)
  Eigen::Vector3i first_node{0, 0, 0};  ///< the model's grid index of point 0
  Eigen::Vector3i points{0, 0, 0};      ///< grid points along x, y, z (cells + 1)
  Eigen::Vector3d cell_size{0, 0, 0};   ///< [m]
  int stride_y = 0, stride_z = 0;       ///< point index steps along y and z
  int num_points = 0;
  /// The arrays of every point (state and forces, grid_forces.cpp) have this many points on each
  /// side beyond the grid, so that a spring or a cell at any point may read its neighbours
  /// without bounds checks.
  int padding = 0;
  std::vector<int> point_of_node;  ///< model node -> grid point, increasing
  /// The points of each z-layer the passes compute: from its first node to its last (empty
  /// where the layer has none). Every spring, cell and face of the body starts at one of its
  /// nodes, so the passes skip the points of the box before and after them (a sixth of the demo
  /// liver's box, a third of the 4 mm liver's; the rows between stay: a loop over one long span
  /// vectorises, a loop over each row's short span of nodes was slower than the whole layer).
  std::vector<PointSpan> layer_spans;
  Eigen::Matrix3Xd rest_points;  ///< rest position of every point [m]
  std::array<SpringFamily, kSpringFamilies> families;

  // cells, indexed by the point of their corner 0 (zero outside the body)
  std::array<std::vector<double>, 6> correction;  ///< D: xx, yy, zz, xy, xz, yz [Pa]
  std::vector<double> cell_beta;                  ///< the material's beta [s]; empty without stiffness damping
  /// 1 for a cell of the body, else 0; from index occupied_padding() (zeros before it: the cells
  /// around an edge lie up to a step back along each other axis, the layer below the grid too)
  std::vector<double> cell_occupied;
  std::vector<double> cell_twist;  ///< zeta G [Pa] (exact-bending model); empty without twist
  bool has_twist = false;
  int cell_rows = 0, cell_slabs = 0;  ///< cells per x-row are whole rows too
  /// Every cell has the same correction, twist stiffness and beta (a body of one material): the
  /// cell pass takes these times cell_occupied and leaves the per-cell arrays above in memory.
  bool uniform_cells = false;
  std::array<double, 6> uniform_correction{};  ///< [Pa]
  double uniform_twist = 0.0;                  ///< [Pa]
  double uniform_beta = 0.0;                   ///< [s]

  /// A neo-Hookean body (Model::cell_law): its cells add the law's term (neo_hookean_cell.h) and
  /// have no crushed-cell recovery; `correction` is the term's edge correction, `cell_beta` zero
  /// (the law adds no damping to it).
  bool neo_hookean = false;
  /// The law's constants of each material, along the grid's axes.
  std::vector<NeoHookeanConstants> law_constants;
  /// The index into law_constants of the cell at each point, -1 where there is none.
  std::vector<int> cell_law;
  /// A body of several materials: the constants that differ between them, at each point (an
  /// empty cell's are the first material's), and 1/4 at a cell of the body, 0 elsewhere, so that
  /// pass 1b's loop over a layer vectorises as a body of one material's does. Empty for a body of
  /// one material.
  struct LawCells {
    std::vector<double> c10, half_bulk, barrier, diagonal_stiffness, quarter;
  };
  LawCells law_cells;

  int occupied_padding() const { return stride_z + stride_y + 1; }
  /// cell_occupied from the first point of layer `slab`.
  const double* occupied_from_layer(int slab) const {
    return cell_occupied.data() + occupied_padding() + static_cast<std::ptrdiff_t>(slab) * stride_z;
  }
  /// The cells of the body that share the edge of family f (x, y or z) at `point`: the cell
  /// whose corner 0 is there and those a step back along either other axis, or both.
  int edge_cells(int f, int point) const {
    const int b = f == 0 ? stride_y : 1, c = f == 2 ? stride_y : stride_z;
    const double* at = cell_occupied.data() + occupied_padding() + point;
    return static_cast<int>((at[0] + at[-b]) + (at[-c] + at[-b - c]));
  }

  /// The point at a model's grid index.
  int point(const Eigen::Vector3i& index) const {
    const Eigen::Vector3i local = index - first_node;
    return local[model_axis.x()] + stride_y * local[model_axis.y()] + stride_z * local[model_axis.z()];
  }
  /// A step along the model's axes as a step along the grid's.
  Eigen::Vector3i grid_step(const Eigen::Vector3i& model_step) const {
    return {model_step[model_axis.x()], model_step[model_axis.y()], model_step[model_axis.z()]};
  }
};

/// Whether nodes [begin, end) lie on consecutive grid points (a box's do): point_of_node strictly
/// increases, so its ends tell. Then node n is at point n + point_of_node[begin] - begin.
inline bool on_consecutive_points(const int* point_of_node, int begin, int end) {
  return begin == end || point_of_node[end - 1] - point_of_node[begin] == end - 1 - begin;
}

/// The grid layout of a built model, or null when the model does not suit it: a box filled less
/// than min_fill (the grid passes spend their work on every point of the box), or cells whose
/// springs are not the lattice's. Either cell law.
std::shared_ptr<const GridLayout> build_grid_layout(const Model& model, double min_fill = kDefaultMinGridFill);

}  // namespace cubespring
