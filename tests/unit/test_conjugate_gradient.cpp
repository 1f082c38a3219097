// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The implicit step's conjugate gradients (src/solve/conjugate_gradient.h) against Eigen's solver and a
// residual computed afresh, and the same bits on any thread count.
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>

#include "solve/conjugate_gradient.h"

namespace cubespring {
namespace {

// A symmetric positive definite system of n rows: a 3D-grid Laplacian (7 points) plus a varying
// diagonal, rows ordered as a lattice's nodes are; its Jacobi preconditioner is not the identity.
SparseMatrix grid_system(int side_x, int side_y, int side_z) {
  const int n = side_x * side_y * side_z;
  std::vector<Eigen::Triplet<double, int>> entries;
  const auto index = [&](int x, int y, int z) { return x + side_x * (y + side_y * z); };
  for (int z = 0; z < side_z; ++z) {
    for (int y = 0; y < side_y; ++y) {
      for (int x = 0; x < side_x; ++x) {
        const int row = index(x, y, z);
        entries.emplace_back(row, row, 6.0 + 0.5 * (row % 7));
        const int neighbours[3][3] = {{x + 1, y, z}, {x, y + 1, z}, {x, y, z + 1}};
        for (const auto& q : neighbours) {
          if (q[0] >= side_x || q[1] >= side_y || q[2] >= side_z) continue;
          entries.emplace_back(row, index(q[0], q[1], q[2]), -1.0);
          entries.emplace_back(index(q[0], q[1], q[2]), row, -1.0);
        }
      }
    }
  }
  SparseMatrix a(n, n);
  a.setFromTriplets(entries.begin(), entries.end());
  a.makeCompressed();
  return a;
}

Eigen::VectorXd right_hand_side(int n) {
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) b[i] = std::sin(0.01 * i) + 0.1;
  return b;
}

// 10000 rows: 3 blocks of the sums, the last one short
TEST(ConjugateGradient, SolvesAsEigensSolverDoesToTheTolerance) {
  const SparseMatrix a = grid_system(25, 20, 20);
  const Eigen::VectorXd b = right_hand_side(static_cast<int>(a.rows()));
  Eigen::VectorXd x = Eigen::VectorXd::Zero(a.rows());
  const ConjugateGradientResult result = conjugate_gradient(a, b, x, 1e-10, 1000, 2);
  ASSERT_TRUE(result.converged);
  EXPECT_GT(result.iterations, 1);
  EXPECT_LE(result.relative_residual, 1e-10);
  EXPECT_LT((b - a * x).norm() / b.norm(), 1e-9);  // afresh, not the solver's updated residual

  Eigen::ConjugateGradient<SparseMatrix, Eigen::Lower | Eigen::Upper> eigen;
  eigen.setTolerance(1e-10);
  eigen.compute(a);
  const Eigen::VectorXd reference = eigen.solve(b);
  ASSERT_EQ(eigen.info(), Eigen::Success);
  EXPECT_LT((x - reference).norm(), 1e-8 * reference.norm());
  // Eigen counts the products but the last; the same algorithm, rounded otherwise
  EXPECT_NEAR(result.iterations, static_cast<int>(eigen.iterations()) + 1, 2);
}

TEST(ConjugateGradient, GivesTheSameBitsOnAnyThreadCount) {
  const SparseMatrix a = grid_system(25, 20, 20);
  const Eigen::VectorXd b = right_hand_side(static_cast<int>(a.rows()));
  std::vector<Eigen::VectorXd> solutions;
  std::vector<int> iterations;
  for (const int threads : {1, 2, 3, 8}) {  // 8: more threads than blocks
    Eigen::VectorXd x = Eigen::VectorXd::Constant(a.rows(), 0.5);
    iterations.push_back(conjugate_gradient(a, b, x, 1e-8, 1000, threads).iterations);
    solutions.push_back(x);
  }
  for (std::size_t i = 1; i < solutions.size(); ++i) {
    EXPECT_EQ(iterations[i], iterations[0]);
    EXPECT_TRUE(solutions[i] == solutions[0]) << i;
  }
}

TEST(ConjugateGradient, AZeroRightHandSideGivesZero) {
  const SparseMatrix a = grid_system(25, 20, 20);
  Eigen::VectorXd x = Eigen::VectorXd::Ones(a.rows());
  const ConjugateGradientResult result = conjugate_gradient(a, Eigen::VectorXd::Zero(a.rows()), x, 1e-6, 100, 2);
  EXPECT_TRUE(result.converged);
  EXPECT_EQ(result.iterations, 0);
  EXPECT_TRUE(x.isZero(0.0));
}

TEST(ConjugateGradient, StopsAtTheIterationCapUnconverged) {
  const SparseMatrix a = grid_system(25, 20, 20);
  const Eigen::VectorXd b = right_hand_side(static_cast<int>(a.rows()));
  Eigen::VectorXd x = Eigen::VectorXd::Zero(a.rows());
  const ConjugateGradientResult result = conjugate_gradient(a, b, x, 1e-14, 3, 2);
  EXPECT_FALSE(result.converged);
  EXPECT_EQ(result.iterations, 3);
  EXPECT_GT(result.relative_residual, 1e-14);
  EXPECT_NEAR(result.relative_residual, (b - a * x).norm() / b.norm(), 1e-6);
}

// A NaN in the matrix makes the first residual NaN: no product. A zero matrix makes the first
// step infinite and the residual NaN after it: one product, not 1000 turns of NaN.
TEST(ConjugateGradient, ANonFiniteResidualStopsItUnconverged) {
  const SparseMatrix system = grid_system(25, 20, 20);
  const Eigen::VectorXd b = right_hand_side(static_cast<int>(system.rows()));
  SparseMatrix with_nan = system;
  with_nan.coeffRef(5000, 5000) = std::nan("");
  SparseMatrix zero = system;
  std::fill(zero.valuePtr(), zero.valuePtr() + zero.nonZeros(), 0.0);
  for (const auto& [a, products] : {std::pair{&with_nan, 0}, std::pair{&zero, 1}}) {
    Eigen::VectorXd x = Eigen::VectorXd::Zero(a->rows());
    const ConjugateGradientResult result = conjugate_gradient(*a, b, x, 1e-8, 1000, 2);
    EXPECT_FALSE(result.converged) << products;
    EXPECT_EQ(result.iterations, products);
  }
}

}  // namespace
}  // namespace cubespring
