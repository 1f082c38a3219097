// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The stiffness matrix against finite differences of the forces, and the zero-energy modes.
#include <cstring>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>

#include <gtest/gtest.h>
#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

#include "cubespring/stiffness.h"
#include "test_support.h"

namespace cubespring {
namespace {

using test::dense_stiffness;
using test::finite_difference_stiffness;
using test::zero_modes;

// The pattern has a 3x3 block for every node with itself, the two ends of each spring and every
// two corners of a cell, and nothing else: rows of sorted columns, compressed. An L of 3 cells
// (corners shared by 1 to 3 cells) against the blocks listed from the model's springs and cells.
TEST(Stiffness, PatternHoldsTheBlocksOfSpringsAndCells) {
  LatticeDesc desc;
  desc.cells = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}};
  Result<Model> built = build_model(desc);
  ASSERT_TRUE(built.ok()) << built.message();
  const Model& model = built.value();
  std::set<std::pair<int, int>> blocks;
  for (int n = 0; n < model.num_nodes(); ++n) blocks.insert({n, n});
  for (const auto& ends : model.spring_nodes) {
    blocks.insert({ends[0], ends[1]});
    blocks.insert({ends[1], ends[0]});
  }
  for (const auto& corners : model.cell_nodes) {
    for (int p : corners) {
      for (int q : corners) blocks.insert({p, q});
    }
  }
  const StiffnessAssembler assembler(model);
  const SparseMatrix& pattern = assembler.pattern();
  ASSERT_TRUE(pattern.isCompressed());
  ASSERT_EQ(pattern.rows(), 3 * model.num_nodes());
  ASSERT_EQ(pattern.nonZeros(), static_cast<Eigen::Index>(9 * blocks.size()));
  std::set<std::pair<int, int>> found;
  for (int row = 0; row < pattern.rows(); ++row) {
    int previous = -1;
    for (SparseMatrix::InnerIterator it(pattern, row); it; ++it) {
      EXPECT_GT(it.col(), previous) << "row " << row;
      EXPECT_EQ(it.value(), 0.0);
      previous = static_cast<int>(it.col());
      found.insert({row / 3, static_cast<int>(it.col()) / 3});
    }
  }
  EXPECT_EQ(found, blocks);
}

// Positions of another body, or another body, would be read past the ends of the assembler's
// arrays: each is refused with an exception naming both counts (result.h), before anything is
// read. A body that fits the matrix's int indices passes check_stiffness_size().
TEST(Stiffness, RefusesPositionsAndBodiesItWasNotBuiltFor) {
  const Model model = test::box_model({2, 2, 2}, Material{});
  const Model other = test::box_model({3, 2, 2}, Material{});
  EXPECT_TRUE(check_stiffness_size(model).ok());
  StiffnessAssembler assembler(model);
  SparseMatrix matrix;
  const auto message_of = [](const auto& call) -> std::string {
    try {
      call();
    } catch (const std::invalid_argument& refused) {
      return refused.what();
    }
    return "(no exception)";
  };
  const std::string short_positions =
      message_of([&] { assembler.assemble(model, other.rest_positions, StiffnessKind::kExact, 1.0, 0.0, matrix); });
  EXPECT_NE(short_positions.find("positions has 36 columns; the body has 27 nodes"), std::string::npos)
      << short_positions;
  const std::string other_body =
      message_of([&] { assembler.assemble(other, other.rest_positions, StiffnessKind::kExact, 1.0, 0.0, matrix); });
  EXPECT_NE(other_body.find("built for a body of 27 nodes"), std::string::npos) << other_body;
  const std::string once = message_of(
      [&] { (void)std::move(assembler).assemble_once(model, other.rest_positions, StiffnessKind::kExact, 1.0, 0.0); });
  EXPECT_NE(once.find("assemble_once: positions has 36 columns"), std::string::npos) << once;
  // and the assembler still serves its own body
  assembler.assemble(model, model.rest_positions, StiffnessKind::kExact, 1.0, 0.0, matrix);
  EXPECT_EQ(matrix.rows(), 3 * model.num_nodes());
}

// The assembler keeps its pattern and its tension arrays between calls: a matrix assembled after
// another (here after a crushed cell, whose inversion term adds to the first) is the one a new
// assembler gives, to the bit; and so is the one it assembles into its own pattern (once).
TEST(Stiffness, AssemblingAgainGivesWhatANewAssemblerGives) {
  const Model model = test::box_model({2, 1, 1}, test::notes_material(0.3));
  Eigen::Matrix3Xd crushed = test::perturbed(model, 5e-4);
  for (int n = 0; n < model.num_nodes(); ++n) {
    if (model.node_grid_index[n].z() == 1) crushed(2, n) -= 0.0095;
  }
  const Eigen::Matrix3Xd x = test::perturbed(model, 1.5e-3);
  for (const StiffnessKind kind : {StiffnessKind::kExact, StiffnessKind::kPositiveSemiDefinite}) {
    StiffnessAssembler reused(model);
    SparseMatrix first, again, fresh;
    reused.assemble(model, crushed, kind, 1.0, 0.0, first);
    reused.assemble(model, x, kind, 1.0, 0.0, again);
    StiffnessAssembler(model).assemble(model, x, kind, 1.0, 0.0, fresh);
    ASSERT_EQ(again.nonZeros(), fresh.nonZeros());
    EXPECT_NE(Eigen::MatrixXd(first), Eigen::MatrixXd(fresh));  // the first call's values are gone
    EXPECT_EQ(Eigen::MatrixXd(again), Eigen::MatrixXd(fresh));
    for (int call = 0; call < 2; ++call) {  // the second builds the pattern it handed over again
      const SparseMatrix once =
          std::move(reused).assemble_once(model, x, kind, 1.0, 0.0);  // NOLINT(bugprone-use-after-move)
      ASSERT_EQ(once.nonZeros(), fresh.nonZeros());
      EXPECT_EQ(Eigen::MatrixXd(once), Eigen::MatrixXd(fresh)) << call;
    }
    SparseMatrix after;                                // the pattern handed over is built again
    reused.assemble(model, x, kind, 1.0, 0.0, after);  // NOLINT(bugprone-use-after-move)
    EXPECT_EQ(Eigen::MatrixXd(after), Eigen::MatrixXd(fresh));
  }
}

// Threads share the matrix's rows by ranges of nodes (from 1024 nodes a thread), each adding the
// terms of the springs and cells that reach its rows in the order one thread adds them: 1, 2 and
// 3 threads give the same bits, in both kinds, with stiffness damping, on a body numbered along
// x (Model::major_axis) in the exact-bending model with crushed cells (their twist and inversion
// terms across the threads' boundaries too).
TEST(Stiffness, AnyThreadCountAssemblesTheSameBits) {
  Material damped = test::notes_material(0.3);
  damped.stiffness_damping = 1e-4;
  LatticeDesc desc = box_lattice({20, 15, 15}, Eigen::Vector3d::Constant(0.01), damped);
  desc.model = CellModel::kExactBending;
  Result<Model> built = build_model(desc);
  ASSERT_TRUE(built.ok()) << built.message();
  const Model& model = built.value();
  ASSERT_EQ(model.major_axis, 0);
  ASSERT_GE(model.num_nodes(), 3 * 1024);
  Eigen::Matrix3Xd x = test::perturbed(model, 1e-3);
  // crushed cells near where 2 and 3 threads' rows meet
  for (const int crushed : {model.num_cells() / 3, model.num_cells() / 2, 2 * model.num_cells() / 3}) {
    for (int corner = 4; corner < 8; ++corner) x(2, model.cell_nodes[crushed][corner]) -= 0.015;
    ASSERT_LT(cell_signed_volume(model, x, crushed), 0.0);
  }
  for (const StiffnessKind kind : {StiffnessKind::kExact, StiffnessKind::kPositiveSemiDefinite}) {
    StiffnessAssembler assembler(model);
    SparseMatrix one, many;
    assembler.assemble(model, x, kind, 1.0, 0.01, one, 1);
    for (const int threads : {2, 3}) {
      assembler.assemble(model, x, kind, 1.0, 0.01, many, threads);
      ASSERT_EQ(many.nonZeros(), one.nonZeros());
      EXPECT_EQ(std::memcmp(one.valuePtr(), many.valuePtr(), sizeof(double) * one.nonZeros()), 0)
          << threads << " threads, kind " << static_cast<int>(kind);
    }
  }
}

TEST(Stiffness, ExactMatchesFiniteDifferences) {
  for (double nu : {0.0, 0.3, 0.49}) {
    const Model model = test::box_model({2, 1, 1}, test::notes_material(nu));
    const Eigen::Matrix3Xd x = test::perturbed(model, 1.5e-3);
    const Eigen::MatrixXd exact = dense_stiffness(model, x, StiffnessKind::kExact);
    const Eigen::MatrixXd numeric = finite_difference_stiffness(model, x);
    EXPECT_LT((exact - numeric).cwiseAbs().maxCoeff(), 1e-6 * exact.cwiseAbs().maxCoeff()) << nu;
    EXPECT_LT((exact - exact.transpose()).cwiseAbs().maxCoeff(), 1e-12 * exact.cwiseAbs().maxCoeff());
  }
}

TEST(Stiffness, ExactMatchesFiniteDifferencesInACrushedCell) {
  const Model model = test::box_model({1, 1, 1}, test::notes_material(0.3));
  Eigen::Matrix3Xd x = test::perturbed(model, 5e-4);
  for (int n = 0; n < model.num_nodes(); ++n) {
    if (model.node_grid_index[n].z() == 1) x(2, n) -= 0.0095;
  }
  const Eigen::MatrixXd exact = dense_stiffness(model, x, StiffnessKind::kExact);
  const Eigen::MatrixXd numeric = finite_difference_stiffness(model, x);
  EXPECT_LT((exact - numeric).cwiseAbs().maxCoeff(), 1e-6 * exact.cwiseAbs().maxCoeff());
}

TEST(Stiffness, ApproximationIsPositiveSemiDefinite) {
  const Model model = test::box_model({2, 2, 1}, test::notes_material(0.49));
  Eigen::Matrix3Xd x = test::perturbed(model, 3e-3);
  x.row(0) *= 0.9;  // compress: negative geometric stiffness in the exact matrix
  const Eigen::MatrixXd approx = dense_stiffness(model, x, StiffnessKind::kPositiveSemiDefinite);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(approx);
  EXPECT_GT(solver.eigenvalues().minCoeff(), -1e-9 * solver.eigenvalues().maxCoeff());
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> exact(dense_stiffness(model, x, StiffnessKind::kExact));
  EXPECT_LT(exact.eigenvalues().minCoeff(), -1e-6 * exact.eigenvalues().maxCoeff());
}

TEST(Stiffness, FreeBlocksHaveSixRigidAndThreeCheckerboardZeroModes) {
  for (const Eigen::Vector3i& cells : {Eigen::Vector3i(1, 1, 1), Eigen::Vector3i(2, 2, 2), Eigen::Vector3i(4, 2, 2)}) {
    EXPECT_EQ(zero_modes(test::box_model(cells, test::notes_material(0.3))), 9) << cells.transpose();
  }
}

TEST(Stiffness, CheckerboardModeIsInTheKernel) {
  const Model model = test::box_model({3, 3, 3}, test::notes_material(0.3));
  const Eigen::MatrixXd k = dense_stiffness(model, model.rest_positions, StiffnessKind::kExact);
  Eigen::VectorXd mode = Eigen::VectorXd::Zero(3 * model.num_nodes());
  for (int n = 0; n < model.num_nodes(); ++n) {
    const Eigen::Vector3i& i = model.node_grid_index[n];
    mode[3 * n + 0] = ((i.y() + i.z()) % 2) ? -1.0 : 1.0;  // u_x = (-1)^(j+k)
  }
  EXPECT_LT((k * mode).norm(), 1e-10 * k.norm());
}

}  // namespace
}  // namespace cubespring
