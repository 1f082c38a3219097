// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "cubespring/cell_removal.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <numeric>
#include <set>
#include <string>
#include <utility>

#include "model/topology_change.h"

namespace cubespring {
namespace {

// Where each cell of `before` is among `after`'s cells (-1: removed): the kept cells in their
// order when the numbering axis is the same (build_model() orders cells by grid key), else found
// by grid index.
std::vector<int> cells_in(const Model& after, const Model& before, const std::vector<char>& removed) {
  std::vector<int> at(static_cast<std::size_t>(before.num_cells()), -1);
  int next = 0;
  bool in_order = after.major_axis == before.major_axis;
  for (int c = 0; c < before.num_cells() && in_order; ++c) {
    if (removed[static_cast<std::size_t>(c)]) continue;
    in_order = next < after.num_cells() && after.cell_grid_index[static_cast<std::size_t>(next)] ==
                                               before.cell_grid_index[static_cast<std::size_t>(c)];
    at[static_cast<std::size_t>(c)] = next++;
  }
  if (in_order && next == after.num_cells()) return at;
  std::map<std::array<int, 3>, int> cell_at;
  for (int c = 0; c < after.num_cells(); ++c) {
    const Eigen::Vector3i& g = after.cell_grid_index[static_cast<std::size_t>(c)];
    cell_at.emplace(std::array<int, 3>{g.x(), g.y(), g.z()}, c);
  }
  for (int c = 0; c < before.num_cells(); ++c) {
    const Eigen::Vector3i& g = before.cell_grid_index[static_cast<std::size_t>(c)];
    at[static_cast<std::size_t>(c)] = removed[static_cast<std::size_t>(c)] ? -1 : cell_at.at({g.x(), g.y(), g.z()});
  }
  return at;
}

}  // namespace

Result<CellRemoval> remove_cells(const Model& model, const State& state, const Constraints& constraints,
                                 const std::vector<int>& cells) {
  if (Status sizes = check_body_sizes(model, state, constraints); !sizes) return sizes;
  const int num_cells = model.num_cells();
  std::vector<char> removed(static_cast<std::size_t>(num_cells), 0);
  for (const int cell : cells) {
    if (cell < 0 || cell >= num_cells) {
      return Status::error("cell " + std::to_string(cell) + " to remove is out of range: the body has " +
                           std::to_string(num_cells) + " cells");
    }
    removed[static_cast<std::size_t>(cell)] = 1;
  }
  CellRemoval removal;
  removal.removed_cells = static_cast<int>(std::count(removed.begin(), removed.end(), char{1}));
  if (removal.removed_cells == num_cells) {
    return Status::error("removing all " + std::to_string(num_cells) +
                         " cells of the body would leave nothing: remove the body instead");
  }

  LatticeDesc desc = lattice_desc(model);
  desc.cells.clear();
  desc.cell_material.clear();
  // a split face goes with either of its cells
  std::set<std::array<int, 3>> gone;
  for (int c = 0; c < num_cells; ++c) {
    const Eigen::Vector3i& g = model.cell_grid_index[static_cast<std::size_t>(c)];
    if (removed[static_cast<std::size_t>(c)]) gone.insert({g.x(), g.y(), g.z()});
  }
  desc.split_faces.clear();
  for (const CellFace& face : model.split_faces) {
    Eigen::Vector3i next = face.cell;
    next[face.axis] += 1;
    if (gone.count({face.cell.x(), face.cell.y(), face.cell.z()}) == 0 &&
        gone.count({next.x(), next.y(), next.z()}) == 0)
      desc.split_faces.push_back(face);
  }
  const double volume = model.rest_cell_volume();
  for (int c = 0; c < num_cells; ++c) {
    const std::size_t ci = static_cast<std::size_t>(c);
    if (!removed[ci]) {
      desc.cells.push_back(model.cell_grid_index[ci]);
      desc.cell_material.push_back(model.cell_material[ci]);
      continue;
    }
    // what leaves with the cell: its lumped mass at its corners' velocities
    const double mass = model.materials[static_cast<std::size_t>(model.cell_material[ci])].density * volume;
    removal.removed_mass += mass;
    for (const int node : model.cell_nodes[ci]) {
      removal.removed_momentum += mass / kCornersPerCell * state.velocities.col(node);
    }
  }
  Result<Model> rebuilt = build_model(desc);
  if (!rebuilt) return Status::error("the body without the removed cells: " + rebuilt.message());
  removal.model = std::move(rebuilt).value();
  const Model& after = removal.model;

  // the remaining cells are the same cells: each keeps its corners' nodes (a node's copies, where
  // split faces made them, are told apart by the cells that have them, not by their grid index)
  removal.new_cell.assign(static_cast<std::size_t>(num_cells), -1);
  const std::vector<int> kept_cell = cells_in(after, model, removed);
  removal.new_node.assign(static_cast<std::size_t>(model.num_nodes()), -1);
  removal.source_node.assign(static_cast<std::size_t>(after.num_nodes()), -1);
  std::vector<char> joined(static_cast<std::size_t>(after.num_nodes()), 0);  // from more than one old node
  bool any_joined = false;
  for (int c = 0; c < num_cells; ++c) {
    const int to = kept_cell[static_cast<std::size_t>(c)];
    if (to < 0) continue;
    removal.new_cell[static_cast<std::size_t>(c)] = to;
    for (std::size_t k = 0; k < kCornersPerCell; ++k) {
      const int old = model.cell_nodes[static_cast<std::size_t>(c)][k];
      const int node = after.cell_nodes[static_cast<std::size_t>(to)][k];
      removal.new_node[static_cast<std::size_t>(old)] = node;
      int& source = removal.source_node[static_cast<std::size_t>(node)];
      if (source >= 0 && source != old) joined[static_cast<std::size_t>(node)] = 1, any_joined = true;
      if (source < 0) source = old;
    }
  }
  // each new node from its old one; where the removed cells alone held a node together its copies
  // start alike, and where they alone held a node's copies apart they are one node again, at the
  // mean of their places and velocities weighted by the mass of the cells each brings (each cell's
  // eighth at its corner), so that momentum is kept
  removal.state.positions.resize(3, after.num_nodes());
  removal.state.velocities.resize(3, after.num_nodes());
  removal.state.time = state.time;
  for (int n = 0; n < after.num_nodes(); ++n) {
    removal.state.positions.col(n) = state.positions.col(removal.source_node[static_cast<std::size_t>(n)]);
    removal.state.velocities.col(n) = state.velocities.col(removal.source_node[static_cast<std::size_t>(n)]);
  }
  if (any_joined) {
    Eigen::VectorXd weight = Eigen::VectorXd::Zero(after.num_nodes());
    for (int n = 0; n < after.num_nodes(); ++n) {
      if (!joined[static_cast<std::size_t>(n)]) continue;
      removal.state.positions.col(n).setZero();
      removal.state.velocities.col(n).setZero();
    }
    for (int c = 0; c < num_cells; ++c) {
      const int to = kept_cell[static_cast<std::size_t>(c)];
      if (to < 0) continue;
      const double eighth =
          model.materials[static_cast<std::size_t>(model.cell_material[static_cast<std::size_t>(c)])].density * volume /
          kCornersPerCell;
      for (std::size_t k = 0; k < kCornersPerCell; ++k) {
        const int node = after.cell_nodes[static_cast<std::size_t>(to)][k];
        if (!joined[static_cast<std::size_t>(node)]) continue;
        const int old = model.cell_nodes[static_cast<std::size_t>(c)][k];
        removal.state.positions.col(node) += eighth * state.positions.col(old);
        removal.state.velocities.col(node) += eighth * state.velocities.col(old);
        weight[node] += eighth;
      }
    }
    for (int n = 0; n < after.num_nodes(); ++n) {
      if (!joined[static_cast<std::size_t>(n)]) continue;
      removal.state.positions.col(n) /= weight[n];
      removal.state.velocities.col(n) /= weight[n];
    }
  }

  Result<Constraints> carried = constraints.gathered(removal.source_node);
  if (!carried) return carried.status();
  removal.constraints = std::move(carried).value();
  removal.pieces = count_pieces(after);
  return removal;
}

Eigen::Matrix3Xd carry_node_columns(const CellRemoval& removal, const Eigen::Matrix3Xd& per_node) {
  if (per_node.cols() == 0) return per_node;  // none (Loads::nodal_forces may be empty)
  Eigen::Matrix3Xd carried = Eigen::Matrix3Xd::Zero(3, removal.model.num_nodes());
  const Eigen::Index columns =
      std::min<Eigen::Index>(per_node.cols(), static_cast<Eigen::Index>(removal.new_node.size()));
  for (Eigen::Index n = 0; n < columns; ++n) {
    const int to = removal.new_node[static_cast<std::size_t>(n)];
    if (to >= 0) carried.col(to) = per_node.col(n);
  }
  return carried;
}

}  // namespace cubespring
