// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// A recorded device path: the tool tip's pose over time, read from CSV, to play a device without
// its hardware (`cubespring haptic-replay`). Units are SI: seconds, metres.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cubespring/haptics/virtual_coupling.h"
#include "cubespring/result.h"

namespace cubespring::haptics {

/// One sample: when, and the tool tip's pose in the scene's frame.
struct DeviceSample {
  double time = 0.0;                  ///< [s]
  Eigen::Vector3d position{0, 0, 0};  ///< [m]
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
};

class DeviceTrajectory {
 public:
  /// The header's columns, in order: `time_s,x_m,y_m,z_m,qw,qx,qy,qz`.
  static const char* const kHeader;
  /// The largest file read [bytes].
  static constexpr std::uintmax_t kMaxBytes = 64000000;

  /// Parses CSV text: the header line, then one sample a line with times strictly increasing;
  /// `#` starts a comment line, blank lines are skipped, quaternions are normalised. Errors are
  /// "SOURCE:LINE: message" naming the column and the value.
  static Result<DeviceTrajectory> parse(const std::string& text, const std::string& source);
  static Result<DeviceTrajectory> load(const std::string& path);

  /// The device at time t [s]: positions linear and orientations slerped between the samples
  /// around t, velocities those of the segment; the first sample's pose at rest before it, the
  /// last one's after it.
  DeviceState at(double t) const;

  double start_time() const { return samples_.front().time; }
  double end_time() const { return samples_.back().time; }
  const std::vector<DeviceSample>& samples() const { return samples_; }

 private:
  explicit DeviceTrajectory(std::vector<DeviceSample> samples) : samples_(std::move(samples)) {}
  std::vector<DeviceSample> samples_;  // at least one
};

}  // namespace cubespring::haptics
