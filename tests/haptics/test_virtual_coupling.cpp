// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The virtual coupling against its closed form: a free tool pulled towards a device that stands
// still follows the critically damped spring x(t) = d (1 - (1 + w t) e^(-w t)), w = sqrt(k / m),
// in position and in angle; what the device feels is the reaction; the world step it allows; and
// the device link never hands a thread half of another's write, and refuses a state that is not
// a number.
#include <atomic>
#include <cmath>
#include <thread>

#include <gtest/gtest.h>

#include "bullet/bullet_scene.h"
#include "cubespring/haptics/coupled_tool.h"
#include "cubespring/haptics/device_link.h"

namespace cubespring::haptics {
namespace {

double critically_damped(double distance, double frequency, double t) {
  return distance * (1.0 - (1.0 + frequency * t) * std::exp(-frequency * t));
}

// A 20 g capsule (5 mm radius, 10 cm long) alone in a world without gravity, coupled at its tip.
struct FreeTool {
  test::BulletScene scene{Eigen::Vector3d::Zero()};
  btRigidBody* body = nullptr;
  std::optional<CoupledTool> tool;

  explicit FreeTool(const CouplingSettings& settings) {
    body = scene.add_rigid(new btCapsuleShapeZ(btScalar(0.005), btScalar(0.09)), 0.0, test::at(0, 0, 0.05), true);
    Eigen::Isometry3d tip = Eigen::Isometry3d::Identity();
    tip.translation() = Eigen::Vector3d(0, 0, -0.05);
    Result<CoupledTool> coupled = CoupledTool::create(scene.world(), *body, 0.02, tip, settings);
    EXPECT_TRUE(coupled.ok()) << coupled.message();
    if (coupled) tool.emplace(std::move(coupled).value());
  }
};

TEST(VirtualCoupling, AFreeToolFollowsTheCriticallyDampedSpringToTheDevice) {
  CouplingSettings settings;
  settings.stiffness = 1000;
  FreeTool free(settings);
  ASSERT_TRUE(free.tool);
  DeviceState device;
  free.tool->place_at(device);
  EXPECT_LT(free.tool->tool_frame().translation().norm(), 1e-8)
      << "placed with its tip at the device (Bullet's floats)";
  const double distance = 0.005;
  device.pose.translation() = Eigen::Vector3d(distance, 0, 0);
  const double w = free.tool->coupling().natural_frequency();
  EXPECT_NEAR(w, std::sqrt(1000 / 0.02), 1e-9);
  const double dt = 2e-5;  // the closed form is the continuous coupling's: small steps
  double worst = 0.0;
  double furthest = 0.0;
  for (int n = 1; n <= 2500; ++n) {
    free.tool->couple(device);
    free.scene.world().stepSimulation(btScalar(dt), 1, btScalar(dt));
    const double x = free.tool->tool_frame().translation().x();
    worst = std::max(worst, std::abs(x - critically_damped(distance, w, n * dt)));
    furthest = std::max(furthest, x);
  }
  EXPECT_LT(worst, 0.01 * distance);
  EXPECT_LE(furthest, distance * (1 + 1e-6)) << "critical damping: no overshoot";
  EXPECT_NEAR(free.tool->tool_frame().translation().x(), distance, 5e-4 * distance) << "w t = 11: 2e-4 short";
  EXPECT_LT(free.tool->tool_frame().translation().tail<2>().norm(), 1e-9) << "a pull at the tip, straight";
}

TEST(VirtualCoupling, AFreeToolTurnsToTheDeviceWithTheSameFrequency) {
  FreeTool free(CouplingSettings{});
  ASSERT_TRUE(free.tool);
  DeviceState device;
  free.tool->place_at(device);
  const double angle = 0.1;  // [rad] about y, through the tip
  device.pose.linear() = Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const double w = free.tool->coupling().natural_frequency();
  const double dt = 2e-5;
  double worst = 0.0;
  for (int n = 1; n <= 2500; ++n) {
    free.tool->couple(device);
    free.scene.world().stepSimulation(btScalar(dt), 1, btScalar(dt));
    const Eigen::AngleAxisd turned(free.tool->tool_frame().linear());
    worst = std::max(worst, std::abs(turned.angle() - critically_damped(angle, w, n * dt)));
  }
  // the tip turns with the body, which the linear spring pulls back: the angle follows the
  // same law while the tip's small offset fades (within a few percent)
  EXPECT_LT(worst, 0.03 * angle);
  EXPECT_NEAR(Eigen::AngleAxisd(free.tool->tool_frame().linear()).angle(), angle, 1e-3 * angle);
  EXPECT_LT(free.tool->tool_frame().translation().norm(), 1e-6);
}

TEST(VirtualCoupling, TheDeviceFeelsTheReactionAboutItsPoint) {
  ToolInertia tool;
  tool.principal_inertia = Eigen::Vector3d(1.7e-5, 1.7e-5, 2.5e-7);
  tool.tip.translation() = Eigen::Vector3d(0, 0, -0.05);
  Result<VirtualCoupling> coupling = VirtualCoupling::create(CouplingSettings{}, tool);
  ASSERT_TRUE(coupling.ok()) << coupling.message();
  // the device away from the origin, tilted 0.3 rad about y
  DeviceState device;
  device.pose.translation() = Eigen::Vector3d(0.02, -0.01, 0.07);
  device.pose.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY()).toRotationMatrix();
  BodyState body;
  body.pose = coupling->body_pose_for(device.pose);
  EXPECT_TRUE(body.pose.translation().isApprox(device.pose * Eigen::Vector3d(0, 0, 0.05)))
      << "the centre of mass 5 cm up the tool's own axis";
  EXPECT_LT(coupling->on_tool(device, body).force.norm(), 1e-12) << "no pull where the device is";
  EXPECT_LT(coupling->on_tool(device, body).torque.norm(), 1e-12);
  // the tool held 2 mm off the device and turned 0.05 rad further about x
  body.pose.translation() += Eigen::Vector3d(0, 0.002, -0.001);
  body.pose.linear() = Eigen::AngleAxisd(0.05, Eigen::Vector3d::UnitX()).toRotationMatrix() * body.pose.linear();
  const Wrench on_tool = coupling->on_tool(device, body);
  const Wrench felt = coupling->on_device(device, body);
  EXPECT_TRUE(on_tool.force.isApprox(1000 * Eigen::Vector3d(0, -0.002, 0.001), 1e-9)) << on_tool.force.transpose();
  // the angular spring turns it back about -x: I w^2 angle with the tool's inertia about that axis
  const Eigen::Matrix3d axes = body.pose.linear();
  const Eigen::Matrix3d inertia = axes * tool.principal_inertia.asDiagonal() * axes.transpose();
  EXPECT_TRUE(on_tool.torque.isApprox(inertia * (1000 / 0.02) * Eigen::Vector3d(-0.05, 0, 0), 1e-6))
      << on_tool.torque.transpose();
  // the device: the opposite force, held at the tool's target centre, and the opposite torque,
  // both taken about the device's point
  const Eigen::Vector3d held_at = device.pose * Eigen::Vector3d(0, 0, 0.05);
  EXPECT_TRUE((felt.force + on_tool.force).isZero(1e-12));
  EXPECT_TRUE(
      felt.torque.isApprox(-on_tool.torque + (held_at - device.pose.translation()).cross(-on_tool.force), 1e-9));
  // past the limits the force and torque keep their direction at the limit's length
  body.pose.translation() += Eigen::Vector3d(0, 1.0, 0);
  EXPECT_NEAR(coupling->on_tool(device, body).force.norm(), CouplingSettings{}.force_limit, 1e-9);
}

TEST(VirtualCoupling, NamesTheStepItNeedsAndBadSettings) {
  ToolInertia tool;
  tool.principal_inertia = Eigen::Vector3d(1e-5, 1e-5, 1e-6);
  CouplingSettings stiff;
  stiff.stiffness = 2000;
  Result<VirtualCoupling> coupling = VirtualCoupling::create(stiff, tool);
  ASSERT_TRUE(coupling.ok());
  // critical damping: explicit steps are stable while w dt < 2 (sqrt 2 - 1); half of that allowed
  EXPECT_NEAR(coupling->longest_stable_step(), (std::sqrt(2.0) - 1) / std::sqrt(2000 / 0.02), 1e-12);
  EXPECT_TRUE(coupling->check_step(0.001).ok());
  const Status too_long = coupling->check_step(0.004);
  ASSERT_FALSE(too_long.ok());
  EXPECT_NE(too_long.message().find("2000 N/m"), std::string::npos) << too_long.message();
  EXPECT_NE(too_long.message().find("0.004 s"), std::string::npos) << too_long.message();
  CouplingSettings bad;
  bad.stiffness = -1;
  EXPECT_NE(VirtualCoupling::create(bad, tool).message().find("stiffness -1 N/m"), std::string::npos);
  bad = CouplingSettings{};
  bad.damping_ratio = std::nan("");
  EXPECT_NE(VirtualCoupling::create(bad, tool).message().find("damping ratio nan"), std::string::npos);
  bad.damping_ratio = 0;  // against tissue an undamped coupling has no stable step
  EXPECT_NE(VirtualCoupling::create(bad, tool).message().find("damping ratio 0: must be a number > 0"),
            std::string::npos);
  // lightly damped, the tissue's sub-steps need w dt < 4 z: the bound falls with the damping
  bad.damping_ratio = 0.1;
  EXPECT_NEAR(VirtualCoupling::create(bad, tool)->longest_stable_step(), 0.5 * 0.4 / std::sqrt(1000 / 0.02), 1e-12);
  tool.mass = 0;
  EXPECT_NE(VirtualCoupling::create(CouplingSettings{}, tool).message().find("tool mass 0 kg"), std::string::npos);
}

TEST(DeviceLink, NoThreadReadsHalfOfAnothersWrite) {
  ToolInertia tool;
  tool.principal_inertia = Eigen::Vector3d(1e-5, 1e-5, 1e-6);
  DeviceLink link(*VirtualCoupling::create(CouplingSettings{}, tool));
  EXPECT_FALSE(link.device());
  EXPECT_TRUE(link.exchange(DeviceState{}).force.isZero()) << "nothing felt before the tool is published";
  DeviceState broken;
  broken.pose.translation().x() = std::nan("");
  link.publish_tool(BodyState{}, 0.0);
  EXPECT_TRUE(link.exchange(broken).force.isZero()) << "a state that is not a number is not felt";
  EXPECT_TRUE(link.device()->pose.translation().allFinite()) << "nor kept";
  std::atomic<bool> done{false};
  std::atomic<int> torn{0};
  // each write puts one number in every field; a torn read mixes two
  std::thread device_thread([&] {
    for (int i = 0; i < 200000; ++i) {
      DeviceState state;
      state.pose.translation() = Eigen::Vector3d::Constant(i);
      state.linear_velocity = Eigen::Vector3d::Constant(i);
      state.time = i;
      const std::optional<PublishedTool> seen = link.tool();
      if (seen &&
          ((seen->body.pose.translation().array() != seen->time).any() || seen->body.linear_velocity.x() != seen->time))
        ++torn;
      link.exchange(state);
    }
    done = true;
  });
  int reads = 0;
  for (int i = 0; !done; ++i) {
    BodyState body;
    body.pose.translation() = Eigen::Vector3d::Constant(i);
    body.linear_velocity = Eigen::Vector3d::Constant(i);
    link.publish_tool(body, i);
    const std::optional<DeviceState> seen = link.device();
    if (seen && ((seen->pose.translation().array() != seen->time).any() || seen->linear_velocity.x() != seen->time))
      ++torn;
    ++reads;
  }
  device_thread.join();
  EXPECT_EQ(torn.load(), 0);
  EXPECT_GT(reads, 0);
  EXPECT_EQ(link.device()->time, 199999);
}

}  // namespace
}  // namespace cubespring::haptics
