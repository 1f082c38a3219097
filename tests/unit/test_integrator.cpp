// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Time integration against analytic periods, conservation laws, stability limits and static
// equilibria.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "cubespring/constraints.h"
#include "cubespring/integrator.h"
#include "cubespring/static_solver.h"
#include "cubespring/validation/experiments.h"
#include "test_support.h"

namespace cubespring {
namespace {

// The two force engines a body may step on: the grid passes (a box fills its own box) and the
// spring lists (a grid fill no body reaches), as StepSettings::min_grid_fill chooses.
struct ForceLayout {
  const char* name;
  double min_grid_fill;
};
const ForceLayout kLayouts[] = {{"grid", kDefaultMinGridFill}, {"lists", std::numeric_limits<double>::quiet_NaN()}};

// Two masses joined by one spring along x, built by hand.
Model single_spring(double m0, double m1, double k) {
  Model model;
  model.materials = {Material{}};
  model.cell_size = Eigen::Vector3d::Constant(0.01);
  model.rest_positions = Eigen::Matrix3Xd::Zero(3, 2);
  model.rest_positions(0, 1) = 0.01;
  model.node_grid_index = {{0, 0, 0}, {1, 0, 0}};
  model.mass = Eigen::Vector2d(m0, m1);
  model.mass_damping = Eigen::Vector2d::Zero();
  model.spring_nodes = {{0, 1}};
  model.spring_rest_length = {0.01};
  model.spring_stiffness = {k};
  model.spring_damping = {0.0};
  model.spring_cell_offset = {0, 0};
  model.node_first_spring = {0, 1, 1};
  return model;
}

class SingleSpring : public ::testing::TestWithParam<Integrator> {};

TEST_P(SingleSpring, OscillatesAtTheAnalyticPeriod) {
  const double m0 = 0.002, m1 = 0.003, k = 50.0;
  const Model model = single_spring(m0, m1, k);
  const double period = 2 * M_PI * std::sqrt(m0 * m1 / (m0 + m1) / k);
  State state = rest_state(model);
  state.positions(0, 1) += 1e-4;
  StepSettings settings;
  settings.integrator = GetParam();
  settings.time_step = period / 2000;
  Stepper stepper(model);
  // time the upward zero crossings of the extension over three periods
  std::vector<double> crossings;
  double previous = 1e-4;
  while (state.time < 3.2 * period) {
    ASSERT_TRUE(stepper.step(model, Constraints(model), Loads{}, settings, state).ok());
    const double extension = state.positions(0, 1) - state.positions(0, 0) - 0.01;
    if (previous < 0 && extension >= 0) {
      crossings.push_back(state.time - settings.time_step * extension / (extension - previous));
    }
    previous = extension;
  }
  ASSERT_GE(crossings.size(), 2u);
  const double measured = (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  const double tolerance = GetParam() == Integrator::kImplicitEuler ? 1e-3 : 1e-5;
  EXPECT_NEAR(measured / period, 1.0, tolerance) << integrator_name(GetParam());
}

INSTANTIATE_TEST_SUITE_P(Integrators, SingleSpring,
                         ::testing::Values(Integrator::kSymplecticEuler, Integrator::kVelocityVerlet,
                                           Integrator::kImplicitEuler));

State wobbling_block(const Model& model) {
  State state = rest_state(model);
  state.positions = test::perturbed(model, 2e-4, 11);
  state.velocities = (test::perturbed(model, 0.05, 12) - model.rest_positions);
  return state;
}

TEST(Integrator, ConservesLinearMomentumWithoutExternalForce) {
  Material m = test::notes_material(0.3);
  m.stiffness_damping = 1e-4;  // internal damping exchanges no momentum
  const Model model = test::box_model({3, 3, 3}, m);
  for (Integrator integrator :
       {Integrator::kSymplecticEuler, Integrator::kVelocityVerlet, Integrator::kImplicitEuler}) {
    State state = wobbling_block(model);
    const Eigen::Vector3d momentum = state.velocities * model.mass;
    StepSettings settings;
    settings.integrator = integrator;
    settings.time_step = 0.5 * max_stable_time_step(model);
    settings.solver_tolerance = 1e-12;
    Stepper stepper(model);
    for (int i = 0; i < 300; ++i) ASSERT_TRUE(stepper.step(model, Constraints(model), Loads{}, settings, state).ok());
    const Eigen::Vector3d after = state.velocities * model.mass;
    EXPECT_LT((after - momentum).norm(), 1e-8 * model.total_mass() * 0.05) << integrator_name(integrator);
  }
}

TEST(Integrator, UndampedExplicitEnergyStaysBounded) {
  const Model model = test::box_model({3, 2, 2}, test::notes_material(0.3));
  for (Integrator integrator : {Integrator::kSymplecticEuler, Integrator::kVelocityVerlet}) {
    State state = wobbling_block(model);
    const auto energy = [&](const State& s) { return kinetic_energy(model, s) + elastic_energy(model, s.positions); };
    const double start = energy(state);
    StepSettings settings;
    settings.integrator = integrator;
    settings.time_step = 0.2 * max_stable_time_step(model);
    Stepper stepper(model);
    double low = start, high = start;
    for (int i = 0; i < 20000; ++i) {
      ASSERT_TRUE(stepper.step(model, Constraints(model), Loads{}, settings, state).ok());
      low = std::min(low, energy(state));
      high = std::max(high, energy(state));
    }
    EXPECT_LT(high / start, 1.1) << integrator_name(integrator);
    EXPECT_GT(low / start, 0.9) << integrator_name(integrator);
  }
}

TEST(Integrator, StableTimeStepSeparatesStableFromUnstable) {
  Material m;  // E = 1 MPa
  const Model model = test::box_model({4, 2, 2}, m);
  const double limit = max_stable_time_step(model);
  // a wave crossing one cell: h / c, the order the bound must have
  EXPECT_GT(limit, 0.1 * 0.01 / pressure_wave_speed(m));
  EXPECT_LT(limit, 2.0 * 0.01 / pressure_wave_speed(m));
  for (const auto& [factor, stable] : {std::pair{1.0, true}, std::pair{4.0, false}}) {
    State state = wobbling_block(model);
    StepSettings settings;
    settings.time_step = factor * limit;
    Stepper stepper(model);
    StepReport report;
    for (int i = 0; i < 3000 && report.ok(); ++i)
      report = stepper.step(model, Constraints(model), Loads{}, settings, state);
    EXPECT_EQ(report.ok(), stable) << factor << " x " << limit << ": " << report.message;
    EXPECT_TRUE(state.positions.allFinite());
  }
}

// A step whose result is not finite is reported and leaves the state as it was, on the grid
// passes and the spring lists, for each explicit integrator: a state that already holds a NaN
// (a caller's bug), and finite speeds that carry the nodes past the largest double in one step
// (only the positions the kick makes are then not finite).
TEST(Integrator, ANonFiniteStepIsReportedAndLeavesTheState) {
  const Model grid = test::box_model({6, 4, 3}, test::notes_material(0.3));
  ASSERT_TRUE(uses_grid_passes(grid));
  const Model* model = &grid;
  for (const auto& [layout, fill] : kLayouts) {
    for (Integrator integrator : {Integrator::kSymplecticEuler, Integrator::kVelocityVerlet}) {
      for (const bool overflow : {false, true}) {
        State state = wobbling_block(*model);
        StepSettings settings;
        settings.integrator = integrator;
        settings.time_step = 0.5 * max_stable_time_step(*model);
        if (overflow) {  // at rest (no force), 1e152 m/s for 1e158 s: x = 1e310 m, speed^2 = 1e304
          state = rest_state(*model);
          state.velocities.row(0).setConstant(1e152);
          settings.time_step = 1e158;
          settings.speed_limit = 1e200;
        } else {
          state.positions(1, 17) = std::numeric_limits<double>::quiet_NaN();
        }
        settings.min_grid_fill = fill;
        const State before = state;
        Stepper stepper(*model);
        const StepReport report = stepper.step(*model, Constraints(*model), Loads{}, settings, state);
        const std::string what =
            std::string(layout) + ", " + integrator_name(integrator) + (overflow ? ", overflow" : ", NaN");
        EXPECT_EQ(report.status, StepStatus::kUnstable) << what;
        EXPECT_NE(report.message.find("NaN or infinite"), std::string::npos) << what << ": " << report.message;
        const auto bytes = sizeof(double) * static_cast<std::size_t>(state.positions.size());
        EXPECT_EQ(std::memcmp(state.positions.data(), before.positions.data(), bytes), 0) << what;
        EXPECT_EQ(std::memcmp(state.velocities.data(), before.velocities.data(), bytes), 0) << what;
        EXPECT_EQ(state.time, before.time) << what;
      }
    }
  }
}

// A driven node sent 1e10 m in 1e-300 s would move at an infinite speed: each integrator reports
// the step as unstable and leaves the state as it was.
TEST(Integrator, ADrivenNodeWithAnInfiniteSpeedIsReported) {
  const Model grid = test::box_model({6, 4, 3}, test::notes_material(0.3));
  ASSERT_TRUE(uses_grid_passes(grid));
  const Model* model = &grid;
  for (const auto& [layout, fill] : kLayouts) {
    Constraints tool(*model);
    ASSERT_TRUE(tool.prescribe_displacement(*model, 5, {1e10, 0, 0}).ok());
    // with a crushed cell too: the grid's kick is then redone at its corners and its speed found again
    for (const bool crushed : {false, true}) {
      for (Integrator integrator :
           {Integrator::kSymplecticEuler, Integrator::kVelocityVerlet, Integrator::kImplicitEuler}) {
        const std::string what =
            std::string(layout) + ", " + integrator_name(integrator) + (crushed ? ", crushed" : "");
        State state = rest_state(*model);
        if (crushed) {  // the last cell's top face pushed through its bottom
          for (int corner = 4; corner < 8; ++corner) state.positions(2, model->cell_nodes.back()[corner]) -= 0.015;
        }
        const State before = state;
        StepSettings settings;
        settings.integrator = integrator;
        settings.min_grid_fill = fill;
        settings.time_step = 1e-300;
        Stepper stepper(*model);
        const StepReport report = stepper.step(*model, tool, Loads{}, settings, state);
        EXPECT_FALSE(report.ok()) << what;
        EXPECT_TRUE(state == before) << what;
      }
    }
  }
}

// A blow-up's message says where it shows: the fastest node, where it stood when the step began,
// and a cell crushed below half its rest volume then (far stiffer than at rest).
TEST(Integrator, AnUnstableStepNamesItsFastestNodeAndACrushedCell) {
  const Model model = test::box_model({6, 4, 3}, test::notes_material(0.3));
  for (const bool crushed : {false, true}) {
    State state = rest_state(model);
    state.velocities.col(5) = Eigen::Vector3d(1e4, 0, 0);  // far above any wave speed
    if (crushed) {                                         // the last cell's top face pushed through its bottom
      for (int corner = 4; corner < 8; ++corner) state.positions(2, model.cell_nodes.back()[corner]) -= 0.015;
    }
    StepSettings settings;
    settings.time_step = 1e-4;
    Stepper stepper(model);
    const StepReport report = stepper.step(model, Constraints(model), Loads{}, settings, state);
    ASSERT_EQ(report.status, StepStatus::kUnstable);
    std::ostringstream node;
    node << "node 5 (at (" << model.rest_positions.col(5).transpose() << ") m when the step began)";
    EXPECT_NE(report.message.find(node.str()), std::string::npos) << report.message;
    const std::string cell = "cell " + std::to_string(model.num_cells() - 1) + " is crushed to -";
    EXPECT_EQ(report.message.find(cell) != std::string::npos, crushed) << report.message;
  }
}

TEST(Integrator, ImplicitEulerIsStableWhereExplicitBlowsUp) {
  // E = 1 MPa, 1 cm cells, dt = 10 ms: far above the explicit limit (about 3e-4 s)
  Material m;
  m.mass_damping = 1.0;
  const Model model = test::box_model({16, 4, 4}, m);
  Constraints clamp(model);
  ASSERT_TRUE(clamp.fix_box(model, {-1e-9, -1, -1}, {1e-9, 1, 1}).ok());
  Loads loads;
  loads.gravity = {0, 0, -9.81};
  StepSettings settings;
  settings.time_step = 0.01;

  State explicit_state = rest_state(model);
  Stepper explicit_stepper(model);
  StepReport report;
  for (int i = 0; i < 100 && report.ok(); ++i)
    report = explicit_stepper.step(model, clamp, loads, settings, explicit_state);
  EXPECT_EQ(report.status, StepStatus::kUnstable);
  // the message names the step taken and where to find the body's limit
  EXPECT_NE(report.message.find("time step of 0.01 s"), std::string::npos) << report.message;
  EXPECT_NE(report.message.find("max_stable_time_step()"), std::string::npos) << report.message;
  EXPECT_TRUE(explicit_state.positions.allFinite());

  settings.integrator = Integrator::kImplicitEuler;
  State state = rest_state(model);
  Stepper stepper(model);
  for (int i = 0; i < 150; ++i) ASSERT_TRUE(stepper.step(model, clamp, loads, settings, state).ok()) << i;
  // it settles at the static equilibrium
  State equilibrium = rest_state(model);
  ASSERT_TRUE(solve_static(model, clamp, loads, StaticSettings{}, equilibrium).converged);
  const double tip = displacements(model, equilibrium).row(2).minCoeff();
  EXPECT_NEAR(displacements(model, state).row(2).minCoeff() / tip, 1.0, 0.02);
}

// The implicit step keeps the PSD parts of the cells' corrections it assembles with: after one
// cell's correction changes, the same stepper steps as a new one does (to the bit), and not as
// it did before the change.
TEST(Integrator, ImplicitStepFollowsAChangedCorrection) {
  Model model = test::box_model({6, 3, 3}, Material{});
  Constraints clamp(model);
  ASSERT_TRUE(clamp.fix_box(model, {-1e-9, -1, -1}, {1e-9, 1, 1}).ok());
  Loads loads;
  loads.gravity = {0, 0, -9.81};
  StepSettings settings;
  settings.integrator = Integrator::kImplicitEuler;
  settings.time_step = 0.01;
  State start = rest_state(model);
  Stepper kept(model);
  ASSERT_TRUE(kept.step(model, clamp, loads, settings, start).ok());  // assembled once
  State unchanged = start;
  ASSERT_TRUE(Stepper(model).step(model, clamp, loads, settings, unchanged).ok());
  for (int c = 0; c < model.num_cells(); c += 2) model.cell_correction[c] *= 3.0;
  model.mark_changed();
  State by_kept = start, by_new = start;
  ASSERT_TRUE(kept.step(model, clamp, loads, settings, by_kept).ok());
  ASSERT_TRUE(Stepper(model).step(model, clamp, loads, settings, by_new).ok());
  EXPECT_TRUE(by_kept.positions == by_new.positions && by_kept.velocities == by_new.velocities);
  EXPECT_GT((by_new.positions - unchanged.positions).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(Integrator, SameRunTwiceIsBitIdenticalOnOneAndTwoThreads) {
  Material m = test::notes_material(0.3);
  m.stiffness_damping = 1e-4;
  // enough springs for 2 blocks of the implicit step's force pass, rows for 2 blocks of its
  // conjugate gradients' sums (4096 rows each) and nodes for 2 threads' rows of its assembly and
  // set-up (1024 each), clamped at x = 0 (the driven rows eliminated by each thread); the explicit
  // step runs on the grid passes, on 2 threads at this size
  const Model model = test::box_model({16, 12, 10}, m);
  ASSERT_GT(model.num_nodes(), 2048);
  Constraints clamp(model);
  ASSERT_TRUE(clamp.fix_box(model, {-1, -1, -1}, {1e-9, 1, 1}).ok());
  Loads loads;
  loads.gravity = {0, 0, -9.81};
  for (Integrator integrator : {Integrator::kSymplecticEuler, Integrator::kImplicitEuler}) {
    std::vector<State> runs;
    for (int threads : {1, 1, 2, 2}) {
      State state = wobbling_block(model);
      StepSettings settings;
      settings.integrator = integrator;
      settings.threads = threads;
      settings.adapt_threads = false;  // every step on the threads named, for the comparison
      settings.time_step = integrator == Integrator::kImplicitEuler ? 1e-3 : 0.5 * max_stable_time_step(model);
      Stepper stepper(model);
      for (int i = 0; i < 30; ++i) {
        const StepReport report = stepper.step(model, clamp, loads, settings, state);
        ASSERT_TRUE(report.ok()) << report.message;
        if (integrator == Integrator::kImplicitEuler) {
          EXPECT_GT(report.solver_iterations, 0);
          EXPECT_LE(report.solver_residual, settings.solver_tolerance);
        }
      }
      runs.push_back(state);
    }
    for (const State& run : runs) EXPECT_TRUE(run == runs[0]) << integrator_name(integrator);
  }
}

// Each integrator's forces come from the passes StepSettings::min_grid_fill chooses: its
// last_forces() are bit for bit those of compute_forces() with that fill at the state it reads
// (the step's start for symplectic and implicit Euler; the implicit step's without damping),
// and the grid's and the lists' forces differ in their last bits, so the check tells them apart.
TEST(Integrator, EveryStepTakesThePassesItsSettingsChoose) {
  Material m = test::notes_material(0.3);
  m.stiffness_damping = 1e-4;
  const Model model = test::box_model({6, 4, 3}, m);
  ASSERT_TRUE(uses_grid_passes(model));
  const State start = wobbling_block(model);
  Loads loads;
  loads.gravity = {0, 0, -9.81};
  for (const Integrator integrator : {Integrator::kSymplecticEuler, Integrator::kImplicitEuler}) {
    const bool implicit = integrator == Integrator::kImplicitEuler;
    Eigen::Matrix3Xd expected[2];
    for (int i = 0; i < 2; ++i) {
      ForceWorkspace ws;
      compute_forces(model, start, loads, ForceOptions{!implicit, 1, kLayouts[i].min_grid_fill}, ws, expected[i]);
    }
    ASSERT_FALSE(expected[0] == expected[1]) << "the grid's and the lists' forces are the same bits: no test";
    for (int i = 0; i < 2; ++i) {
      StepSettings settings;
      settings.integrator = integrator;
      settings.time_step = 0.5 * max_stable_time_step(model);
      settings.min_grid_fill = kLayouts[i].min_grid_fill;
      State state = start;
      Stepper stepper(model);
      ASSERT_TRUE(stepper.step(model, Constraints(model), loads, settings, state).ok());
      EXPECT_TRUE(stepper.last_forces() == expected[i]) << integrator_name(integrator) << ", " << kLayouts[i].name;
    }
  }
}

// The explicit steps of a dense body run on its grid passes; the same steps on the spring lists
// give the same states to rounding: damped, under gravity, clamped, and with a cell crushed at
// the start (its corners' kick is redone with its recovery).
TEST(Integrator, GridAndSpringListsStepAlike) {
  Material m = test::notes_material(0.3);
  m.stiffness_damping = 1e-4;
  m.mass_damping = 5.0;
  const Model grid = test::box_model({6, 4, 3}, m);
  ASSERT_TRUE(uses_grid_passes(grid));
  const Model& lists = grid;  // stepped on the spring lists
  Constraints clamp(grid);
  ASSERT_TRUE(clamp.fix_box(grid, {-1, -1, -1}, {1e-9, 1, 1}).ok());
  Loads loads;
  loads.gravity = {0, 0, -9.81};
  for (Integrator integrator : {Integrator::kSymplecticEuler, Integrator::kVelocityVerlet}) {
    for (const bool crushed : {false, true}) {
      State start = wobbling_block(grid);
      if (crushed) {
        const int c = grid.num_cells() - 1;  // the far top corner cell
        for (int corner = 4; corner < 8; ++corner) start.positions(2, grid.cell_nodes[c][corner]) -= 0.015;
        ASSERT_LT(cell_signed_volume(grid, start.positions, c), 0.0);
      }
      StepSettings settings;
      settings.integrator = integrator;
      settings.time_step = 0.5 * max_stable_time_step(grid);
      StepSettings lists_settings = settings;
      lists_settings.min_grid_fill = std::numeric_limits<double>::quiet_NaN();
      State on_grid = start, on_lists = start;
      Stepper grid_stepper(grid), lists_stepper(lists);
      for (int i = 0; i < 20; ++i) {
        ASSERT_TRUE(grid_stepper.step(grid, clamp, loads, settings, on_grid).ok());
        ASSERT_TRUE(lists_stepper.step(lists, clamp, loads, lists_settings, on_lists).ok());
      }
      const double moved = (on_lists.positions - start.positions).cwiseAbs().maxCoeff();
      ASSERT_GT(moved, 1e-6);
      EXPECT_LT((on_grid.positions - on_lists.positions).cwiseAbs().maxCoeff(), 1e-9 * moved)
          << integrator_name(integrator) << (crushed ? ", crushed" : "");
      EXPECT_LT((on_grid.velocities - on_lists.velocities).cwiseAbs().maxCoeff(),
                1e-9 * on_lists.velocities.cwiseAbs().maxCoeff())
          << integrator_name(integrator) << (crushed ? ", crushed" : "");
    }
  }
}

// One explicit step from `start` against compute_forces() and plain kicks and drifts: symplectic
// Euler is a kick and drift with the forces at the start; velocity Verlet a half kick and drift,
// then a half kick with the forces at the new positions and the half-step velocities. The steps
// fuse each kick with its force pass (the grid's in one vectorised sweep per thread,
// grid_kick.cpp) and must give the same bits.
void expect_step_is_forces_then_kicks(Integrator integrator, const Model& model, const Constraints& clamp,
                                      const Loads& loads, const State& start, double dt, int threads,
                                      const std::string& what, double min_grid_fill = kDefaultMinGridFill) {
  StepSettings settings;
  settings.min_grid_fill = min_grid_fill;
  settings.integrator = integrator;
  settings.threads = threads;
  settings.adapt_threads = false;  // the threads named, on every step
  settings.time_step = dt;
  State stepped = start;
  Stepper stepper(model);
  ASSERT_TRUE(stepper.step(model, clamp, loads, settings, stepped).ok()) << what;

  const bool verlet = integrator == Integrator::kVelocityVerlet;
  const double kick = verlet ? 0.5 * dt : dt;
  ForceWorkspace workspace;
  Eigen::Matrix3Xd forces;
  const ForceOptions options{true, 1, min_grid_fill};
  compute_forces(model, start, loads, options, workspace, forces);
  State expected = start;
  const auto kick_and_drive = [&](const State& from, double drift) {
    for (int n = 0; n < model.num_nodes(); ++n) {
      const Eigen::Vector3d v = from.velocities.col(n) + (kick / model.mass[n]) * forces.col(n);
      expected.velocities.col(n) = v;
      expected.positions.col(n) = from.positions.col(n) + drift * v;
      if (clamp.is_driven(n)) {
        expected.positions.col(n) = clamp.target(n);
        expected.velocities.col(n) = (clamp.target(n) - start.positions.col(n)) / dt;
      }
    }
  };
  kick_and_drive(start, dt);
  if (verlet) {
    const State half_step = expected;
    compute_forces(model, half_step, loads, options, workspace, forces);
    kick_and_drive(half_step, 0.0);
  }
  EXPECT_TRUE(stepper.last_forces() == forces) << what;
  EXPECT_TRUE(stepped.velocities == expected.velocities) << what;
  EXPECT_TRUE(stepped.positions == expected.positions) << what;
}

// Cell c's top face pushed through its bottom face: its corners then get the recovery.
void crush_cell(const Model& model, int c, State& state) {
  for (int corner = 4; corner < 8; ++corner) state.positions(2, model.cell_nodes[c][corner]) -= 0.015;
}

// Grid and lists, with and without mass damping, loads and a crushed cell; a body with holes; and
// a body on 1-3 threads with driven nodes in every thread's share.
void expect_every_step_is_forces_then_kicks(Integrator integrator) {
  const auto expect_step_is_forces_then_kick = [integrator](auto&&... arguments) {
    expect_step_is_forces_then_kicks(integrator, arguments...);
  };
  for (const double mass_damping : {0.0, 5.0}) {
    Material m = test::notes_material(0.3);
    m.stiffness_damping = 1e-4;
    m.mass_damping = mass_damping;
    const Model grid = test::box_model({6, 4, 3}, m);
    ASSERT_TRUE(uses_grid_passes(grid));
    const Model* model = &grid;
    for (const auto& [layout, fill] : kLayouts) {
      Constraints clamp(*model);
      ASSERT_TRUE(clamp.fix_box(*model, {-1, -1, -1}, {1e-9, 1, 1}).ok());
      for (const bool with_loads : {false, true}) {
        for (const bool crushed : {false, true}) {
          Loads loads;
          if (with_loads) {
            loads.gravity = {0.5, 0, -9.81};
            loads.nodal_forces = 1e-3 * Eigen::Matrix3Xd::Random(3, model->num_nodes());
          }
          State start = wobbling_block(*model);
          if (crushed) crush_cell(*model, model->num_cells() - 1, start);
          expect_step_is_forces_then_kick(*model, clamp, loads, start, 0.5 * max_stable_time_step(*model), 1,
                                          std::string(layout) + ", alpha " + std::to_string(mass_damping) +
                                              (with_loads ? ", loads" : "") + (crushed ? ", crushed" : ""),
                                          fill);
        }
      }
    }
  }
  // a body with holes on the grid: its nodes' points are not one range, so the kick gathers
  // their forces through point_of_node
  LatticeDesc holes = box_lattice({6, 5, 4}, Eigen::Vector3d::Constant(0.01), test::notes_material(0.3));
  std::vector<Eigen::Vector3i> kept;
  for (const Eigen::Vector3i& cell : holes.cells) {
    if (cell.x() > 0 && (cell.x() + 2 * cell.y() + 3 * cell.z()) % 5 == 0) continue;  // a fifth gone
    kept.push_back(cell);
  }
  holes.cells = kept;
  Result<Model> holed = build_model(holes);
  ASSERT_TRUE(holed.ok()) << holed.message();
  ASSERT_TRUE(uses_grid_passes(holed.value()));
  ASSERT_LT(holed.value().num_nodes(), 7 * 6 * 5);
  expect_step_is_forces_then_kick(holed.value(), Constraints(holed.value()), Loads{}, wobbling_block(holed.value()),
                                  0.5 * max_stable_time_step(holed.value()), 1, "holes");
  // a body whose grid passes take 1-3 threads (13125 points, numbered along y: 24 layers of
  // cells), each kicking and driving its share of the nodes (a clamped face through every layer,
  // a moved top); with a cell crushed in the first or the last thread's layers, its corners'
  // kick is redone with the recovery
  Material damped = test::notes_material(0.3);
  damped.mass_damping = 5.0;
  const Model large = test::box_model({24, 24, 20}, damped);
  ASSERT_TRUE(uses_grid_passes(large));
  Loads loads;
  loads.gravity = {0, 0, -9.81};
  loads.nodal_forces = 1e-3 * Eigen::Matrix3Xd::Random(3, large.num_nodes());
  const double dt = 0.5 * max_stable_time_step(large);
  Constraints driven(large);
  ASSERT_TRUE(driven.fix_box(large, {-1, -1, -1}, {1e-9, 1, 1}).ok());
  ASSERT_TRUE(driven.prescribe_box_displacement(large, {0.1, -1, 0.2 - 1e-9}, {1, 1, 1}, {1e-4, 0, -2e-4}).ok());
  for (const int crushed_cell : {-1, 0, large.num_cells() - 1}) {
    State start = wobbling_block(large);
    if (crushed_cell >= 0) crush_cell(large, crushed_cell, start);
    for (const int threads : {1, 2, 3}) {
      expect_step_is_forces_then_kick(
          large, driven, loads, start, dt, threads,
          std::to_string(threads) + " threads, crushed cell " + std::to_string(crushed_cell));
    }
  }
}

TEST(Integrator, SymplecticStepIsTheForcesThenAKickAndDrift) {
  expect_every_step_is_forces_then_kicks(Integrator::kSymplecticEuler);
}

TEST(Integrator, VelocityVerletStepIsTwoHalfKicksAroundTheForces) {
  expect_every_step_is_forces_then_kicks(Integrator::kVelocityVerlet);
}

// The speed check sees the crushed cells' corners after their recovery: the fastest node of the
// step (from compute_forces and a kick) is a corner of the crushed cell, and a speed limit just
// under its speed stops the step while one just over it lets it pass, on the grid (whose kick
// ran before the recovery was known) as on the lists.
TEST(Integrator, TheSpeedCheckSeesTheCrushedCellsRecovery) {
  const Model grid = test::box_model({6, 4, 3}, test::notes_material(0.3));
  ASSERT_TRUE(uses_grid_passes(grid));
  const int crushed = grid.num_cells() - 1;
  const Model* model = &grid;
  for (const auto& [layout, fill] : kLayouts) {
    const std::string what = layout;
    State start = wobbling_block(*model);
    crush_cell(*model, crushed, start);
    const double dt = 0.5 * max_stable_time_step(*model);
    ForceWorkspace workspace;
    Eigen::Matrix3Xd forces;
    compute_forces(*model, start, Loads{}, ForceOptions{true, 1, fill}, workspace, forces);
    Eigen::Index fastest = 0;
    const Eigen::VectorXd speed_sq =
        (start.velocities + dt * forces * model->mass.cwiseInverse().asDiagonal()).colwise().squaredNorm().transpose();
    const double fastest_speed = std::sqrt(speed_sq.maxCoeff(&fastest));
    const auto& corners = model->cell_nodes[crushed];
    ASSERT_NE(std::find(corners.begin(), corners.end(), static_cast<int>(fastest)), corners.end()) << what;
    for (const double margin : {1.0 - 1e-9, 1.0 + 1e-9}) {
      StepSettings settings;
      settings.time_step = dt;
      settings.min_grid_fill = fill;
      settings.speed_limit = margin * fastest_speed;
      State state = start;
      Stepper stepper(*model);
      const StepReport report = stepper.step(*model, Constraints(*model), Loads{}, settings, state);
      EXPECT_EQ(report.ok(), margin > 1.0) << what << ", limit " << margin << " x the fastest: " << report.message;
    }
  }
}

TEST(Integrator, CrushedCornerCellRecovers) {
  // a corner cell's top face pushed 1.5 cells down, through its bottom face, then released
  Material m = test::notes_material(0.3);
  m.mass_damping = 30.0;
  const Model model = test::box_model({3, 3, 3}, m);
  Constraints clamp(model);
  ASSERT_TRUE(clamp.fix_box(model, {-1, -1, -1e-9}, {1, 1, 1e-9}).ok());
  State state = rest_state(model);
  int corner_cell = -1;
  for (int c = 0; c < model.num_cells(); ++c) {
    if (model.cell_grid_index[c] == Eigen::Vector3i(2, 2, 2)) corner_cell = c;
  }
  for (int corner = 4; corner < 8; ++corner) state.positions(2, model.cell_nodes[corner_cell][corner]) -= 0.015;
  ASSERT_LT(cell_signed_volume(model, state.positions, corner_cell), 0.0);
  StepSettings settings;
  settings.integrator = Integrator::kImplicitEuler;
  settings.time_step = 1e-3;
  Stepper stepper(model);
  for (int i = 0; i < 1500; ++i) ASSERT_TRUE(stepper.step(model, clamp, Loads{}, settings, state).ok()) << i;
  EXPECT_GT(cell_signed_volume(model, state.positions, corner_cell), 0.0);
  EXPECT_LT((state.positions - model.rest_positions).cwiseAbs().maxCoeff(), 0.01 * 0.01);
}

// A time step that is not a finite number > 0 is the caller's input, not an instability
// (result.h's contract): refused as invalid input, naming the value, with the state untouched.
TEST(Integrator, RefusesABadTimeStep) {
  const Model model = test::box_model({1, 1, 1}, Material{});
  for (const double time_step : {-1.0, 0.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    for (const Integrator integrator : {Integrator::kSymplecticEuler, Integrator::kImplicitEuler}) {
      const State rest = rest_state(model);
      State state = rest;
      StepSettings settings;
      settings.integrator = integrator;
      settings.time_step = time_step;
      Stepper stepper(model);
      const StepReport report = stepper.step(model, Constraints(model), Loads{}, settings, state);
      EXPECT_EQ(report.status, StepStatus::kInvalidInput) << time_step;
      EXPECT_NE(report.message.find("time_step = "), std::string::npos) << report.message;
      EXPECT_TRUE(state == rest);
    }
  }
}

// Arrays of another body would be read and written past their ends: each is refused, naming it
// and both counts, and the state is left as it was. So are a gravity that is not finite, a speed
// limit that is not a number >= 0, and a body other than the stepper's.
TEST(Integrator, RefusesInputsThatDoNotFitTheBody) {
  const Model model = test::box_model({2, 2, 2}, Material{});
  const Model other = test::box_model({3, 2, 2}, Material{});
  struct Case {
    const char* what;
    State state;
    Loads loads;
    Constraints constraints;
    StepSettings settings;
    const Model* stepper_body;
    std::string expected;
  };
  const State rest = rest_state(model);
  State no_velocities = rest;
  no_velocities.velocities.resize(3, 0);
  Loads short_loads;
  short_loads.nodal_forces.setZero(3, 5);
  Loads nan_gravity;
  nan_gravity.gravity.z() = std::nan("");
  StepSettings nan_limit;
  nan_limit.speed_limit = std::nan("");
  const std::vector<Case> cases{
      {"velocities", no_velocities, Loads{}, Constraints(model), StepSettings{}, &model,
       "state.velocities has 0 columns; the body has 27 nodes"},
      {"state of another body", rest_state(other), Loads{}, Constraints(model), StepSettings{}, &model,
       "state.positions has 36 columns; the body has 27 nodes"},
      {"nodal forces", rest, short_loads, Constraints(model), StepSettings{}, &model,
       "loads.nodal_forces has 5 columns; the body has 27 nodes (or leave it empty)"},
      {"gravity", rest, nan_gravity, Constraints(model), StepSettings{}, &model, "loads.gravity"},
      {"constraints", rest, Loads{}, Constraints(other), StepSettings{}, &model,
       "the constraints are for a body of 36 nodes; this one has 27"},
      {"speed limit", rest, Loads{}, Constraints(model), nan_limit, &model, "speed_limit = nan"},
      {"stepper", rest, Loads{}, Constraints(model), StepSettings{}, &other,
       "the stepper was made for a body of 36 nodes"},
  };
  for (const Case& c : cases) {
    for (const Integrator integrator : {Integrator::kSymplecticEuler, Integrator::kImplicitEuler}) {
      State state = c.state;
      StepSettings settings = c.settings;
      settings.integrator = integrator;
      Stepper stepper(*c.stepper_body);
      const StepReport report = stepper.step(model, c.constraints, c.loads, settings, state);
      EXPECT_EQ(report.status, StepStatus::kInvalidInput) << c.what;
      EXPECT_NE(report.message.find(c.expected), std::string::npos) << c.what << ": " << report.message;
      EXPECT_TRUE(state == c.state) << c.what;
    }
  }
  // check_state_and_loads() gives the stepper's message as a Status, for the same cases
  for (const Case& c : cases) {
    if (c.stepper_body != &model || c.constraints.num_nodes() != model.num_nodes() ||
        c.what == std::string("speed limit")) {
      continue;  // the body, constraints and step settings are the stepper's to check
    }
    const Status status = check_state_and_loads(model, c.state, c.loads);
    EXPECT_FALSE(status.ok()) << c.what;
    EXPECT_NE(status.message().find(c.expected), std::string::npos) << c.what << ": " << status.message();
  }
  EXPECT_TRUE(check_state_and_loads(model, rest).ok());
  // the functions that return their result throw instead
  ForceWorkspace ws;
  Eigen::Matrix3Xd forces;
  EXPECT_THROW(compute_forces(model, no_velocities, Loads{}, ForceOptions{true, 1}, ws, forces), std::invalid_argument);
  EXPECT_THROW(compute_forces(model, rest, short_loads, ForceOptions{false, 1}, ws, forces), std::invalid_argument);
  EXPECT_THROW(compute_forces(model, rest, nan_gravity, ForceOptions{false, 1}, ws, forces), std::invalid_argument);
  EXPECT_NO_THROW(compute_forces(model, no_velocities, Loads{}, ForceOptions{false, 1}, ws, forces));
  EXPECT_THROW((void)elastic_energy(model, other.rest_positions), std::invalid_argument);
  // and the static solver reports them, leaving the state
  State state = rest;
  StaticSettings zero_tolerance;
  zero_tolerance.tolerance = 0.0;
  for (const auto& [report, expected] :
       {std::pair{solve_static(model, Constraints(other), Loads{}, StaticSettings{}, state), "36 nodes"},
        std::pair{solve_static(model, Constraints(model), short_loads, StaticSettings{}, state), "loads.nodal_forces"},
        std::pair{solve_static(model, Constraints(model), Loads{}, zero_tolerance, state), "tolerance = 0"}}) {
    EXPECT_FALSE(report.converged);
    EXPECT_NE(report.message.find(expected), std::string::npos) << report.message;
  }
  EXPECT_TRUE(state == rest);
}

TEST(Integrator, RefusesBadSolverSettings) {
  const Model model = test::box_model({1, 1, 1}, Material{});
  for (const auto& [tolerance, iterations] : {std::pair{0.0, 10}, std::pair{1e-6, 0}, std::pair{std::nan(""), 10},
                                              std::pair{std::numeric_limits<double>::infinity(), 10}}) {
    State state = rest_state(model);
    StepSettings settings;
    settings.integrator = Integrator::kImplicitEuler;
    settings.solver_tolerance = tolerance;
    settings.solver_max_iterations = iterations;
    Stepper stepper(model);
    const StepReport report = stepper.step(model, Constraints(model), Loads{}, settings, state);
    EXPECT_EQ(report.status, StepStatus::kInvalidInput) << tolerance << " " << iterations;
    EXPECT_NE(report.message.find("solver_max_iterations = " + std::to_string(iterations)), std::string::npos)
        << report.message;
  }
}

TEST(Integrator, CgFailureIsAStatusNotACrash) {
  const Model model = test::box_model({4, 4, 4}, Material{});
  State state = wobbling_block(model);
  const State before = state;
  StepSettings settings;
  settings.integrator = Integrator::kImplicitEuler;
  settings.time_step = 0.01;
  settings.solver_max_iterations = 2;
  settings.solver_tolerance = 1e-14;
  Stepper stepper(model);
  const StepReport report = stepper.step(model, Constraints(model), Loads{}, settings, state);
  EXPECT_EQ(report.status, StepStatus::kSolverFailed);
  EXPECT_NE(report.message.find("conjugate gradients"), std::string::npos);
  EXPECT_TRUE(state == before);
}

}  // namespace
}  // namespace cubespring
