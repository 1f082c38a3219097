// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "forces/grid/grid_layout.h"

#include <algorithm>
#include <functional>
#include <limits>

#include <cmath>

#include "model/cell_geometry.h"

namespace cubespring {
namespace {

// The family of a spring from its two nodes' grid step, -1 if no family has it.
int family_of_step(const Eigen::Vector3i& step) {
  for (int axis = 0; axis < 3; ++axis) {
    if (step == Eigen::Vector3i::Unit(axis)) return axis;
  }
  for (int k = 0; k < 4; ++k) {
    if (step == corner_offset(7 - k) - corner_offset(k)) return kEdgeFamilies + k;
  }
  return -1;
}

// GridLayout::law_cells of a body of several materials. The law's constants differ between
// materials only in their moduli and the diagonals' stiffness (a lattice's cells are one size:
// Model::cell_size), which neo_hookean_cell_pass reads from here; the rest it takes from the
// first material.
void set_law_cells(GridLayout& grid) {
  const NeoHookeanConstants& first = grid.law_constants.front();
  GridLayout::LawCells& cells = grid.law_cells;
  const std::size_t size = grid.cell_law.size();
  cells.c10.assign(size, first.c10);
  cells.half_bulk.assign(size, first.half_bulk);
  cells.barrier.assign(size, first.barrier);
  cells.diagonal_stiffness.assign(size, first.diagonal_stiffness);
  cells.quarter.assign(size, 0.0);
  for (std::size_t point = 0; point < size; ++point) {
    const int law = grid.cell_law[point];
    if (law < 0) continue;
    const NeoHookeanConstants& constants = grid.law_constants[static_cast<std::size_t>(law)];
    cells.c10[point] = constants.c10;
    cells.half_bulk[point] = constants.half_bulk;
    cells.barrier[point] = constants.barrier;
    cells.diagonal_stiffness[point] = constants.diagonal_stiffness;
    cells.quarter[point] = 0.25;
  }
}

// The cells' coefficients as constants when every cell has the same (to the bit).
void set_uniform_cells(const Model& model, GridLayout& grid) {
  const int first = grid.point(model.cell_grid_index[0]);
  const auto same_in_every_cell = [&](const std::vector<double>& values) {
    const auto same_as_first = [&](const Eigen::Vector3i& cell) { return values[grid.point(cell)] == values[first]; };
    return values.empty() || std::all_of(model.cell_grid_index.begin(), model.cell_grid_index.end(), same_as_first);
  };
  grid.uniform_cells = std::all_of(grid.correction.begin(), grid.correction.end(), same_in_every_cell) &&
                       same_in_every_cell(grid.cell_twist) && same_in_every_cell(grid.cell_beta);
  if (!grid.uniform_cells) return;
  for (int i = 0; i < 6; ++i) grid.uniform_correction[i] = grid.correction[i][first];
  if (!grid.cell_twist.empty()) grid.uniform_twist = grid.cell_twist[first];
  if (!grid.cell_beta.empty()) grid.uniform_beta = grid.cell_beta[first];
}

// Whether every spring of family f has the stiffness and damping of one cell's share times its
// number of cells (to the bit): a diagonal's share is that of the first occupied cell, an
// edge's that of the first edge of one cell (every body has one: the x-edge at the far y and z
// side of its last cell, for one).
void set_uniform_family(GridLayout& grid, int f) {
  SpringFamily& family = grid.families[f];
  const bool diagonal = f >= kEdgeFamilies;
  const auto cells = [&](int point) {
    return diagonal ? grid.cell_occupied[grid.occupied_padding() + point] : grid.edge_cells(f, point);
  };
  family.uniform = false;
  int one_cell = 0;
  while (one_cell < grid.num_points && cells(one_cell) != 1) ++one_cell;
  if (one_cell == grid.num_points) return;
  family.cell_stiffness = family.stiffness[one_cell];
  family.cell_damping = family.damping.empty() ? 0.0 : family.damping[one_cell];
  for (int p = 0; p < grid.num_points; ++p) {
    const double count = cells(p);
    if (family.stiffness[p] != count * family.cell_stiffness ||
        (!family.damping.empty() && family.damping[p] != count * family.cell_damping)) {
      return;
    }
  }
  family.uniform = true;
}

}  // namespace

std::shared_ptr<const GridLayout> build_grid_layout(const Model& model, double min_fill) {
  const bool neo_hookean = model.cell_law == CellLaw::kNeoHookean;
  if (model.num_cells() == 0 || (neo_hookean && model.law_constants.size() != model.materials.size()) ||
      static_cast<int>(model.cell_grid_index.size()) != model.num_cells() ||
      static_cast<int>(model.node_grid_index.size()) != model.num_nodes()) {
    return nullptr;
  }
  Eigen::Vector3i lower = model.cell_grid_index[0], upper = lower;
  for (const Eigen::Vector3i& cell : model.cell_grid_index) {
    lower = lower.cwiseMin(cell);
    upper = upper.cwiseMax(cell);
  }
  auto layout = std::make_shared<GridLayout>();
  GridLayout& grid = *layout;
  const int major = model.major_axis;
  grid.model_axis = {(major + 1) % 3, (major + 2) % 3, major};
  const Eigen::Vector3i cells = grid.grid_step(upper - lower + Eigen::Vector3i::Ones());
  const double box_cells = static_cast<double>(cells.x()) * cells.y() * cells.z();
  if (!(model.num_cells() >= min_fill * box_cells)) return nullptr;  // NaN: never
  // points are indexed by int, with a layer and a row of padding on each side (a sparse body's
  // box, taken at a small min_fill, may be far larger than the body)
  const Eigen::Vector3d points = (cells + Eigen::Vector3i::Ones()).cast<double>();
  const double padded_points = points.prod() + 2.0 * (points.x() * points.y() + points.x() + 1.0);
  if (padded_points > static_cast<double>(std::numeric_limits<int>::max())) return nullptr;

  grid.first_node = lower;
  grid.points = cells + Eigen::Vector3i::Ones();
  grid.cell_size = {model.cell_size[grid.model_axis.x()], model.cell_size[grid.model_axis.y()],
                    model.cell_size[grid.model_axis.z()]};
  grid.stride_y = grid.points.x();
  grid.stride_z = grid.points.x() * grid.points.y();
  grid.num_points = grid.stride_z * grid.points.z();
  grid.padding = grid.stride_z + grid.stride_y + 1;
  const auto size = static_cast<std::size_t>(grid.num_points);

  grid.rest_points.resize(3, grid.num_points);
  for (int z = 0; z < grid.points.z(); ++z) {
    for (int y = 0; y < grid.points.y(); ++y) {
      for (int x = 0; x < grid.points.x(); ++x) {
        Eigen::Vector3i index = lower;
        index[grid.model_axis.x()] += x;
        index[grid.model_axis.y()] += y;
        index[grid.model_axis.z()] += z;
        grid.rest_points.col(grid.point(index)) = model.origin + index.cast<double>().cwiseProduct(model.cell_size);
      }
    }
  }
  grid.point_of_node.resize(model.num_nodes());
  for (int n = 0; n < model.num_nodes(); ++n) grid.point_of_node[n] = grid.point(model.node_grid_index[n]);
  // nodes come in the grid's z-major order, x fastest (Model::major_axis): a thread's layers hold a
  // contiguous range of them
  // (and the points of nodes strictly increase: the kick and copy-in rely on it)
  if (std::adjacent_find(grid.point_of_node.begin(), grid.point_of_node.end(), std::greater_equal<>()) !=
      grid.point_of_node.end()) {
    return nullptr;
  }

  grid.layer_spans.assign(static_cast<std::size_t>(grid.points.z()), PointSpan{});
  for (const int point : grid.point_of_node) {  // in increasing order
    const int in_layer = point % grid.stride_z;
    PointSpan& span = grid.layer_spans[static_cast<std::size_t>(point / grid.stride_z)];
    span = span.begin == span.end ? PointSpan{in_layer, in_layer + 1} : PointSpan{span.begin, in_layer + 1};
  }

  const int step_of_axis[3] = {1, grid.stride_y, grid.stride_z};
  for (int f = 0; f < kSpringFamilies; ++f) {
    SpringFamily& family = grid.families[f];
    if (f < kEdgeFamilies) {
      family.to = step_of_axis[f];
      family.to_corner = Eigen::Vector3i::Unit(f);
      family.rest_length = grid.cell_size[f];
      family.rows = f == 1 ? cells.y() : grid.points.y();
      family.slabs = f == 2 ? cells.z() : grid.points.z();
    } else {
      const int k = f - kEdgeFamilies;
      const Eigen::Vector3i from = corner_offset(k), to = corner_offset(7 - k);
      family.from = from.x() + grid.stride_y * from.y() + grid.stride_z * from.z();
      family.to = to.x() + grid.stride_y * to.y() + grid.stride_z * to.z();
      family.from_corner = from;
      family.to_corner = to;
      family.rest_length = model.cell_size.norm();
      family.rows = cells.y();
      family.slabs = cells.z();
    }
    family.stiffness.assign(size, 0.0);
    if (model.has_stiffness_damping) family.damping.assign(size, 0.0);
  }
  for (int s = 0; s < model.num_springs(); ++s) {
    const auto& ends = model.spring_nodes[s];
    const Eigen::Vector3i first = model.node_grid_index[ends[0]];
    const int f = family_of_step(grid.grid_step(model.node_grid_index[ends[1]] - first));
    if (f < 0) return nullptr;
    SpringFamily& family = grid.families[f];
    if (std::abs(model.spring_rest_length[s] - family.rest_length) > 1e-12 * family.rest_length) return nullptr;
    // edges are indexed by their first node, diagonals by their cell's corner 0
    const int point = grid.point(first) - family.from;
    family.stiffness[point] = model.spring_stiffness[s];
    if (model.has_stiffness_damping) family.damping[point] = model.spring_damping[s];
  }

  for (auto& coefficient : grid.correction) coefficient.assign(size, 0.0);
  grid.cell_occupied.assign(size + grid.occupied_padding(), 0.0);
  if (model.has_stiffness_damping) grid.cell_beta.assign(size, 0.0);
  grid.has_twist = model.has_twist;
  if (model.has_twist) grid.cell_twist.assign(size, 0.0);
  grid.cell_rows = cells.y();
  grid.cell_slabs = cells.z();
  grid.neo_hookean = neo_hookean;
  if (neo_hookean) {
    grid.cell_law.assign(size, -1);
    for (NeoHookeanConstants constants : model.law_constants) {  // along the grid's axes
      constants.cell_size = constants.cell_size(grid.model_axis).eval();
      constants.edge_stiffness = constants.edge_stiffness(grid.model_axis).eval();
      grid.law_constants.push_back(constants);
    }
  }
  for (int c = 0; c < model.num_cells(); ++c) {
    const int point = grid.point(model.cell_grid_index[c]);
    const Eigen::Matrix3d d = model.cell_correction[c](grid.model_axis, grid.model_axis);
    // 6 coefficients are kept: a correction that is not symmetric (to rounding) stays on the lists
    if ((d - d.transpose()).cwiseAbs().maxCoeff() > 1e-12 * d.cwiseAbs().maxCoeff()) return nullptr;
    const double coefficients[6] = {d(0, 0), d(1, 1), d(2, 2), d(0, 1), d(0, 2), d(1, 2)};
    for (int i = 0; i < 6; ++i) grid.correction[i][point] = coefficients[i];
    grid.cell_occupied[grid.occupied_padding() + point] = 1.0;
    if (model.has_twist) grid.cell_twist[point] = model.cell_twist_stiffness[c];
    if (neo_hookean) grid.cell_law[point] = model.cell_material[c];
    if (model.has_stiffness_damping && !neo_hookean) {  // the neo-Hookean term's correction has no rate
      grid.cell_beta[point] = model.materials[model.cell_material[c]].stiffness_damping;
    }
  }
  if (neo_hookean && grid.law_constants.size() > 1) set_law_cells(grid);
  set_uniform_cells(model, grid);
  for (int f = 0; f < kSpringFamilies; ++f) set_uniform_family(grid, f);
  return layout;
}

}  // namespace cubespring
