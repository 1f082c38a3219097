// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The step's choice of threads (src/solve/thread_choice.h) against step times given to it: it
// takes the faster count, measures the other now and then (less often the slower that one was),
// and at once when the current count slows past the other's time. Through the stepper: a body's
// steps give the same bits whatever it chose.
#include <gtest/gtest.h>

#include "cubespring/integrator.h"
#include "solve/thread_choice.h"
#include "test_support.h"

namespace cubespring {
namespace {

// Steps `steps` times with the given step time per thread count; returns how many took 1 thread.
int run(ThreadChoice& choice, int steps, double one_thread_seconds, double two_thread_seconds) {
  int on_one = 0;
  for (int i = 0; i < steps; ++i) {
    const int threads = choice.threads(2);
    EXPECT_TRUE(threads == 1 || threads == 2) << threads;
    if (threads == 1) ++on_one;
    choice.record(threads, threads == 1 ? one_thread_seconds : two_thread_seconds);
  }
  return on_one;
}

TEST(ThreadChoice, OneThreadAllowedIsOneThread) {
  ThreadChoice choice;
  for (int i = 0; i < 10; ++i) {
    EXPECT_EQ(choice.threads(1), 1);
    choice.record(1, 1e-3);
  }
}

TEST(ThreadChoice, TakesTheFasterCountAndProbesTheOtherRarely) {
  ThreadChoice choice;
  // two threads twice as fast: all but the probes on two, the probes at least 16 steps apart
  const int probes = run(choice, 1000, 2e-3, 1e-3);
  EXPECT_GE(probes, 1);
  EXPECT_LE(probes, 1000 / ThreadChoice::kLeastStepsBetween + 1);
  // a core taken: two threads now 50 times as slow as one; it turns to one within a few steps,
  // and probes two again once per 50 / kProbeShare = 2500 steps
  EXPECT_GE(run(choice, 3, 2e-3, 0.1), 1);
  const int on_one = run(choice, 10000, 2e-3, 0.1);
  EXPECT_GE(on_one, 10000 - 10000 / 2500);
  // the core free again: back to two by the next probe
  run(choice, 6000, 2e-3, 1e-3);
  EXPECT_LE(run(choice, 1000, 2e-3, 1e-3), 1000 / ThreadChoice::kLeastStepsBetween + 1);
}

TEST(ThreadChoice, TimesWithinNoiseOfEachOtherKeepTheCurrentCount) {
  ThreadChoice choice;
  run(choice, 10, 1e-3, 1e-3);
  // one thread 10% faster is within the switch's margin: two threads stay, but for the probes
  EXPECT_LE(run(choice, 1000, 0.9e-3, 1e-3), 1000 / ThreadChoice::kLeastStepsBetween + 1);
}

// Whatever the stepper chose, the steps are the same bits as one thread's.
TEST(ThreadChoice, AStepperThatAdaptsGivesOneThreadsBits) {
  Material m;
  const Model model = test::box_model({32, 8, 8}, m);
  Constraints clamp(model);
  ASSERT_TRUE(clamp.fix_box(model, Eigen::Vector3d::Constant(-1), Eigen::Vector3d(1e-9, 1, 1)).ok());
  Loads loads;
  loads.gravity = Eigen::Vector3d(0, 0, -9.81);
  StepSettings one, adapting;
  one.time_step = adapting.time_step = 1e-5;
  one.threads = 1;
  adapting.threads = 2;
  State a = rest_state(model), b = rest_state(model);
  Stepper first(model), second(model);
  int on_two = 0;
  for (int i = 0; i < 200; ++i) {
    ASSERT_TRUE(first.step(model, clamp, loads, one, a).ok());
    const StepReport report = second.step(model, clamp, loads, adapting, b);
    ASSERT_TRUE(report.ok());
    if (report.threads == 2) ++on_two;
  }
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.velocities, b.velocities);
  std::printf("%d of 200 steps took 2 threads\n", on_two);
}

}  // namespace
}  // namespace cubespring
