// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The run's progress on stderr: a bar redrawn in place on a terminal, a line per tenth otherwise
// (logs and pipes get no carriage returns).
#pragma once

#include <chrono>
#include <cstdio>

namespace cubespring::app {

class ProgressBar {
 public:
  /// `frames` to write, `duration` of simulated time [s].
  ProgressBar(int frames, double duration);

  /// Frames written so far and the simulated time reached [s]; cheap to call every step.
  void update(int frames_done, double time);
  /// Draws the final state and ends the line.
  void finish(int frames_done, double time);

 private:
  void draw(int frames_done, double time);

  using Clock = std::chrono::steady_clock;
  int frames_;
  double duration_;
  bool terminal_;
  Clock::time_point start_;
  Clock::time_point last_draw_;
  int last_tenth_ = -1;
};

}  // namespace cubespring::app
