// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "cubespring/haptics/device_link.h"

namespace cubespring::haptics {

Wrench DeviceLink::exchange(const DeviceState& device) {
  std::optional<BodyState> tool;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    device_ = device;
    tool = tool_;
  }
  // the coupling's arithmetic outside the lock: the simulation never waits on it
  return tool ? coupling_.on_device(device, *tool) : Wrench{};
}

std::optional<DeviceState> DeviceLink::device() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return device_;
}

void DeviceLink::publish_tool(const BodyState& tool, double time) {
  const std::lock_guard<std::mutex> lock(mutex_);
  tool_ = tool;
  tool_time_ = time;
}

std::optional<BodyState> DeviceLink::tool() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return tool_;
}

double DeviceLink::tool_time() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return tool_time_;
}

}  // namespace cubespring::haptics
