// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "step_timing.h"

#include <algorithm>
#include <chrono>
#include <limits>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace cubespring::app {

double time_per_call(double min_seconds, const std::function<void()>& fn, FirstCall first) {
  using Clock = std::chrono::steady_clock;
  const auto first_start = Clock::now();
  fn();
  const double first_seconds = std::chrono::duration<double>(Clock::now() - first_start).count();
  if (first == FirstCall::kTimedIfLong && first_seconds >= min_seconds) return first_seconds;
  int calls = 0;
  const auto start = Clock::now();
  double elapsed = 0.0;
  do {
    fn();
    ++calls;
    elapsed = std::chrono::duration<double>(Clock::now() - start).count();
  } while (elapsed < min_seconds);
  return elapsed / calls;
}

std::vector<double> interleaved_best_times(double min_seconds, const std::vector<std::function<void()>>& functions) {
  std::vector<double> best(functions.size(), std::numeric_limits<double>::infinity());
  for (int batch = 0; batch < kBatches; ++batch) {
    for (std::size_t f = 0; f < functions.size(); ++f) {
      best[f] = std::min(best[f], time_per_call(min_seconds / kBatches, functions[f]));
    }
  }
  return best;
}

ExplicitStepper::ExplicitStepper(const Model& model, const Constraints& constraints, const Loads& loads,
                                 const State& start, Integrator integrator, int threads, double time_step,
                                 double min_grid_fill)
    : model_(model), constraints_(constraints), loads_(loads), state_(start), stepper_(model) {
  settings_.min_grid_fill = min_grid_fill;
  settings_.integrator = integrator;
  settings_.threads = threads;
  settings_.adapt_threads = false;
  settings_.time_step = time_step;
}

void TwoAtOnce::operator()() const {
#ifdef _OPENMP
#pragma omp parallel num_threads(2)
  {
    if (omp_get_thread_num() == 0) first_();
    // one thread when the runtime gives no second (OMP_THREAD_LIMIT, OMP_DYNAMIC): it runs both
    if (omp_get_thread_num() == 1 || omp_get_num_threads() == 1) second_();
  }
#else
  first_();
  second_();
#endif
}

void ExplicitStepper::operator()() { (void)stepper_.step(model_, constraints_, loads_, settings_, state_); }

}  // namespace cubespring::app
