// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "solve/node_block_matrix.h"

#include <algorithm>
#include <utility>

#include <Eigen/Cholesky>

namespace cubespring {

bool NodeBlockMatrix::assign(const SparseMatrix& a) {
  const int nodes = static_cast<int>(a.rows() / 3);
  const int* outer = a.outerIndexPtr();
  const int* inner = a.innerIndexPtr();
  row_begin_.assign(1, 0);
  row_begin_.reserve(static_cast<std::size_t>(nodes) + 1);
  column_.clear();
  value_target_.resize(static_cast<std::size_t>(a.nonZeros()));
  for (int n = 0; n < nodes; ++n) {
    // the node's block columns: the union of its three rows' (each sorted)
    scratch_.clear();
    for (int e = outer[3 * n]; e < outer[3 * n + 3]; ++e) scratch_.push_back(inner[e] / 3);
    std::sort(scratch_.begin(), scratch_.end());
    scratch_.erase(std::unique(scratch_.begin(), scratch_.end()), scratch_.end());
    const auto first = static_cast<std::ptrdiff_t>(column_.size());
    column_.insert(column_.end(), scratch_.begin(), scratch_.end());
    for (int axis = 0; axis < 3; ++axis) {
      for (int e = outer[3 * n + axis]; e < outer[3 * n + axis + 1]; ++e) {
        const auto at = std::lower_bound(column_.begin() + first, column_.end(), inner[e] / 3);
        // Eigen's 3 x 3 blocks are column-major
        value_target_[static_cast<std::size_t>(e)] =
            9 * static_cast<int>(at - column_.begin()) + axis + 3 * (inner[e] % 3);
      }
    }
    row_begin_.push_back(static_cast<int>(column_.size()));
  }
  value_.assign(9 * column_.size(), 0.0F);
  return update(a);
}

bool NodeBlockMatrix::update(const SparseMatrix& a) {
  if (static_cast<std::size_t>(a.nonZeros()) != value_target_.size() || a.rows() != 3 * nodes()) return assign(a);
  const double* values = a.valuePtr();
  for (std::size_t e = 0; e < value_target_.size(); ++e)
    value_[static_cast<std::size_t>(value_target_[e])] = static_cast<float>(values[e]);
  return invert_diagonal();
}

void NodeBlockMatrix::start(std::vector<int> row_begin, std::vector<int> columns) {
  row_begin_ = std::move(row_begin);
  column_ = std::move(columns);
  value_.assign(9 * column_.size(), 0.0F);
  value_target_.clear();
}

bool NodeBlockMatrix::invert_diagonal() {
  const int count = nodes();
  diagonal_inverse_.resize(static_cast<std::size_t>(count));
  for (int n = 0; n < count; ++n) {
    const auto begin = column_.begin() + row_begin(n), end = column_.begin() + row_begin(n + 1);
    const auto at = std::lower_bound(begin, end, n);
    if (at == end || *at != n) return false;
    const int k = static_cast<int>(at - column_.begin());
    const Eigen::LLT<Eigen::Matrix3d> factor(block(k).cast<double>());
    if (factor.info() != Eigen::Success) return false;
    diagonal_inverse_[static_cast<std::size_t>(n)] = factor.solve(Eigen::Matrix3d::Identity());
  }
  return true;
}

Eigen::SparseMatrix<double> NodeBlockMatrix::to_sparse() const {
  std::vector<Eigen::Triplet<double, int>> entries;
  entries.reserve(value_.size());
  for (int n = 0; n < nodes(); ++n) {
    for (int k = row_begin(n); k < row_begin(n + 1); ++k) {
      for (int c = 0; c < 3; ++c) {
        for (int r = 0; r < 3; ++r) entries.emplace_back(3 * n + r, 3 * column(k) + c, double{block(k)(r, c)});
      }
    }
  }
  Eigen::SparseMatrix<double> a(3 * nodes(), 3 * nodes());
  a.setFromTriplets(entries.begin(), entries.end());
  return a;
}

Eigen::Vector3d NodeBlockMatrix::row_times(int node, const double* __restrict x) const {
  const float* __restrict values = value_.data();
  const int* __restrict columns = column_.data();
  double s0 = 0.0, s1 = 0.0, s2 = 0.0;  // local sums: nothing the compiler must store each block
  for (int k = row_begin(node), end = row_begin(node + 1); k < end; ++k) {
    const float* b = values + 9 * k;
    const double* v = x + 3 * columns[k];
    s0 += b[0] * v[0] + b[3] * v[1] + b[6] * v[2];
    s1 += b[1] * v[0] + b[4] * v[1] + b[7] * v[2];
    s2 += b[2] * v[0] + b[5] * v[1] + b[8] * v[2];
  }
  return {s0, s1, s2};
}

void NodeBlockMatrix::residual(const Eigen::VectorXd& b, const Eigen::VectorXd& x, Eigen::VectorXd& r) const {
  for (int n = 0; n < nodes(); ++n) r.segment<3>(3 * n) = b.segment<3>(3 * n) - row_times(n, x.data());
}

void NodeBlockMatrix::gauss_seidel(const Eigen::VectorXd& b, Eigen::VectorXd& x, bool forward) const {
  const int count = nodes();
  for (int k = 0; k < count; ++k) {
    const int n = forward ? k : count - 1 - k;
    const Eigen::Vector3d step =
        diagonal_inverse_[static_cast<std::size_t>(n)] * (b.segment<3>(3 * n) - row_times(n, x.data()));
    x.segment<3>(3 * n) += step;
  }
}

}  // namespace cubespring
