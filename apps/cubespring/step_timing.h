// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// How the bench commands time steps on this shared machine: interleaved batches, best kept.
#pragma once

#include <functional>
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

/// One explicit step of a body per call, at half its stable time step; the model, constraints and
/// loads must outlive it.
class ExplicitStepper {
 public:
  ExplicitStepper(const Model& model, const Constraints& constraints, const Loads& loads, const State& start,
                  Integrator integrator, int threads);
  void operator()();

 private:
  const Model& model_;
  const Constraints& constraints_;
  const Loads& loads_;
  StepSettings settings_;
  State state_;
  Stepper stepper_;
};

}  // namespace cubespring::app
