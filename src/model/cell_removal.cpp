// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "cubespring/cell_removal.h"

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <string>
#include <utility>

namespace cubespring {
namespace {

// Pieces that cells sharing a node make: union-find over the nodes, each cell joining its corners.
int count_pieces(const Model& model) {
  std::vector<int> parent(static_cast<std::size_t>(model.num_nodes()));
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&](int n) {
    while (parent[static_cast<std::size_t>(n)] != n) {
      int& up = parent[static_cast<std::size_t>(n)];
      up = parent[static_cast<std::size_t>(up)];  // halve the path as we go
      n = up;
    }
    return n;
  };
  for (const auto& corners : model.cell_nodes) {
    for (int corner = 1; corner < kCornersPerCell; ++corner) {
      const int a = root(corners[0]), b = root(corners[static_cast<std::size_t>(corner)]);
      if (a != b) parent[static_cast<std::size_t>(b)] = a;
    }
  }
  int pieces = 0;
  for (int n = 0; n < model.num_nodes(); ++n) pieces += root(n) == n;
  return pieces;
}

Status check_sizes(const Model& model, const State& state, const Constraints& constraints) {
  const Eigen::Index nodes = model.num_nodes();
  if (state.positions.cols() != nodes || state.velocities.cols() != nodes) {
    return Status::error("the state has " + std::to_string(state.positions.cols()) + " positions and " +
                         std::to_string(state.velocities.cols()) + " velocities for a body of " +
                         std::to_string(nodes) + " nodes");
  }
  if (constraints.num_nodes() != nodes) {
    return Status::error("the constraints are for " + std::to_string(constraints.num_nodes()) +
                         " nodes, the body has " + std::to_string(nodes));
  }
  return {};
}

}  // namespace

Result<CellRemoval> remove_cells(const Model& model, const State& state, const Constraints& constraints,
                                 const std::vector<int>& cells) {
  if (Status sizes = check_sizes(model, state, constraints); !sizes) return sizes;
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

  removal.new_node.assign(static_cast<std::size_t>(model.num_nodes()), -1);
  removal.state.positions.resize(3, after.num_nodes());
  removal.state.velocities.resize(3, after.num_nodes());
  removal.state.time = state.time;
  for (int n = 0; n < after.num_nodes(); ++n) {
    const int old = model.node_at(after.node_grid_index[static_cast<std::size_t>(n)]);
    removal.new_node[static_cast<std::size_t>(old)] = n;
    removal.state.positions.col(n) = state.positions.col(old);
    removal.state.velocities.col(n) = state.velocities.col(old);
  }
  // a remaining cell's corners are nodes of both models: find its new index from its first corner
  removal.new_cell.assign(static_cast<std::size_t>(num_cells), -1);
  std::vector<int> cell_at_first_corner(static_cast<std::size_t>(after.num_nodes()), -1);
  for (int c = 0; c < after.num_cells(); ++c)
    cell_at_first_corner[static_cast<std::size_t>(after.cell_nodes[static_cast<std::size_t>(c)][0])] = c;
  for (int c = 0; c < num_cells; ++c) {
    if (removed[static_cast<std::size_t>(c)]) continue;
    const int first = removal.new_node[static_cast<std::size_t>(model.cell_nodes[static_cast<std::size_t>(c)][0])];
    removal.new_cell[static_cast<std::size_t>(c)] = cell_at_first_corner[static_cast<std::size_t>(first)];
  }

  Result<Constraints> carried = constraints.renumbered(removal.new_node, after.num_nodes());
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
