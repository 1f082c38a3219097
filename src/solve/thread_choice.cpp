// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "solve/thread_choice.h"

#include <algorithm>
#include <cmath>

namespace cubespring {
namespace {

int slot(int threads) { return threads > 1 ? 1 : 0; }

}  // namespace

int ThreadChoice::threads(int allowed) {
  if (allowed <= 1) return 1;
  if (allowed != allowed_) {  // all threads until measured otherwise
    *this = ThreadChoice();
    allowed_ = allowed;
    current_ = allowed;
  }
  const int other = current_ > 1 ? 1 : allowed_;
  const double current_mean = mean_[slot(current_)];
  const double other_mean = mean_[slot(other)];
  if (steps_ < kWarmUpSteps || current_mean <= 0.0) return current_;
  if (other_mean <= 0.0 || probe_now_) return other;
  // a probe costs (other - current) per step it is taken: at most kProbeShare of the steps between
  const double between = std::max<double>(kLeastStepsBetween, std::ceil(other_mean / current_mean / kProbeShare));
  return since_probe_ >= between ? other : current_;
}

void ThreadChoice::record(int threads, double seconds) {
  if (allowed_ <= 1 || !(seconds >= 0.0)) return;
  if (++steps_ <= kWarmUpSteps) return;
  double& mean = mean_[slot(threads)];
  if (threads == current_) {
    mean = mean > 0.0 ? 0.9 * mean + 0.1 * seconds : seconds;
    ++since_probe_;
    const double other_mean = mean_[slot(current_ > 1 ? 1 : allowed_)];
    probe_now_ = other_mean > 0.0 && seconds > 2.0 * other_mean;  // a core was just taken
    return;
  }
  // a probe: its one time is the other count's measure now
  mean = seconds;
  since_probe_ = 0;
  probe_now_ = false;
  if (seconds < kSwitchBelow * mean_[slot(current_)]) current_ = threads;
}

}  // namespace cubespring
