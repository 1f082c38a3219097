// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "cubespring/haptics/virtual_coupling.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace cubespring::haptics {
namespace {

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", value);
  return text;
}

Eigen::Vector3d clamped(const Eigen::Vector3d& v, double limit) {
  const double length = v.norm();
  return length > limit ? Eigen::Vector3d(v * (limit / length)) : v;
}

// The rotation taking `from` to `to`, as an axis times its angle in [0, pi] (world frame).
Eigen::Vector3d rotation_between(const Eigen::Matrix3d& from, const Eigen::Matrix3d& to) {
  Eigen::Quaterniond turn(to * from.transpose());
  if (turn.w() < 0) turn.coeffs() = -turn.coeffs();  // the short way round
  const Eigen::AngleAxisd angle_axis(turn);
  return angle_axis.angle() * angle_axis.axis();
}

// Explicit damped spring x'' = -w^2 x - 2 z w x' over steps h / w (the velocity first, then the
// position with it): stable while h < 1 / z and h < 2 (sqrt(z^2 + 1) - z). While the tool touches
// tissue its position follows the soft sub-steps instead (bullet's hand_over), which the
// coupling's own damping must keep stable: h < 4 z, so an undamped coupling never is.
double stable_step_times_frequency(double damping_ratio) {
  const double z = damping_ratio;
  return std::min({2.0 * (std::sqrt(z * z + 1.0) - z), 1.0 / z, 4.0 * z});
}

// Half the bound: the coupled tool then follows the device as the continuous coupling would, not
// merely without blowing up.
constexpr double kStepSafety = 0.5;

}  // namespace

Result<VirtualCoupling> VirtualCoupling::create(const CouplingSettings& settings, const ToolInertia& tool) {
  const auto positive = [](double v) { return std::isfinite(v) && v > 0; };
  if (!positive(settings.stiffness))
    return Status::error("coupling stiffness " + number(settings.stiffness) + " N/m: must be a number > 0");
  if (!positive(settings.damping_ratio))
    return Status::error("coupling damping ratio " + number(settings.damping_ratio) +
                         ": must be a number > 0 (an undamped coupling is unstable against tissue)");
  if (!positive(settings.force_limit))
    return Status::error("coupling force limit " + number(settings.force_limit) + " N: must be a number > 0");
  if (!positive(settings.torque_limit))
    return Status::error("coupling torque limit " + number(settings.torque_limit) + " N m: must be a number > 0");
  if (!positive(tool.mass)) return Status::error("tool mass " + number(tool.mass) + " kg: must be a number > 0");
  if (!(tool.principal_inertia.allFinite() && (tool.principal_inertia.array() > 0).all()))
    return Status::error("tool inertia (" + number(tool.principal_inertia.x()) + ", " +
                         number(tool.principal_inertia.y()) + ", " + number(tool.principal_inertia.z()) +
                         ") kg m^2: each principal moment must be a number > 0");
  if (!tool.tip.matrix().allFinite()) return Status::error("tool tip pose: must be finite");
  return VirtualCoupling(settings, tool);
}

VirtualCoupling::VirtualCoupling(const CouplingSettings& settings, const ToolInertia& tool)
    : settings_(settings),
      tool_(tool),
      frequency_(std::sqrt(settings.stiffness / tool.mass)),
      damping_(2.0 * settings.damping_ratio * std::sqrt(settings.stiffness * tool.mass)) {}

Eigen::Isometry3d VirtualCoupling::body_pose_for(const Eigen::Isometry3d& tool_frame) const {
  return tool_frame * tool_.tip.inverse();
}

Wrench VirtualCoupling::on_tool(const DeviceState& device, const BodyState& body) const {
  // where the body would be if the tool stood exactly at the device, and how fast that point moves
  const Eigen::Isometry3d target = body_pose_for(device.pose);
  const Eigen::Vector3d target_velocity =
      device.linear_velocity + device.angular_velocity.cross(target.translation() - device.pose.translation());
  Wrench wrench;
  wrench.force = settings_.stiffness * (target.translation() - body.pose.translation()) +
                 damping_ * (target_velocity - body.linear_velocity);
  wrench.force = clamped(wrench.force, settings_.force_limit);
  // the same natural frequency and damping ratio about every axis: torque = I (w^2 angle + 2 z w rate)
  const Eigen::Matrix3d axes = body.pose.linear();
  const Eigen::Matrix3d inertia = axes * tool_.principal_inertia.asDiagonal() * axes.transpose();
  const Eigen::Vector3d angle = rotation_between(body.pose.linear(), target.linear());
  const Eigen::Vector3d rate = device.angular_velocity - body.angular_velocity;
  wrench.torque = inertia * (frequency_ * frequency_ * angle + 2.0 * settings_.damping_ratio * frequency_ * rate);
  wrench.torque = clamped(wrench.torque, settings_.torque_limit);
  return wrench;
}

Wrench VirtualCoupling::on_device(const DeviceState& device, const BodyState& body) const {
  const Wrench tool = on_tool(device, body);
  // the spring's other end is the target centre of mass, carried rigidly by the device's frame
  const Eigen::Vector3d arm = body_pose_for(device.pose).translation() - device.pose.translation();
  Wrench felt;
  felt.force = -tool.force;
  felt.torque = -tool.torque + arm.cross(felt.force);
  return felt;
}

double VirtualCoupling::longest_stable_step() const {
  return kStepSafety * stable_step_times_frequency(settings_.damping_ratio) / frequency_;
}

Status VirtualCoupling::check_step(double step) const {
  if (step <= longest_stable_step()) return {};
  return Status::error("a coupling of " + number(settings_.stiffness) + " N/m (damping ratio " +
                       number(settings_.damping_ratio) + ") on a tool of " + number(tool_.mass) +
                       " kg is stable at world steps up to " + number(longest_stable_step()) + " s, and the step is " +
                       number(step) + " s: step the world in shorter steps, lower the stiffness or give the tool " +
                       "more mass");
}

}  // namespace cubespring::haptics
