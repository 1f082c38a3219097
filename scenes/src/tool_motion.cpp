// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "cubespring/scene/tool_motion.h"

#include <algorithm>

namespace cubespring::scene {
namespace {

Eigen::Isometry3d pose_of(const Eigen::Vector3d& position, const Eigen::Quaterniond& orientation) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = orientation.toRotationMatrix();
  pose.translation() = position;
  return pose;
}

}  // namespace

Eigen::Isometry3d pose_at(const std::vector<Keyframe>& keyframes, double t) {
  if (keyframes.empty()) return Eigen::Isometry3d::Identity();
  if (t <= keyframes.front().time) return pose_of(keyframes.front().position, keyframes.front().orientation);
  if (t >= keyframes.back().time) return pose_of(keyframes.back().position, keyframes.back().orientation);
  // the first key frame later than t, and the one before it
  const auto after = std::upper_bound(keyframes.begin(), keyframes.end(), t,
                                      [](double time, const Keyframe& k) { return time < k.time; });
  const Keyframe& a = *(after - 1);
  const Keyframe& b = *after;
  const double s = (t - a.time) / (b.time - a.time);
  return pose_of((1.0 - s) * a.position + s * b.position, a.orientation.slerp(s, b.orientation));
}

}  // namespace cubespring::scene
