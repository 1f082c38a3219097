// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Plays a recorded device path against a scene in real time, as a haptic device would drive it:
// the device's loop on a thread of its own at its rate, the scene's world on this one at the
// wall clock's pace, the two sharing a haptics::DeviceLink. What `cubespring haptic-replay` does.
#pragma once

#include <string>

#include "cubespring/haptics/device_trajectory.h"
#include "cubespring/haptics/virtual_coupling.h"
#include "cubespring/result.h"
#include "cubespring/scene/scene.h"

namespace cubespring::app {

struct ReplayOptions {
  std::string tool;      ///< the scene's tool the device drives; empty: the first
  double rate = 1000.0;  ///< the device loop's [Hz]
  haptics::CouplingSettings coupling;
  int threads = 1;        ///< of the organ's force passes
  double duration = 0.0;  ///< [s] to play; 0: the path's; past its end the device holds its last pose
};

/// How the device loop kept its rate: each period is the time between two of its wake-ups.
struct LoopTiming {
  int periods = 0;
  double nominal = 0.0;            ///< [s]
  double mean = 0.0;               ///< [s]
  double percentile99 = 0.0;       ///< [s]
  double longest = 0.0;            ///< [s]
  int later_than_1_5_periods = 0;  ///< at 1 kHz: later than 1.5 ms
  int later_than_5_periods = 0;
  bool real_time_priority = false;  ///< the loop's thread ran under SCHED_FIFO (allowed to root)
};

struct ReplayResult {
  LoopTiming device;
  int world_steps = 0;
  double world_step = 0.0;    ///< [s]
  double simulated = 0.0;     ///< [s]
  double physics_wall = 0.0;  ///< wall time inside the world's steps [s]
  double most_behind = 0.0;   ///< the most the simulation lagged the wall clock [s]
  std::string csv;            ///< device_forces.csv
  std::string plot;           ///< device_force.png
};

/// The header of device_forces.csv: the device's rows at its rate.
extern const char* const kDeviceForceCsvHeader;

/// Settles the scene, makes the chosen tool a coupled body at the path's first pose, then plays
/// the path in real time and writes device_forces.csv and device_force.png to `out`. Errors name
/// the tool, the coupling setting or the instability at fault.
Result<ReplayResult> replay_device_path(const scene::Scene& scene, const haptics::DeviceTrajectory& path,
                                        const ReplayOptions& options, const std::string& out);

}  // namespace cubespring::app
