// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The implicit step's multigrid preconditioner (src/solve/grid_multigrid.h): a symmetric positive
// definite cycle, as conjugate gradients need, and implicit steps that reach the same state as with
// Jacobi's preconditioner in far fewer iterations, with the same bits on any thread count.
#include <algorithm>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "cubespring/constraints.h"
#include "cubespring/integrator.h"
#include "solve/grid_multigrid.h"
#include "test_support.h"

namespace cubespring {
namespace {

// A beam of 1 cm cells (24x6x6 unless said), E = 1 MPa, clamped at x = 0, under gravity.
struct ClampedBeam {
  explicit ClampedBeam(double poisson_ratio, const Eigen::Vector3i& cells = {24, 6, 6}) {
    Material material;
    material.young_modulus = 1e6;
    material.poisson_ratio = poisson_ratio;
    material.density = 1000.0;
    model = test::box_model(cells, material);
    clamp = Constraints(model);
    EXPECT_TRUE(clamp.fix_box(model, {-1, -1, -1}, {1e-9, 1, 1}).ok());
    loads.gravity = {0.0, 0.0, -9.81};
  }
  Model model;
  Constraints clamp;
  Loads loads;
};

// The implicit step's matrix of the beam bent by a few steps, with the clamped rows eliminated as
// the step does (identity rows, zero columns).
SparseMatrix clamped_system(const ClampedBeam& beam, const Eigen::Matrix3Xd& positions, double dt,
                            std::vector<std::uint8_t>& fixed) {
  SparseMatrix system;
  StiffnessAssembler(beam.model)
      .assemble(beam.model, positions, StiffnessKind::kPositiveSemiDefinite, dt * dt, dt, system);
  fixed.assign(static_cast<std::size_t>(system.rows()), 0);
  for (int n = 0; n < beam.model.num_nodes(); ++n) {
    for (int a = 0; a < 3; ++a) {
      if (beam.clamp.is_driven(n)) fixed[static_cast<std::size_t>(3 * n + a)] = 1;
      system.coeffRef(3 * n + a, 3 * n + a) += beam.model.mass[n];
    }
  }
  for (int row = 0; row < system.rows(); ++row) {
    for (SparseMatrix::InnerIterator it(system, row); it; ++it) {
      if (fixed[static_cast<std::size_t>(row)] || fixed[static_cast<std::size_t>(it.col())]) {
        it.valueRef() = row == it.col() ? 1.0 : 0.0;
      }
    }
  }
  return system;
}

TEST(GridMultigrid, ItsCycleIsSymmetricAndPositiveDefinite) {
  const ClampedBeam beam(0.45);
  std::vector<std::uint8_t> fixed;
  const SparseMatrix system = clamped_system(beam, test::perturbed(beam.model, 1e-3), 4e-3, fixed);
  GridMultigrid multigrid(beam.model);
  ASSERT_GE(multigrid.num_levels(), 2);  // 1225 nodes: a cycle, not only the direct solve
  ASSERT_TRUE(multigrid.setup(system, fixed));
  const Eigen::Index n = system.rows();
  for (unsigned seed = 1; seed <= 3; ++seed) {
    std::srand(seed);
    const Eigen::VectorXd u = Eigen::VectorXd::Random(n), v = Eigen::VectorXd::Random(n);
    Eigen::VectorXd bu(n), bv(n);
    multigrid.apply(u, bu);
    multigrid.apply(v, bv);
    EXPECT_NEAR(v.dot(bu), u.dot(bv), 1e-10 * bu.norm() * v.norm()) << seed;
    EXPECT_GT(u.dot(bu), 0.0) << seed;
  }
  // near the inverse: one cycle on A x removes most of x (Jacobi's diagonal would keep most)
  const Eigen::VectorXd x = Eigen::VectorXd::Random(n);
  Eigen::VectorXd cycled(n);
  multigrid.apply(system * x, cycled);
  EXPECT_LT((cycled - x).norm(), 0.5 * x.norm());
}

// Implicit steps of 4 ms at nu = 0.45: both preconditioners to 1e-8 reach the same positions; the
// multigrid in a quarter of the iterations or fewer.
TEST(GridMultigrid, ImplicitStepsReachJacobisStateInFewerIterations) {
  const ClampedBeam beam(0.45);
  StepSettings settings;
  settings.integrator = Integrator::kImplicitEuler;
  settings.time_step = 4e-3;
  settings.solver_tolerance = 1e-8;
  State jacobi = rest_state(beam.model), multigrid = jacobi;
  Stepper jacobi_stepper(beam.model), multigrid_stepper(beam.model);
  int jacobi_iterations = 0, multigrid_iterations = 0;
  for (int step = 0; step < 5; ++step) {
    settings.preconditioner = SolverPreconditioner::kJacobi;
    const StepReport a = jacobi_stepper.step(beam.model, beam.clamp, beam.loads, settings, jacobi);
    settings.preconditioner = SolverPreconditioner::kMultigrid;
    const StepReport b = multigrid_stepper.step(beam.model, beam.clamp, beam.loads, settings, multigrid);
    ASSERT_TRUE(a.ok() && b.ok()) << a.message << b.message;
    jacobi_iterations += a.solver_iterations;
    multigrid_iterations += b.solver_iterations;
  }
  const double sag = (jacobi.positions - beam.model.rest_positions).cwiseAbs().maxCoeff();
  EXPECT_GT(sag, 1e-4);
  EXPECT_LT((multigrid.positions - jacobi.positions).cwiseAbs().maxCoeff(), 1e-6 * sag);
  EXPECT_LE(4 * multigrid_iterations, jacobi_iterations);
}

// The default (automatic) keeps Jacobi where its solves are short, with Jacobi's very bits, and
// takes the multigrid after two long ones.
TEST(GridMultigrid, TheAutomaticChoiceTakesItWhereJacobisSolvesAreLong) {
  StepSettings settings;
  settings.integrator = Integrator::kImplicitEuler;
  ASSERT_EQ(settings.preconditioner, SolverPreconditioner::kAutomatic);
  for (const bool stiff : {false, true}) {
    const ClampedBeam beam(stiff ? 0.45 : 0.3);
    settings.time_step = stiff ? 4e-3 : 5e-4;
    State automatic = rest_state(beam.model), jacobi = automatic;
    Stepper automatic_stepper(beam.model), jacobi_stepper(beam.model);
    std::vector<int> iterations, jacobi_iterations;
    for (int step = 0; step < 4; ++step) {
      settings.preconditioner = SolverPreconditioner::kAutomatic;
      iterations.push_back(
          automatic_stepper.step(beam.model, beam.clamp, beam.loads, settings, automatic).solver_iterations);
      settings.preconditioner = SolverPreconditioner::kJacobi;
      jacobi_iterations.push_back(
          jacobi_stepper.step(beam.model, beam.clamp, beam.loads, settings, jacobi).solver_iterations);
    }
    EXPECT_EQ(iterations[0], jacobi_iterations[0]) << stiff;  // the first two solves are Jacobi's
    EXPECT_EQ(iterations[1], jacobi_iterations[1]) << stiff;
    if (stiff) {
      ASSERT_GT(jacobi_iterations[1], kJacobiIterationsBeforeMultigrid);
      EXPECT_LE(4 * iterations[3], jacobi_iterations[3]);
    } else {
      ASSERT_LE(*std::max_element(jacobi_iterations.begin(), jacobi_iterations.end()),
                kJacobiIterationsBeforeMultigrid);
      EXPECT_EQ(iterations, jacobi_iterations);
      EXPECT_TRUE(automatic.positions == jacobi.positions);
    }
  }
}

// A Jacobi solve that hits the iteration cap is solved again with the multigrid in the same step,
// whose report counts both solves' products.
TEST(GridMultigrid, TheAutomaticChoiceSolvesAgainWhatJacobiCouldNot) {
  const ClampedBeam beam(0.45);
  StepSettings settings;
  settings.integrator = Integrator::kImplicitEuler;
  settings.time_step = 4e-3;
  settings.solver_max_iterations = 40;
  State state = rest_state(beam.model);
  Stepper stepper(beam.model);
  settings.preconditioner = SolverPreconditioner::kJacobi;
  State jacobi = state;
  EXPECT_EQ(Stepper(beam.model).step(beam.model, beam.clamp, beam.loads, settings, jacobi).status,
            StepStatus::kSolverFailed);
  settings.preconditioner = SolverPreconditioner::kAutomatic;
  const StepReport report = stepper.step(beam.model, beam.clamp, beam.loads, settings, state);
  ASSERT_TRUE(report.ok()) << report.message;
  EXPECT_GT(report.solver_iterations, 40);
  EXPECT_LE(report.solver_iterations, 80);
  EXPECT_LE(report.solver_residual, settings.solver_tolerance);
}

// 8019 rows: two blocks of conjugate gradients' sums, so 2 threads share them
TEST(GridMultigrid, ImplicitStepsGiveTheSameBitsOnAnyThreadCount) {
  const ClampedBeam beam(0.3, {32, 8, 8});
  StepSettings settings;
  settings.integrator = Integrator::kImplicitEuler;
  settings.time_step = 2e-3;
  settings.preconditioner = SolverPreconditioner::kMultigrid;
  std::vector<State> ends;
  settings.adapt_threads = false;  // two threads on every step, for the comparison
  for (const int threads : {1, 2}) {
    settings.threads = threads;
    State state = rest_state(beam.model);
    Stepper stepper(beam.model);
    for (int step = 0; step < 3; ++step)
      ASSERT_TRUE(stepper.step(beam.model, beam.clamp, beam.loads, settings, state).ok());
    ends.push_back(state);
  }
  EXPECT_TRUE(ends[0].positions == ends[1].positions);
  EXPECT_TRUE(ends[0].velocities == ends[1].velocities);
}

}  // namespace
}  // namespace cubespring
