// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "conjugate_gradient.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "thread_shares.h"

namespace cubespring {
namespace {

// Rows per block of the dot products' partial sums: fixed, so the sums do not depend on the
// thread count; large enough that a block's sum costs far more than adding it to the total.
constexpr int kRowsPerBlock = 4096;

// The sum of a dot product's block partials, in block order (the same bits in every thread).
double total(const std::vector<double>& partials) {
  double sum = 0.0;
  for (double partial : partials) sum += partial;
  return sum;
}

// 1 / the row's diagonal entry, 1 where it is zero (as Eigen's DiagonalPreconditioner).
double inverse_diagonal_of(const SparseMatrix& a, int row) {
  const int* inner = a.innerIndexPtr();
  const int* begin = inner + a.outerIndexPtr()[row];
  const int* end = inner + a.outerIndexPtr()[row + 1];
  const int* hit = std::lower_bound(begin, end, row);
  const double diagonal = hit != end && *hit == row ? a.valuePtr()[hit - inner] : 0.0;
  return diagonal != 0.0 ? 1.0 / diagonal : 1.0;
}

double row_times(const SparseMatrix& a, int row, const Eigen::VectorXd& v) {
  const int* inner = a.innerIndexPtr();
  const double* values = a.valuePtr();
  double sum = 0.0;
  for (int e = a.outerIndexPtr()[row]; e < a.outerIndexPtr()[row + 1]; ++e) sum += values[e] * v[inner[e]];
  return sum;
}

}  // namespace

ConjugateGradientResult conjugate_gradient(const SparseMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                           double tolerance, int max_iterations, int threads) {
  const int n = static_cast<int>(a.rows());
  const int blocks = std::max(1, (n + kRowsPerBlock - 1) / kRowsPerBlock);
  Eigen::VectorXd inverse_diagonal(n), r(n), z(n), p(n), ap(n);
  // each phase its own partials: a thread may write the next phase's while another still reads
  std::vector<double> b_b(blocks), r_r(blocks), r_z(blocks), p_ap(blocks);
  std::vector<double> unused(blocks);  // the second sums of a single dot product: written, never read
  ConjugateGradientResult result;

  run_shares(std::min(threads, blocks), [&](int share, int shares, const auto& barrier) {
    const int first_row = std::min(n, blocks * share / shares * kRowsPerBlock);
    const int end_row = std::min(n, blocks * (share + 1) / shares * kRowsPerBlock);
    // for this thread's rows, block by block: each block's sums of the two terms term(row)
    // returns (a pair) into its place in partials_1 and partials_2
    const auto for_my_blocks = [&](std::vector<double>& partials_1, std::vector<double>& partials_2,
                                   const auto& term) {
      for (int row_block = first_row; row_block < end_row; row_block += kRowsPerBlock) {
        double sum_1 = 0.0, sum_2 = 0.0;
        for (int row = row_block; row < std::min(end_row, row_block + kRowsPerBlock); ++row) {
          const auto [term_1, term_2] = term(row);
          sum_1 += term_1;
          sum_2 += term_2;
        }
        const auto block = static_cast<std::size_t>(row_block / kRowsPerBlock);
        partials_1[block] = sum_1;
        partials_2[block] = sum_2;
      }
    };

    // r = b - A x, z = D^-1 r, p = z
    for_my_blocks(b_b, r_r, [&](int row) {
      inverse_diagonal[row] = inverse_diagonal_of(a, row);
      r[row] = b[row] - row_times(a, row, x);
      z[row] = inverse_diagonal[row] * r[row];
      p[row] = z[row];
      return std::pair{b[row] * b[row], r[row] * r[row]};
    });
    for_my_blocks(r_z, unused, [&](int row) { return std::pair{r[row] * z[row], 0.0}; });
    barrier();
    const double b_norm2 = total(b_b);
    if (b_norm2 == 0.0) {  // x = 0 solves it
      for (int row = first_row; row < end_row; ++row) x[row] = 0.0;
      if (share == 0) result = {0, 0.0, true};
      return;
    }
    const double threshold = std::max(tolerance * tolerance * b_norm2, std::numeric_limits<double>::min());
    double r_norm2 = total(r_r);
    double rz_new = total(r_z);
    int products = 0;
    while (r_norm2 >= threshold && std::isfinite(r_norm2) && products < max_iterations) {
      ++products;
      for_my_blocks(p_ap, unused, [&](int row) {
        ap[row] = row_times(a, row, p);
        return std::pair{p[row] * ap[row], 0.0};
      });
      barrier();
      const double alpha = rz_new / total(p_ap);
      for_my_blocks(r_r, r_z, [&](int row) {
        x[row] += alpha * p[row];
        r[row] -= alpha * ap[row];
        z[row] = inverse_diagonal[row] * r[row];
        return std::pair{r[row] * r[row], r[row] * z[row]};
      });
      barrier();
      r_norm2 = total(r_r);
      const double rz_old = rz_new;
      rz_new = total(r_z);
      const double beta = rz_new / rz_old;
      for (int row = first_row; row < end_row; ++row) p[row] = z[row] + beta * p[row];
      barrier();  // every p before the next product reads it
    }
    if (share == 0) {
      result.iterations = products;
      result.relative_residual = std::sqrt(r_norm2 / b_norm2);
      result.converged = result.relative_residual <= tolerance;
    }
  });
  return result;
}

}  // namespace cubespring
