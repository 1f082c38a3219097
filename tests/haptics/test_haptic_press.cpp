// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The haptic issue's stability and smoothness targets on the contact issue's drag scene: a device
// drives a 20 g capsule probe of 5 mm radius through the coupling, at 1 ms world steps and a
// 1 kHz device, into a 10 x 10 x 5 cm block of 5 kPa tissue (nu = 0.45, 5 mm exact-bending cells,
// mass damping 40/s, friction 0.3) resting on the ground: down at 0.1 m/s to 8 mm under the
// surface, a hold, a 2 cm drag at 2 cm/s, each move starting and stopping smoothly as a hand's. At coupling stiffnesses
// of 200 and 2000 N/m the force the device feels, once the tissue pushes back, never points into the tissue while the
// device is under its surface, the probe never passes the surface by more than 0.5 mm, the tissue carries what the
// spring pulls (momentum balance of the weightless tool at rest), and the drag's force is smooth (RMS less its 20 ms
// moving average under 3% of its mean). Label slow.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "bullet/bullet_scene.h"
#include "cubespring/haptics/coupled_tool.h"
#include "cubespring/haptics/device_link.h"

namespace cubespring::haptics {
namespace {

constexpr double kStep = 0.001;    // world step and device period [s]
constexpr double kRadius = 0.005;  // the probe's [m]

double top_of(const bullet::SoftBody& soft) { return soft.state().positions.row(2).maxCoeff(); }

// A hand's move from 0 to `distance` that starts and stops smoothly: its speed rises as (1 - cos)
// / 2 over `ramp` [s], holds `speed` [m/s], and falls the same way. Where it is after `t` [s].
double smooth_move(double t, double distance, double speed, double ramp) {
  const double cruise = distance / speed - ramp;  // the ramps cover speed x ramp together
  const auto ramped = [&](double s) { return speed * (0.5 * s - ramp / (2 * M_PI) * std::sin(M_PI * s / ramp)); };
  if (t <= 0) return 0.0;
  if (t < ramp) return ramped(t);
  if (t < ramp + cruise) return 0.5 * speed * ramp + speed * (t - ramp);
  if (t < 2 * ramp + cruise) return distance - ramped(2 * ramp + cruise - t);
  return distance;
}

// The device's path: above the block's centre, pressed 1.3 cm down (at most 0.1 m/s) to 8 mm under
// the surface, held, dragged 2 cm along +x at 2 cm/s, held.
struct DevicePath {
  double top;  // the surface's height at rest [m]
  static constexpr double kPressStart = 0.2;
  static constexpr double kPressEnd = kPressStart + 0.013 / 0.1 + 0.05;
  static constexpr double kDragStart = kPressEnd + 0.3;
  static constexpr double kDragEnd = kDragStart + 0.02 / 0.02 + 0.1;
  static constexpr double kEnd = kDragEnd + 0.1;

  Eigen::Vector3d at(double t) const {
    return {-0.01 + smooth_move(t - kDragStart, 0.02, 0.02, 0.1), 0,
            top + 0.005 - smooth_move(t - kPressStart, 0.013, 0.1, 0.05)};
  }
};

class HapticPress : public ::testing::TestWithParam<double> {};

TEST_P(HapticPress, NeitherOscillatesNorTunnelsAndDragsSmoothly) {
  test::BulletScene scene;
  bullet::SoftBody* soft = test::add_tissue_block(scene, 0.3);
  ASSERT_NE(soft, nullptr);
  scene.run(1.0, kStep);  // settle under its weight
  const double top = top_of(*soft);

  btRigidBody* body = scene.add_rigid(new btCapsuleShapeZ(btScalar(kRadius), btScalar(0.1 - 2 * kRadius)), 0.0,
                                      test::at(0, 0, 1), true);
  Eigen::Isometry3d tip = Eigen::Isometry3d::Identity();
  tip.translation() = Eigen::Vector3d(0, 0, -0.05);
  CouplingSettings coupling;
  coupling.stiffness = GetParam();
  Result<CoupledTool> created = CoupledTool::create(scene.world(), *body, 0.02, tip, coupling);
  ASSERT_TRUE(created.ok()) << created.message();
  CoupledTool tool = std::move(created).value();
  ASSERT_TRUE(tool.coupling().check_step(kStep).ok());
  DeviceLink link(tool.coupling());

  const DevicePath path{top};
  DeviceState device;
  device.pose.translation() = path.at(0);
  tool.place_at(device);
  std::vector<double> drag_force;
  double deepest = 0.0;
  double least_felt_inside = 1e9;
  bool pressing = false;
  for (int n = 0; n * kStep < DevicePath::kEnd; ++n) {
    const double t = n * kStep;
    device.time = t;
    device.pose.translation() = path.at(t);
    device.linear_velocity = (path.at(t + 0.5 * kStep) - path.at(t - 0.5 * kStep)) / kStep;
    const Wrench felt = link.exchange(device);  // the device's period, then the world's step
    // pressing: once the tissue pushes the probe with 20 mN, while the device is under the surface
    // (at first touch the device feels the tool's inertia: a few mN either way)
    pressing = pressing || scene.world().getContactWrench(body).force.z() > 0.02;
    if (pressing && device.pose.translation().z() < top)
      least_felt_inside = std::min(least_felt_inside, felt.force.z());
    // the steady part of the drag, at 2 cm/s
    if (t > DevicePath::kDragStart + 0.3 && t < DevicePath::kDragEnd - 0.1) drag_force.push_back(felt.force.norm());
    tool.couple(*link.device());
    scene.world().stepSimulation(btScalar(kStep), 1, btScalar(kStep));
    ASSERT_TRUE(scene.world().getSoftBodyError().empty()) << scene.world().getSoftBodyError();
    link.publish_tool(tool.state(), t + kStep);
    deepest = std::max(deepest, scene.world().getContactWrench(body).penetration);
    if (std::abs(t - (DevicePath::kDragStart - 0.01)) < 0.5 * kStep) {
      // at rest in the hold: the tissue carries what the spring pulls
      const Wrench pulled = tool.coupling().on_tool(*link.device(), tool.state());
      const Eigen::Vector3d carried = scene.world().getContactWrench(body).force;
      std::printf("hold: pulled %.4f N, carried %.4f N, tool speed %.2e m/s\n", pulled.force.z(), carried.z(),
                  tool.state().linear_velocity.norm());
      EXPECT_NEAR(carried.z(), -pulled.force.z(), 0.02 * std::abs(pulled.force.z()));
      EXPECT_GT(-pulled.force.z(), 0.05) << "it presses";
      // the coupling's damper reads the tool's velocity: Bullet's must be its motion (it read
      // 4-5 mm/s here while the coupling's force acted after the sub-steps only)
      EXPECT_LT(tool.state().linear_velocity.norm(), 1e-3);
    }
  }
  // the drag's force less its 20 ms moving average
  const int window = 20;
  double mean = 0.0;
  double square = 0.0;
  int count = 0;
  for (size_t i = window / 2; i + window / 2 < drag_force.size(); ++i) {
    double average = 0.0;
    for (size_t j = i - window / 2; j < i + window / 2; ++j) average += drag_force[j] / window;
    square += (drag_force[i] - average) * (drag_force[i] - average);
    mean += drag_force[i];
    ++count;
  }
  mean /= count;
  const double rough = std::sqrt(square / count) / mean;
  std::printf(
      "k = %.0f N/m: deepest %.3f mm, least upward force while under the surface %.4f N, drag %.4f N, "
      "rough %.2f%%\n",
      GetParam(), 1e3 * deepest, least_felt_inside, mean, 100 * rough);
  EXPECT_TRUE(pressing) << "the tissue pushed back";
  EXPECT_LT(deepest, 0.0005);
  EXPECT_GE(least_felt_inside, 0.0) << "the device is never pulled into the tissue";
  EXPECT_LT(rough, 0.03);
}

INSTANTIATE_TEST_SUITE_P(CouplingStiffness, HapticPress, ::testing::Values(200.0, 2000.0),
                         [](const ::testing::TestParamInfo<double>& k) {
                           return std::to_string(static_cast<int>(k.param)) + "_N_per_m";
                         });

}  // namespace
}  // namespace cubespring::haptics
