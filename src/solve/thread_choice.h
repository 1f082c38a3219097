// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// How many of the threads a step is allowed it takes: all of them, unless one thread has been
// measured faster. A core busy with another process makes the threads' barriers wait for the
// scheduler: with one busy process on the two cores, the 2-thread step of a 32x8x8 body took
// 6.7 ms against 0.033 ms on one thread. Results do not depend on the thread count, so the choice
// changes only how long a step takes.
#pragma once

namespace cubespring {

class ThreadChoice {
 public:
  /// The threads for the next step, 1 or `allowed`: the faster as last measured, or the other
  /// once in a while to measure it again (a probe, costing at most kProbeShare of the time
  /// between probes at the last measured ratio).
  int threads(int allowed);
  /// The wall time [s] of the step threads() was last asked for, taken on `threads` threads.
  void record(int threads, double seconds);

  static constexpr int kWarmUpSteps = 2;         ///< not timed: the first steps build the engine
  static constexpr int kLeastStepsBetween = 16;  ///< probes at least this many steps apart
  static constexpr double kProbeShare = 0.02;
  static constexpr double kSwitchBelow = 0.85;  ///< the other count wins below this share of the time

 private:
  int allowed_ = 1;
  int current_ = 1;          // the count taken between probes
  double mean_[2] = {0, 0};  // the mean step time on 1 thread and on allowed_ threads [s]; 0: unknown
  int steps_ = 0;            // steps recorded since allowed_ was set
  int since_probe_ = 0;      // steps on current_ since the last probe
  bool probe_now_ = false;   // the current count just slowed past the other's time: measure it at once
};

}  // namespace cubespring
