// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "solve/conjugate_gradient.h"

#include <algorithm>
#include <cmath>
#include <limits>
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

// u . v over `count` entries in kLanes chains (entry i in chain i mod kLanes), added in a fixed
// order at the end: the same bits every call; a single chain waits on every add (4 cycles an
// entry), which had made the 1-thread solve slower than Eigen's, whose dot products run in lanes
double dot(const double* __restrict u, const double* __restrict v, int count) {
  constexpr int kLanes = 8;
  double lanes[kLanes] = {};
  int i = 0;
  for (; i + kLanes <= count; i += kLanes) {
    for (int lane = 0; lane < kLanes; ++lane) lanes[lane] += u[i + lane] * v[i + lane];
  }
  for (int lane = 0; i < count; ++i, ++lane) lanes[lane] += u[i] * v[i];
  return ((lanes[0] + lanes[1]) + (lanes[2] + lanes[3])) + ((lanes[4] + lanes[5]) + (lanes[6] + lanes[7]));
}

double row_times(const SparseMatrix& a, int row, const Eigen::VectorXd& v) {
  const int* __restrict inner = a.innerIndexPtr();
  const double* __restrict values = a.valuePtr();
  const double* __restrict x = v.data();
  const int begin = a.outerIndexPtr()[row], end = a.outerIndexPtr()[row + 1];
  double sum = 0.0;
  for (int e = begin; e < end; ++e) sum += values[e] * x[inner[e]];
  return sum;
}

}  // namespace

ConjugateGradientResult conjugate_gradient(const SparseMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                           double tolerance, int max_iterations, int threads,
                                           Preconditioner* preconditioner) {
  const int n = static_cast<int>(a.rows());
  const int blocks = std::max(1, (n + kRowsPerBlock - 1) / kRowsPerBlock);
  Eigen::VectorXd inverse_diagonal(n), r(n), z(n), p(n), ap(n);
  // each dot product its own partials: a thread may write the next one's while another still
  // adds up this one's
  std::vector<double> b_b(blocks), r_r(blocks), r_z(blocks), p_ap(blocks);
  ConjugateGradientResult result;

  run_shares(std::min(threads, blocks), [&](int share, int shares, const auto& barrier) {
    const int first_block = blocks * share / shares, end_block = blocks * (share + 1) / shares;
    const int first_row = std::min(n, first_block * kRowsPerBlock);
    const int end_row = std::min(n, end_block * kRowsPerBlock);
    // u . v over each of this thread's blocks, into its place in `partials`
    const auto block_dots = [&](const Eigen::VectorXd& u, const Eigen::VectorXd& v, std::vector<double>& partials) {
      for (int block = first_block; block < end_block; ++block) {
        const int begin = block * kRowsPerBlock;
        partials[static_cast<std::size_t>(block)] =
            dot(u.data() + begin, v.data() + begin, std::min(n, begin + kRowsPerBlock) - begin);
      }
    };

    // z = M^-1 r: Jacobi's row by row in each thread, another preconditioner in one thread
    // between barriers (every r before it, its z before any thread reads it)
    const auto precondition = [&] {
      if (!preconditioner) {
        for (int row = first_row; row < end_row; ++row) z[row] = inverse_diagonal[row] * r[row];
        return;
      }
      barrier();
      if (share == 0) preconditioner->apply(r, z);
      barrier();
    };

    // r = b - A x, z = M^-1 r, p = z
    for (int row = first_row; row < end_row; ++row) {
      if (!preconditioner) inverse_diagonal[row] = inverse_diagonal_of(a, row);
      r[row] = b[row] - row_times(a, row, x);
    }
    precondition();
    for (int row = first_row; row < end_row; ++row) p[row] = z[row];
    block_dots(b, b, b_b);
    block_dots(r, r, r_r);
    block_dots(r, z, r_z);
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
    // every thread takes the same turns: the same sums, added in the same order
    while (r_norm2 >= threshold && std::isfinite(r_norm2) && products < max_iterations) {
      ++products;
      for (int row = first_row; row < end_row; ++row) ap[row] = row_times(a, row, p);
      block_dots(p, ap, p_ap);
      barrier();
      const double alpha = rz_new / total(p_ap);
      for (int row = first_row; row < end_row; ++row) {
        x[row] += alpha * p[row];
        r[row] -= alpha * ap[row];
      }
      precondition();
      block_dots(r, r, r_r);
      block_dots(r, z, r_z);
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
