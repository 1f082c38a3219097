// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include <cmath>
#include <cstdio>
#include <fstream>

#include <gtest/gtest.h>

#include "cubespring/constraints.h"
#include "cubespring/integrator.h"
#include "cubespring/static_solver.h"
#include "test_support.h"

namespace cubespring {
namespace {

std::string temp_path(const std::string& name) { return ::testing::TempDir() + name; }

TEST(State, ReplayFromASavedStateIsBitIdentical) {
  const Model model = test::box_model({4, 3, 3}, test::notes_material(0.3));
  Constraints clamp(model);
  ASSERT_TRUE(clamp.fix_box(model, {-1, -1, -1}, {1e-9, 1, 1}).ok());
  Loads loads;
  loads.gravity = {0, 0, -9.81};
  StepSettings settings;
  settings.time_step = 0.5 * max_stable_time_step(model);
  State state = rest_state(model);
  Stepper stepper(model);
  for (int i = 0; i < 50; ++i) ASSERT_TRUE(stepper.step(model, clamp, loads, settings, state).ok());
  const std::string path = temp_path("cubespring_state.bin");
  ASSERT_TRUE(save_state(state, path).ok());
  for (int i = 0; i < 50; ++i) ASSERT_TRUE(stepper.step(model, clamp, loads, settings, state).ok());

  Result<State> loaded = load_state(model, path);
  ASSERT_TRUE(loaded.ok()) << loaded.message();
  State replay = loaded.value();
  Stepper fresh(model);
  for (int i = 0; i < 50; ++i) ASSERT_TRUE(fresh.step(model, clamp, loads, settings, replay).ok());
  EXPECT_TRUE(replay == state);
  EXPECT_EQ(state_hash(replay), state_hash(state));
  std::remove(path.c_str());
}

TEST(State, LoadRejectsWrongFiles) {
  const Model small = test::box_model({1, 1, 1}, Material{});
  const Model large = test::box_model({2, 1, 1}, Material{});
  const std::string path = temp_path("cubespring_small.bin");
  ASSERT_TRUE(save_state(rest_state(small), path).ok());
  Result<State> mismatch = load_state(large, path);
  ASSERT_FALSE(mismatch.ok());
  EXPECT_NE(mismatch.message().find("8 nodes"), std::string::npos) << mismatch.message();
  EXPECT_NE(mismatch.message().find(path), std::string::npos);

  std::ofstream(path) << "not a state";
  Result<State> garbage = load_state(small, path);
  ASSERT_FALSE(garbage.ok());
  EXPECT_NE(garbage.message().find("bad header"), std::string::npos);

  // a file of the first format (its magic ends in 1): loaded for a body numbered z-major, as its
  // nodes are in the same order, refused for a body numbered along x
  const Model along_x = test::box_model({20, 15, 15}, Material{});
  ASSERT_EQ(along_x.major_axis, 0);
  for (const Model* model : {&small, &along_x}) {
    ASSERT_TRUE(save_state(rest_state(*model), path).ok());
    std::fstream file(path, std::ios::in | std::ios::out | std::ios::binary);
    file.seekp(7);
    file.put('1');
    file.close();
    Result<State> first_format = load_state(*model, path);
    if (model == &small) {
      EXPECT_TRUE(first_format.ok()) << first_format.message();
    } else {
      ASSERT_FALSE(first_format.ok());
      EXPECT_NE(first_format.message().find("numbered along x"), std::string::npos) << first_format.message();
    }
  }

  Result<State> missing = load_state(small, temp_path("no/such/file.bin"));
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.message().find("cannot open"), std::string::npos);
  std::remove(path.c_str());
}

TEST(State, HashSeesOneBit) {
  const Model model = test::box_model({1, 1, 1}, Material{});
  State a = rest_state(model);
  State b = a;
  EXPECT_EQ(state_hash(a), state_hash(b));
  b.positions(0, 3) = std::nextafter(b.positions(0, 3), 1.0);
  EXPECT_NE(state_hash(a), state_hash(b));
  EXPECT_FALSE(a == b);
}

TEST(Constraints, RejectOutOfRangeNodesAndEmptyBoxes) {
  const Model model = test::box_model({1, 1, 1}, Material{});
  Constraints constraints(model);
  const Status bad = constraints.fix_nodes(model, {0, 8});
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.message().find("node 8"), std::string::npos);
  const Status empty = constraints.fix_box(model, {1, 1, 1}, {2, 2, 2});
  ASSERT_FALSE(empty.ok());
  EXPECT_NE(empty.message().find("no node"), std::string::npos);
  EXPECT_EQ(constraints.num_driven(), 0);
  ASSERT_TRUE(constraints.fix_box(model, {-1, -1, -1}, {1e-9, 1, 1}).ok());
  EXPECT_EQ(constraints.num_driven(), 4);
}

TEST(Constraints, MovingClampPullsABarToItsStaticLength) {
  // a bar fixed at x = 0 and pulled by 0.1 mm at x = L: the static solve stretches it uniformly
  const Model model = test::box_model({4, 1, 1}, test::notes_material(0.0));
  Constraints constraints(model);
  ASSERT_TRUE(constraints.fix_box(model, {-1, -1, -1}, {1e-9, 1, 1}).ok());
  ASSERT_TRUE(constraints.prescribe_box_displacement(model, {0.04 - 1e-9, -1, -1}, {1, 1, 1}, {1e-4, 0, 0}).ok());
  EXPECT_EQ(constraints.num_driven(), 8);
  EXPECT_FALSE(constraints.prescribe_box_displacement(model, {1, 1, 1}, {2, 2, 2}, {0, 0, 0}).ok());
  State state = rest_state(model);
  ASSERT_TRUE(solve_static(model, constraints, Loads{}, StaticSettings{}, state).converged);
  const int middle = model.node_at({2, 1, 1});
  EXPECT_NEAR(state.positions(0, middle) - model.rest_positions(0, middle), 0.5e-4, 1e-9);
}

TEST(Constraints, DrivenNodesFollowTheirTarget) {
  const Model model = test::box_model({2, 1, 1}, test::notes_material(0.3));
  Constraints constraints(model);
  const int node = model.node_at({2, 0, 0});
  ASSERT_TRUE(constraints.prescribe_displacement(model, node, {1e-3, 0, 0}).ok());
  State state = rest_state(model);
  StepSettings settings;
  settings.time_step = 1e-5;
  Stepper stepper(model);
  ASSERT_TRUE(stepper.step(model, constraints, Loads{}, settings, state).ok());
  EXPECT_DOUBLE_EQ(state.positions(0, node), model.rest_positions(0, node) + 1e-3);
  EXPECT_NEAR(state.velocities(0, node), 1e-3 / 1e-5, 1e-9);
}

// A frictionless support: the face x = 0 held along x only, its nodes free to slide in y and z,
// so a bar pulled along x contracts laterally as a free bar does (a clamped face would hold the
// contraction back at that end). One corner pinned and one more node held along z take out the
// rigid motions the support leaves; the homogeneous stretch satisfies them.
TEST(Constraints, AFrictionlessSupportHoldsOneComponentAndLetsTheOthersSlide) {
  const Model model = test::box_model({4, 2, 2}, test::notes_material(0.3));
  Constraints constraints(model);
  const double strain = 1e-4, length = 0.04, width = 0.02;
  ASSERT_TRUE(constraints.prescribe_box_axis_displacement(model, {-1, -1, -1}, {1e-9, 1, 1}, 0, 0.0).ok());
  ASSERT_TRUE(
      constraints.prescribe_box_axis_displacement(model, {length - 1e-9, -1, -1}, {1, 1, 1}, 0, strain * length).ok());
  const int corner = model.node_at({0, 0, 0});
  const int beside = model.node_at({0, 2, 0});
  ASSERT_TRUE(constraints.prescribe_axis_position(corner, 1, model.rest_positions(1, corner)).ok());
  ASSERT_TRUE(constraints.prescribe_axis_position(corner, 2, model.rest_positions(2, corner)).ok());
  ASSERT_TRUE(constraints.prescribe_axis_position(beside, 2, model.rest_positions(2, beside)).ok());
  EXPECT_EQ(constraints.driven_axes(corner), Constraints::kAllAxes);
  EXPECT_EQ(constraints.driven_axes(beside), 0b101);
  EXPECT_EQ(constraints.driven_axes(model.node_at({0, 1, 1})), 0b001);
  EXPECT_EQ(constraints.num_driven(), 18);
  EXPECT_FALSE(constraints.prescribe_axis_position(corner, 3, 0.0).ok());
  EXPECT_FALSE(constraints.prescribe_box_axis_displacement(model, {-1, -1, -1}, {1, 1, 1}, 0, NAN).ok());

  State state = rest_state(model);
  ASSERT_TRUE(solve_static(model, constraints, Loads{}, StaticSettings{}, state).converged);
  // the supported face's far corner slid inward by the lateral strain, as the free end's did
  for (const int x : {0, 4}) {
    const int far = model.node_at({x, 2, 2});
    const double lateral = (state.positions(1, far) - model.rest_positions(1, far)) / width;
    EXPECT_NEAR(lateral, -0.3 * strain, 0.02 * 0.3 * strain) << "x index " << x;
    EXPECT_NEAR(state.positions(0, far) - model.rest_positions(0, far), strain * length * x / 4, 1e-12);
  }
}

// An explicit step moves a node driven along z to its target along z only; gravity along x moves
// it along x as it moves its free neighbours.
TEST(Constraints, ANodeDrivenAlongOneAxisIsFreeAlongTheOthers) {
  const Model model = test::box_model({2, 1, 1}, test::notes_material(0.3));
  Constraints constraints(model);
  const int node = model.node_at({2, 0, 0});
  ASSERT_TRUE(constraints.prescribe_axis_position(node, 2, model.rest_positions(2, node) + 1e-6).ok());
  Loads loads;
  loads.gravity = {-9.81, 0, 0};
  State state = rest_state(model);
  StepSettings settings;
  settings.time_step = 1e-5;
  Stepper stepper(model);
  ASSERT_TRUE(stepper.step(model, constraints, loads, settings, state).ok());
  EXPECT_DOUBLE_EQ(state.positions(2, node), model.rest_positions(2, node) + 1e-6);
  EXPECT_NEAR(state.velocities(2, node), 1e-6 / 1e-5, 1e-9);
  const int free_node = model.node_at({2, 1, 1});
  EXPECT_LT(state.positions(0, node), model.rest_positions(0, node));
  EXPECT_NEAR(state.velocities(0, node), state.velocities(0, free_node),
              1e-3 * std::abs(state.velocities(0, free_node)));
}

}  // namespace
}  // namespace cubespring
