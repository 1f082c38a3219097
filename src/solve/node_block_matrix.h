// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// A sparse matrix of 3 x 3 blocks, one block row per node, for the multigrid's levels: a lattice's
// matrix couples a node's three axes with each neighbour's, so a block keeps one column index for
// its 9 values and a row's products run in three independent sums, where the scalar rows of
// SparseMatrix take an index per value and one chain of adds (a backward Gauss-Seidel sweep on
// them took 3.5 times the forward one on 64x16x16 cells). The blocks are single precision: the
// smoother's passes over them are bound by memory, and a preconditioner needs to be symmetric
// positive definite, not exact (the products are summed in double).
#pragma once

#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "cubespring/stiffness.h"

namespace cubespring {

class NodeBlockMatrix {
 public:
  /// Takes `a` (3 rows a node, square; the rows of a node may have different patterns: a missing
  /// entry is a zero) and inverts each node's diagonal block. False when one of those is not
  /// positive definite (then nothing but another assign() may be used).
  bool assign(const SparseMatrix& a);
  /// The same for a matrix of the last assign()'s pattern (the next step's, from the same
  /// assembler): its values only, copied by a map kept from assign(). Assigns anew when the
  /// pattern's size differs.
  bool update(const SparseMatrix& a);
  /// Starts a matrix of the given block pattern (row n's blocks: columns[row_begin[n] ..
  /// row_begin[n + 1]), ascending), every block zero, to be filled through block().
  void start(std::vector<int> row_begin, std::vector<int> columns);
  /// Inverts each node's diagonal block (after start() and filling): false as assign().
  bool invert_diagonal();

  int nodes() const { return static_cast<int>(row_begin_.size()) - 1; }
  int row_begin(int node) const { return row_begin_[static_cast<std::size_t>(node)]; }
  int column(int k) const { return column_[static_cast<std::size_t>(k)]; }
  Eigen::Map<const Eigen::Matrix3f> block(int k) const {
    return Eigen::Map<const Eigen::Matrix3f>(&value_[9 * static_cast<std::size_t>(k)]);
  }
  Eigen::Map<Eigen::Matrix3f> block(int k) {
    return Eigen::Map<Eigen::Matrix3f>(&value_[9 * static_cast<std::size_t>(k)]);
  }
  /// The matrix as scalar entries, for a direct factorisation.
  Eigen::SparseMatrix<double> to_sparse() const;

  /// r = b - A x.
  void residual(const Eigen::VectorXd& b, const Eigen::VectorXd& x, Eigen::VectorXd& r) const;
  /// One block Gauss-Seidel sweep over the nodes, in their order or (forward false) backwards:
  /// each node's three unknowns solved together, x_n += D_n^-1 (b - A x)_n.
  void gauss_seidel(const Eigen::VectorXd& b, Eigen::VectorXd& x, bool forward) const;

 private:
  Eigen::Vector3d row_times(int node, const double* __restrict x) const;

  std::vector<int> row_begin_{0};  // blocks of node n: [row_begin_[n], row_begin_[n + 1])
  std::vector<int> column_;        // each block's column node
  std::vector<float> value_;       // each block's 9 values, column-major (as Eigen's)
  std::vector<Eigen::Matrix3d> diagonal_inverse_;
  std::vector<int> value_target_;  // assign(): where each of a's values goes in value_
  std::vector<int> scratch_;
};

}  // namespace cubespring
