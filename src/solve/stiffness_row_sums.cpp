// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "cubespring/stiffness_row_sums.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "solve/gershgorin.h"

namespace cubespring {

SparseMatrix rest_stiffness(const Model& model) {
  return StiffnessAssembler(model).assemble_once(model, model.rest_positions, StiffnessKind::kPositiveSemiDefinite, 1.0,
                                                 0.0);
}

Eigen::VectorXd node_row_sums(const SparseMatrix& stiffness) {
  Eigen::VectorXd sums = Eigen::VectorXd::Zero(stiffness.rows() / 3);
  for (int row = 0; row < stiffness.rows(); ++row) {
    double sum = 0.0;
    for (SparseMatrix::InnerIterator it(stiffness, row); it; ++it) sum += std::abs(it.value());
    sums[row / 3] = std::max(sums[row / 3], sum);
  }
  return sums;
}

Eigen::VectorXd stiffness_row_sums(const Model& model) { return node_row_sums(rest_stiffness(model)); }

Eigen::VectorXd stiffness_row_sums_after(const Model& before, const Eigen::VectorXd& before_sums,
                                         const CellRemoval& removal) {
  const Model& after = removal.model;
  if (before_sums.size() != before.num_nodes() || static_cast<int>(removal.new_node.size()) != before.num_nodes() ||
      static_cast<int>(removal.new_cell.size()) != before.num_cells()) {
    throw std::invalid_argument("stiffness_row_sums_after: " + std::to_string(before_sums.size()) + " row sums, " +
                                std::to_string(removal.new_node.size()) + " node and " +
                                std::to_string(removal.new_cell.size()) + " cell maps for a body of " +
                                std::to_string(before.num_nodes()) + " nodes and " +
                                std::to_string(before.num_cells()) + " cells");
  }
  Eigen::VectorXd sums(after.num_nodes());
  for (int n = 0; n < before.num_nodes(); ++n) {
    const int to = removal.new_node[static_cast<std::size_t>(n)];
    if (to >= 0) sums[to] = before_sums[n];
  }
  // the nodes that lost a cell: their rows change, every other row is as it was
  std::vector<char> changed(static_cast<std::size_t>(after.num_nodes()), 0);
  bool any = false;
  for (int c = 0; c < before.num_cells(); ++c) {
    if (removal.new_cell[static_cast<std::size_t>(c)] >= 0) continue;
    for (const int node : before.cell_nodes[static_cast<std::size_t>(c)]) {
      const int to = removal.new_node[static_cast<std::size_t>(node)];
      if (to >= 0) changed[static_cast<std::size_t>(to)] = 1, any = true;
    }
  }
  if (!any) return sums;
  // their rows hold every cell that shares a node with them: a body of those cells alone has them
  LatticeDesc around = lattice_desc(after);
  around.cells.clear();
  around.cell_material.clear();
  std::vector<int> around_cells;  // of `after`
  std::set<std::array<int, 3>> taken;
  for (int c = 0; c < after.num_cells(); ++c) {
    const auto& corners = after.cell_nodes[static_cast<std::size_t>(c)];
    if (std::none_of(corners.begin(), corners.end(), [&](int n) { return changed[static_cast<std::size_t>(n)]; }))
      continue;
    const Eigen::Vector3i& g = after.cell_grid_index[static_cast<std::size_t>(c)];
    around.cells.push_back(g);
    around.cell_material.push_back(after.cell_material[static_cast<std::size_t>(c)]);
    around_cells.push_back(c);
    taken.insert({g.x(), g.y(), g.z()});
  }
  around.split_faces.clear();  // those between two of its cells
  for (const CellFace& face : after.split_faces) {
    Eigen::Vector3i next = face.cell;
    next[face.axis] += 1;
    if (taken.count({face.cell.x(), face.cell.y(), face.cell.z()}) != 0 &&
        taken.count({next.x(), next.y(), next.z()}) != 0)
      around.split_faces.push_back(face);
  }
  Result<Model> local = build_model(around);
  // a part of a body that was built from the same description builds
  if (!local) throw std::logic_error("stiffness_row_sums_after: the cells around the cut: " + local.message());
  const Eigen::VectorXd local_sums = stiffness_row_sums(*local);
  // a node of the body is the same corner of the same cell in the part (copies of a node at one
  // grid point, where faces are split, are told apart by their cells)
  std::map<std::array<int, 3>, int> local_cell_at;
  for (int c = 0; c < local->num_cells(); ++c) {
    const Eigen::Vector3i& g = local->cell_grid_index[static_cast<std::size_t>(c)];
    local_cell_at.emplace(std::array<int, 3>{g.x(), g.y(), g.z()}, c);
  }
  for (const int c : around_cells) {
    const Eigen::Vector3i& g = after.cell_grid_index[static_cast<std::size_t>(c)];
    const int in_local = local_cell_at.at({g.x(), g.y(), g.z()});
    for (std::size_t k = 0; k < kCornersPerCell; ++k) {
      const int n = after.cell_nodes[static_cast<std::size_t>(c)][k];
      if (changed[static_cast<std::size_t>(n)])
        sums[n] = local_sums[local->cell_nodes[static_cast<std::size_t>(in_local)][k]];
    }
  }
  return sums;
}

}  // namespace cubespring
