// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "grid_ldlt.h"

#include <algorithm>
#include <numeric>

namespace cubespring {
namespace {

// Parts this small are ordered as they come: their dense block costs little.
constexpr std::size_t kSmallestPart = 16;

// Appends `nodes` to `order`, halves first and the plane between them last.
void dissect(const Model& model, std::vector<int> nodes, std::vector<int>& order) {
  if (nodes.size() <= kSmallestPart) {
    order.insert(order.end(), nodes.begin(), nodes.end());
    return;
  }
  Eigen::Vector3i lo = model.node_grid_index[nodes[0]], hi = lo;
  for (const int n : nodes) {
    lo = lo.cwiseMin(model.node_grid_index[n]);
    hi = hi.cwiseMax(model.node_grid_index[n]);
  }
  int axis = 0;
  (hi - lo).maxCoeff(&axis);
  if (hi[axis] - lo[axis] < 2) {  // no plane with nodes on both sides
    order.insert(order.end(), nodes.begin(), nodes.end());
    return;
  }
  // nodes are coupled only to nodes at most one index away (they share a cell), so the plane at
  // `middle` separates the two sides
  const int middle = (lo[axis] + hi[axis]) / 2;
  std::vector<int> below, plane, above;
  for (const int n : nodes) {
    const int at = model.node_grid_index[n][axis];
    (at < middle ? below : at == middle ? plane : above).push_back(n);
  }
  nodes.clear();
  nodes.shrink_to_fit();
  dissect(model, std::move(below), order);
  dissect(model, std::move(above), order);
  order.insert(order.end(), plane.begin(), plane.end());
}

}  // namespace

std::vector<int> nested_dissection_order(const Model& model) {
  std::vector<int> nodes(model.num_nodes());
  std::iota(nodes.begin(), nodes.end(), 0);
  std::vector<int> order;
  order.reserve(nodes.size());
  dissect(model, std::move(nodes), order);
  return order;
}

GridLDLT::GridLDLT(const Model& model) : permutation_(3 * model.num_nodes()) {
  const std::vector<int> order = nested_dissection_order(model);
  for (std::size_t place = 0; place < order.size(); ++place) {
    for (int a = 0; a < 3; ++a) permutation_.indices()[3 * order[place] + a] = static_cast<int>(3 * place + a);
  }
}

bool GridLDLT::factorise(const Eigen::SparseMatrix<double>& k, double shift) {
  Eigen::SparseMatrix<double> permuted;
  permuted = k.twistedBy(permutation_);
  for (int i = 0; i < permuted.rows(); ++i) permuted.coeffRef(i, i) += shift;
  if (!analysed_) {
    ldlt_.analyzePattern(permuted);
    analysed_ = true;
  }
  ldlt_.factorize(permuted);
  return ldlt_.info() == Eigen::Success;
}

Eigen::VectorXd GridLDLT::solve(const Eigen::VectorXd& b) const {
  const Eigen::VectorXd permuted = permutation_ * b;
  return permutation_.inverse() * Eigen::VectorXd(ldlt_.solve(permuted));
}

Eigen::VectorXd GridLDLT::pivot_direction(Eigen::Index i) const {
  Eigen::VectorXd unit = Eigen::VectorXd::Zero(ldlt_.vectorD().size());
  unit[i] = 1.0;
  return permutation_.inverse() * Eigen::VectorXd(ldlt_.matrixU().solve(unit));
}

}  // namespace cubespring
