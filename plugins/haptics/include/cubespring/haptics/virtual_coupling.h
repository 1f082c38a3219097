// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// A virtual coupling (Colgate, Stanley and Brown 1995): a rigid tool tied to a haptic device's
// pose by a spring-damper, so that the tool stops at the tissue while the device goes on, and the
// device feels the spring. Units are SI throughout: metres, kilograms, seconds, newtons, radians.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "cubespring/result.h"

namespace cubespring::haptics {

/// The coupling's spring-damper. The angular part follows with the linear part's natural
/// frequency on every axis (its stiffness is that frequency squared times the tool's inertia), so
/// one stiffness sets both and a slender tool's small inertia about its axis cannot make it stiff.
struct CouplingSettings {
  double stiffness = 1000.0;   ///< linear [N/m]: a desktop device renders 1000-2000 N/m
  double damping_ratio = 1.0;  ///< of the spring with the tool's mass (1: critical; > 0) [-]
  double force_limit = 10.0;   ///< the most force the coupling exerts [N]
  double torque_limit = 1.0;   ///< the most torque about the tool's centre of mass [N m]
};

/// Where a device puts the tool: the pose of the tool's frame (its tip at the origin) in the
/// world, and how fast it moves.
struct DeviceState {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  Eigen::Vector3d linear_velocity{0, 0, 0};   ///< of the frame's origin [m/s]
  Eigen::Vector3d angular_velocity{0, 0, 0};  ///< [rad/s], world frame
  double time = 0.0;                          ///< when it was there [s]
};

/// A rigid body as the coupling sees it: the pose of its centre-of-mass frame and its velocities.
struct BodyState {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  Eigen::Vector3d linear_velocity{0, 0, 0};   ///< of the centre of mass [m/s]
  Eigen::Vector3d angular_velocity{0, 0, 0};  ///< [rad/s], world frame
};

struct Wrench {
  Eigen::Vector3d force{0, 0, 0};   ///< [N], world frame
  Eigen::Vector3d torque{0, 0, 0};  ///< [N m], world frame, about the point the struct's user names
};

/// The tool's mass properties and where its tip is on its body.
struct ToolInertia {
  double mass = 0.02;                                     ///< [kg]
  Eigen::Vector3d principal_inertia{0, 0, 0};             ///< about the centre of mass, in the body frame [kg m^2]
  Eigen::Isometry3d tip = Eigen::Isometry3d::Identity();  ///< the tool's frame in the body frame
};

class VirtualCoupling {
 public:
  /// Checks the settings (finite, positive stiffness, damping ratio and limits) and the tool.
  static Result<VirtualCoupling> create(const CouplingSettings& settings, const ToolInertia& tool);

  /// The force and the torque about the centre of mass that the coupling puts on the tool's body
  /// when the device is at `device`: each part clamped to its limit.
  Wrench on_tool(const DeviceState& device, const BodyState& body) const;
  /// What the device feels at its frame's origin: the reaction, its torque about that point.
  Wrench on_device(const DeviceState& device, const BodyState& body) const;

  /// The longest world step the coupling is stable at: it acts as an explicit force over a step.
  double longest_stable_step() const;
  /// An error naming the stiffness, the tool's mass and what to change when `step` [s] is longer
  /// than longest_stable_step().
  Status check_step(double step) const;

  /// The body's pose for the tool's frame at `pose` (where the device would put it).
  Eigen::Isometry3d body_pose_for(const Eigen::Isometry3d& tool_frame) const;

  const CouplingSettings& settings() const { return settings_; }
  const ToolInertia& tool() const { return tool_; }
  double natural_frequency() const { return frequency_; }  ///< [rad/s]

 private:
  VirtualCoupling(const CouplingSettings& settings, const ToolInertia& tool);
  CouplingSettings settings_;
  ToolInertia tool_;
  double frequency_ = 0.0;  // sqrt(k / m)
  double damping_ = 0.0;    // linear [N s/m]
};

}  // namespace cubespring::haptics
