// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// How the bench commands time steps on this shared machine: interleaved batches, best kept.
#pragma once

#include <functional>
#include <utility>
#include <vector>

#include "cubespring/constraints.h"
#include "cubespring/integrator.h"
#include "cubespring/model.h"
#include "cubespring/state.h"

namespace cubespring::app {

/// What time_per_call() does with its first call.
enum class FirstCall {
  kWarmUp,       ///< not timed: it fills caches and first-touch allocations
  kTimedIfLong,  ///< timed, and alone when it takes min_seconds or more (a warm-up would double a long run)
};

/// The mean time per call [s] of fn(), called repeatedly for at least min_seconds after its first.
double time_per_call(double min_seconds, const std::function<void()>& fn, FirstCall first = FirstCall::kWarmUp);

/// Batches of the compared measurements, taken in turn (a, b, c, a, b, c, ...): a burst of load on
/// this shared machine then slows one batch of each rather than one whole column.
inline constexpr int kBatches = 5;

/// The mean time per call [s] of each function, as the fastest of kBatches batches of at least
/// min_seconds / kBatches each, the functions' batches interleaved.
std::vector<double> interleaved_best_times(double min_seconds, const std::vector<std::function<void()>>& functions);

/// One explicit step of a body per call, of time_step [s]; the model, constraints and loads must
/// outlive it. (The stable step is the caller's to find once: max_stable_time_step() assembles
/// the body's stiffness, which costs more than thousands of steps.) min_grid_fill chooses the
/// force passes (StepSettings::min_grid_fill: 0 the grid whenever it can, NaN the spring lists).
/// It takes all `threads` (StepSettings::adapt_threads off, to measure them) unless adapting().
class ExplicitStepper {
 public:
  ExplicitStepper(const Model& model, const Constraints& constraints, const Loads& loads, const State& start,
                  Integrator integrator, int threads, double time_step, double min_grid_fill = kDefaultMinGridFill);
  void operator()();
  /// Lets the step take one thread while one is faster (StepSettings::adapt_threads), as a user's does.
  ExplicitStepper& adapting() {
    settings_.adapt_threads = true;
    return *this;
  }

 private:
  const Model& model_;
  const Constraints& constraints_;
  const Loads& loads_;
  StepSettings settings_;
  State state_;
  Stepper stepper_;
};

/// Two functions run at once on two threads per call (one after the other without OpenMP), for
/// what two cores of this machine give two independent jobs: their shared caches, memory and
/// clock make it less than twice one core. A 2-thread split of one job gains about as much when
/// the split costs nothing (a little more when each half's arrays fit the caches better).
class TwoAtOnce {
 public:
  TwoAtOnce(std::function<void()> first, std::function<void()> second)
      : first_(std::move(first)), second_(std::move(second)) {}
  void operator()() const;

 private:
  std::function<void()> first_, second_;
};

}  // namespace cubespring::app
