// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// What a haptic device's thread and the simulation's thread share: the device's last state one
// way, the tool's last state the other. Each side copies under one short lock (a few hundred
// bytes, no allocation), so neither waits on the other's work and no read is torn. Units are SI.
#pragma once

#include <mutex>
#include <optional>

#include "cubespring/haptics/virtual_coupling.h"

namespace cubespring::haptics {

class DeviceLink {
 public:
  explicit DeviceLink(const VirtualCoupling& coupling) : coupling_(coupling) {}

  /// The device's side, at its own rate (1 kHz): gives the device's state and returns what the
  /// device should render. Between simulation steps the tool stands where the last step left it
  /// and the coupling spring stretches with the device's own motion, so the force follows the
  /// hand at the device's rate instead of holding for a whole simulation step. Zero until the
  /// simulation has published the tool.
  Wrench exchange(const DeviceState& device);

  /// The simulation's side: the device's last state (none before the device's first exchange)...
  std::optional<DeviceState> device() const;
  /// ... and, after each step, the tool's body where the step left it, at simulated time `time` [s].
  void publish_tool(const BodyState& tool, double time);

  /// The tool's last published state and its time [s] (none before the first).
  std::optional<BodyState> tool() const;
  double tool_time() const;

  const VirtualCoupling& coupling() const { return coupling_; }

 private:
  const VirtualCoupling coupling_;
  mutable std::mutex mutex_;
  std::optional<DeviceState> device_;
  std::optional<BodyState> tool_;
  double tool_time_ = 0.0;
};

}  // namespace cubespring::haptics
