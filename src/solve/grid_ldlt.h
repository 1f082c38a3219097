// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// A sparse LDL^T of a lattice's stiffness (3 degrees of freedom a node, node-major), multifrontal
// in a nested-dissection order of the node grid: a plane of nodes splits the grid's longest side in
// halves, each half is ordered the same way, and the plane's nodes come last. Each plane (and each
// part too small to split) is one front: a dense matrix of its own unknowns and the later ones they
// couple to, factorised with dense kernels, its Schur complement passed on to the front it feeds.
// No pivoting: the pivots' signs are the matrix's inertia, which the static solver reads. On 16^3
// cells a factorisation took 7 s with Eigen's simplicial LDL^T in minimum-degree (AMD) order.
#pragma once

#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "cubespring/model.h"

namespace cubespring {

/// The nodes in nested-dissection order of their grid indices.
std::vector<int> nested_dissection_order(const Model& model);

class GridLDLT {
 public:
  explicit GridLDLT(const Model& model);

  /// Factorises k + shift I (k: 3 rows per node of the model, both triangles stored, the same
  /// pattern at every call); false when that fails (a zero or non-finite pivot).
  bool factorise(const Eigen::SparseMatrix<double>& k, double shift);
  /// The pivots D, in elimination order. Their signs are the inertia of k + shift I.
  const Eigen::VectorXd& pivots() const { return pivots_; }
  /// x with (k + shift I) x = b.
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;
  /// v with v^T (k + shift I) v = pivots()[i] (a direction of negative curvature where that
  /// pivot is negative).
  Eigen::VectorXd pivot_direction(Eigen::Index i) const;
  /// The factor's dense fronts [bytes] (estimate_block_factorisation counts them beforehand).
  double factor_bytes() const;

 private:
  struct Front {
    int begin = 0, end = 0;     // its own unknowns: places [begin, end) in elimination order
    std::vector<int> update;    // the later places it couples to, ascending
    std::vector<int> children;  // fronts whose update it takes
    Eigen::MatrixXd lower;      // (own + update) x own: unit lower L11 over L21
  };
  void analyse(const Eigen::SparseMatrix<double>& permuted);
  // L^-1 and L^-T on a vector in elimination order
  void forward(Eigen::VectorXd& y) const;
  void backward(Eigen::VectorXd& y) const;

  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> permutation_;  // dof -> its place
  std::vector<int> front_ends_;  // in nodes' places: where each front's nodes end
  std::vector<Front> fronts_;    // in elimination order
  Eigen::VectorXd pivots_;
  bool analysed_ = false;
};

}  // namespace cubespring
