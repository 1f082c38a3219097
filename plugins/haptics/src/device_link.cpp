// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "cubespring/haptics/device_link.h"

#include "seqlock.h"

namespace cubespring::haptics {
namespace {

// The states as plain numbers (Eigen's types are not trivially copyable in the language's sense).
struct DeviceWords {
  double pose[16];
  double linear_velocity[3];
  double angular_velocity[3];
  double time;
};

struct ToolWords {
  double pose[16];
  double linear_velocity[3];
  double angular_velocity[3];
  double time;
};

template <typename Words>
void pack(const Eigen::Isometry3d& pose, const Eigen::Vector3d& linear, const Eigen::Vector3d& angular, double time,
          Words& words) {
  Eigen::Map<Eigen::Matrix4d>(words.pose) = pose.matrix();
  Eigen::Map<Eigen::Vector3d>(words.linear_velocity) = linear;
  Eigen::Map<Eigen::Vector3d>(words.angular_velocity) = angular;
  words.time = time;
}

template <typename State, typename Words>
State unpack(const Words& words) {
  State state;
  state.pose.matrix() = Eigen::Map<const Eigen::Matrix4d>(words.pose);
  state.linear_velocity = Eigen::Map<const Eigen::Vector3d>(words.linear_velocity);
  state.angular_velocity = Eigen::Map<const Eigen::Vector3d>(words.angular_velocity);
  return state;
}

bool finite(const DeviceState& device) {
  return device.pose.matrix().allFinite() && device.linear_velocity.allFinite() &&
         device.angular_velocity.allFinite() && std::isfinite(device.time);
}

}  // namespace

struct DeviceLink::Boxes {
  Seqlock<DeviceWords> device;
  Seqlock<ToolWords> tool;
  // each reader's last whole value, for when a write is in progress: only its own thread uses it
  mutable ToolWords last_tool{};
  mutable bool has_tool = false;
  mutable DeviceWords last_device{};
  mutable bool has_device = false;
};

DeviceLink::DeviceLink(const VirtualCoupling& coupling) : coupling_(coupling), boxes_(std::make_unique<Boxes>()) {}
DeviceLink::~DeviceLink() = default;

Wrench DeviceLink::exchange(const DeviceState& device) {
  if (!finite(device)) return {};
  DeviceWords words{};
  pack(device.pose, device.linear_velocity, device.angular_velocity, device.time, words);
  boxes_->device.write(words);
  const std::optional<PublishedTool> published = tool();
  // the coupling's arithmetic after the exchange: the simulation never waits on it
  return published ? coupling_.on_device(device, published->body) : Wrench{};
}

std::optional<DeviceState> DeviceLink::device() const {
  if (boxes_->device.read(boxes_->last_device)) boxes_->has_device = true;
  if (!boxes_->has_device) return std::nullopt;
  DeviceState state = unpack<DeviceState>(boxes_->last_device);
  state.time = boxes_->last_device.time;
  return state;
}

void DeviceLink::publish_tool(const BodyState& tool, double time) {
  ToolWords words{};
  pack(tool.pose, tool.linear_velocity, tool.angular_velocity, time, words);
  boxes_->tool.write(words);
}

std::optional<PublishedTool> DeviceLink::tool() const {
  if (boxes_->tool.read(boxes_->last_tool)) boxes_->has_tool = true;
  if (!boxes_->has_tool) return std::nullopt;
  return PublishedTool{unpack<BodyState>(boxes_->last_tool), boxes_->last_tool.time};
}

}  // namespace cubespring::haptics
