// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The static solver's LDL^T in nested-dissection order: a permutation of the nodes, solves that
// match a dense solve, pivots whose signs are the matrix's inertia, and pivot directions with
// the curvature their pivot says.
#include <algorithm>
#include <numeric>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "cubespring/lattice.h"
#include "cubespring/static_solver.h"
#include "cubespring/stiffness.h"
#include "solve/grid_ldlt.h"

namespace cubespring {
namespace {

Model l_shaped_body() {  // not a box: the dissection takes each part's own bounds
  Material material;
  material.young_modulus = 1e4;
  material.poisson_ratio = 0.45;
  LatticeDesc desc = box_lattice({5, 4, 3}, Eigen::Vector3d::Constant(0.01), material);
  desc.cells.erase(std::remove_if(desc.cells.begin(), desc.cells.end(),
                                  [](const Eigen::Vector3i& c) { return c.x() >= 3 && c.y() >= 2; }),
                   desc.cells.end());
  desc.model = CellModel::kExactBending;
  desc.law = CellLaw::kNeoHookean;
  return build_model(desc).value();
}

TEST(GridLdlt, OrdersEveryNodeOnce) {
  const Model model = l_shaped_body();
  std::vector<int> order = nested_dissection_order(model);
  ASSERT_EQ(static_cast<int>(order.size()), model.num_nodes());
  std::sort(order.begin(), order.end());
  std::vector<int> all(model.num_nodes());
  std::iota(all.begin(), all.end(), 0);
  EXPECT_EQ(order, all);
}

TEST(GridLdlt, SolvesAndCountsNegativeEigenvaluesAsADenseSolverDoes) {
  const Model model = l_shaped_body();
  Eigen::Matrix3Xd x = model.rest_positions;
  x.row(2) *= 0.7;  // squeezed by 30%: a stiffness at finite strain
  StiffnessAssembler assembler(model);
  SparseMatrix assembled;
  assembler.assemble(model, x, StiffnessKind::kExact, 1.0, 0.0, assembled);
  const Eigen::SparseMatrix<double> k = assembled;
  const Eigen::MatrixXd dense(k);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(dense);
  // a shift between two eigenvalues, well away from both: a known number of them below it
  const Eigen::VectorXd values = eigen.eigenvalues();
  const int below = 40;
  const double shift = -0.5 * (values[below - 1] + values[below]);
  GridLDLT ldlt(model);
  ASSERT_TRUE(ldlt.factorise(k, shift));
  const Eigen::VectorXd pivots = ldlt.pivots();
  EXPECT_EQ((pivots.array() < 0.0).count(), below);

  const Eigen::MatrixXd shifted = dense + shift * Eigen::MatrixXd::Identity(dense.rows(), dense.cols());
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(dense.rows(), -1.0, 2.0);
  const Eigen::VectorXd solved = ldlt.solve(b);
  EXPECT_LT((shifted * solved - b).norm(), 1e-8 * b.norm());

  Eigen::Index most_negative = 0;
  pivots.minCoeff(&most_negative);
  const Eigen::VectorXd v = ldlt.pivot_direction(most_negative);
  EXPECT_NEAR(v.dot(shifted * v), pivots[most_negative], 1e-8 * std::abs(pivots[most_negative]));
}

// The estimate that measure checks before it builds a block counts the fronts' kept bytes exactly
// as the factorisation keeps them (it mirrors the dissection on boxes, without the matrix), and
// its peak and operations grow as they must with the block's cross-section.
TEST(GridLdlt, TheBlockEstimateCountsTheFactorsBytes) {
  Material material;
  for (const Eigen::Vector3i& cells : {Eigen::Vector3i(1, 1, 1), Eigen::Vector3i(6, 3, 2), Eigen::Vector3i(5, 5, 5),
                                       Eigen::Vector3i(12, 4, 3), Eigen::Vector3i(2, 9, 7)}) {
    const Model model = build_model(box_lattice(cells, Eigen::Vector3d::Constant(0.01), material)).value();
    StiffnessAssembler assembler(model);
    SparseMatrix assembled;
    assembler.assemble(model, model.rest_positions, StiffnessKind::kExact, 1.0, 0.0, assembled);
    GridLDLT ldlt(model);
    ASSERT_TRUE(ldlt.factorise(assembled, 1.0));  // shifted: the free block's rigid modes
    const FactorisationCost cost = estimate_block_factorisation(cells);
    EXPECT_EQ(cost.factor_bytes, ldlt.factor_bytes()) << cells.transpose();
    EXPECT_GT(cost.peak_bytes, cost.factor_bytes);
  }
  // a block 8 times larger across its cross-section: about 8^2 the bytes, 8^3 the operations
  const FactorisationCost small = estimate_block_factorisation({10, 10, 10});
  const FactorisationCost large = estimate_block_factorisation({80, 80, 80});
  EXPECT_GT(large.peak_bytes / small.peak_bytes, 0.5 * 512);  // 8^3 blocks of 8^2 each, at most
  EXPECT_GT(large.operations / small.operations, 0.5 * 8 * 8 * 8 * 8 * 8 * 8);
}

}  // namespace
}  // namespace cubespring
