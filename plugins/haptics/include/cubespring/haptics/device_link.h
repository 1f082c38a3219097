// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// What a haptic device's thread and the simulation's thread share: the device's last state one
// way, the tool's last state the other. Lock-free: each side writes its own state without ever
// waiting, and reads the other's whole (never half of one write and half of the next). One
// thread calls the device's side (exchange, tool), one the simulation's (device, publish_tool).
// Units are SI.
#pragma once

#include <memory>
#include <optional>

#include "cubespring/haptics/virtual_coupling.h"

namespace cubespring::haptics {

/// The tool as the simulation published it after a step.
struct PublishedTool {
  BodyState body;
  double time = 0.0;  ///< simulated time at the end of that step [s]
};

class DeviceLink {
 public:
  explicit DeviceLink(const VirtualCoupling& coupling);
  ~DeviceLink();
  DeviceLink(const DeviceLink&) = delete;
  DeviceLink& operator=(const DeviceLink&) = delete;

  /// The device's side, at its own rate (1 kHz): gives the device's state and returns what the
  /// device should render. Between simulation steps the tool stands where the last step left it
  /// and the coupling spring stretches with the device's own motion, so the force follows the
  /// hand at the device's rate instead of holding for a whole simulation step. Zero until the
  /// simulation has published the tool, and for a state that is not finite (which is not kept).
  Wrench exchange(const DeviceState& device);

  /// The device's side too: the tool's last publication, body and time together (none before the
  /// first), as exchange() uses it.
  std::optional<PublishedTool> tool() const;

  /// The simulation's side: the device's last state (none before the device's first exchange)...
  std::optional<DeviceState> device() const;
  /// ... and, after each step, the tool's body where the step left it, at simulated time `time` [s].
  void publish_tool(const BodyState& tool, double time);

  const VirtualCoupling& coupling() const { return coupling_; }

 private:
  struct Boxes;
  const VirtualCoupling coupling_;
  std::unique_ptr<Boxes> boxes_;
};

}  // namespace cubespring::haptics
