// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// A sparse LDL^T of a lattice's stiffness (3 degrees of freedom a node, node-major) in a nested-
// dissection order of the node grid: a plane of nodes splits the grid's longest side in halves,
// each half is ordered the same way, and the plane's nodes come last. On the lattice's 3D grid
// this fills and costs far less than Eigen's minimum-degree ordering (AMD): a Newton iteration
// of the static solver on 16^3 cells took 7 s with AMD (docs/model-neo-hookean.md section 5).
#pragma once

#include <vector>

#include <Eigen/SparseCholesky>

#include "cubespring/model.h"

namespace cubespring {

/// The nodes in nested-dissection order of their grid indices.
std::vector<int> nested_dissection_order(const Model& model);

class GridLDLT {
 public:
  explicit GridLDLT(const Model& model);

  /// Factorises k + shift I (k: 3 rows per node of the model); false when that fails (a zero
  /// pivot).
  bool factorise(const Eigen::SparseMatrix<double>& k, double shift);
  /// The pivots D, in elimination order. Their signs are the inertia of k + shift I.
  Eigen::VectorXd pivots() const { return ldlt_.vectorD(); }
  /// x with (k + shift I) x = b.
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;
  /// v with v^T (k + shift I) v = pivots()[i] (a direction of negative curvature where that
  /// pivot is negative).
  Eigen::VectorXd pivot_direction(Eigen::Index i) const;

 private:
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> permutation_;  // dof -> its place
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::NaturalOrdering<int>> ldlt_;
  bool analysed_ = false;
};

}  // namespace cubespring
