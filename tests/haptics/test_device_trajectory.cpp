// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// A recorded device path: read from CSV with errors that name the line, the column and the value,
// and played back between its samples.
#include <cmath>

#include <gtest/gtest.h>

#include "cubespring/haptics/device_trajectory.h"

namespace cubespring::haptics {
namespace {

const std::string kHeader = "time_s,x_m,y_m,z_m,qw,qx,qy,qz\n";

TEST(DeviceTrajectory, PlaysLinearlyAndSlerpsBetweenSamples) {
  const std::string text = "# a press\n" + kHeader +
                           "0, 0, 0, 0.1, 1, 0, 0, 0\n"
                           "\n"
                           "0.5, 0.01, 0, 0.05, 0.7071067811865476, 0.7071067811865476, 0, 0\n";
  Result<DeviceTrajectory> path = DeviceTrajectory::parse(text, "press.csv");
  ASSERT_TRUE(path.ok()) << path.message();
  EXPECT_EQ(path->samples().size(), 2u);
  const DeviceState middle = path->at(0.25);
  EXPECT_TRUE(middle.pose.translation().isApprox(Eigen::Vector3d(0.005, 0, 0.075), 1e-12));
  EXPECT_TRUE(middle.linear_velocity.isApprox(Eigen::Vector3d(0.02, 0, -0.1), 1e-12));
  // a quarter turn about x over 0.5 s: half of it at 0.25 s, at pi rad/s
  EXPECT_NEAR(Eigen::AngleAxisd(middle.pose.linear()).angle(), M_PI / 4, 1e-9);
  EXPECT_TRUE(middle.angular_velocity.isApprox(Eigen::Vector3d(M_PI, 0, 0), 1e-9));
  // held still before the first sample and after the last
  EXPECT_TRUE(path->at(-1).pose.translation().isApprox(Eigen::Vector3d(0, 0, 0.1)));
  EXPECT_TRUE(path->at(-1).linear_velocity.isZero());
  EXPECT_TRUE(path->at(7).pose.translation().isApprox(Eigen::Vector3d(0.01, 0, 0.05)));
  EXPECT_TRUE(path->at(7).linear_velocity.isZero());
}

struct BadTrajectory {
  std::string text;
  std::string message;  // what the error must contain
};

class DeviceTrajectoryErrors : public ::testing::TestWithParam<BadTrajectory> {};

TEST_P(DeviceTrajectoryErrors, NameTheLineTheColumnAndTheValue) {
  Result<DeviceTrajectory> path = DeviceTrajectory::parse(GetParam().text, "path.csv");
  ASSERT_FALSE(path.ok());
  EXPECT_NE(path.message().find(GetParam().message), std::string::npos) << path.message();
  EXPECT_EQ(path.message().find('\n'), std::string::npos) << "one line";
  EXPECT_LT(path.message().size(), 300u);
}

INSTANTIATE_TEST_SUITE_P(
    Bad, DeviceTrajectoryErrors,
    ::testing::Values(
        BadTrajectory{"", "path.csv: empty"},
        BadTrajectory{
            "time,x,y,z\n0,0,0,0\n",
            "path.csv:1: the first line must be the header time_s,x_m,y_m,z_m,qw,qx,qy,qz, not \"time,x,y,z\""},
        BadTrajectory{kHeader, "no samples"},
        BadTrajectory{kHeader + "0,0,0,0,1,0,0\n", "path.csv:2: 7 values, expected 8"},
        BadTrajectory{kHeader + "0,0,0,0,1,0,0,0\n0.1,0,y,0,1,0,0,0\n", "path.csv:3: y_m \"y\" is not"},
        BadTrajectory{kHeader + "0,1e999,0,0,1,0,0,0\n", "x_m \"1e999\" is not a finite number"},
        BadTrajectory{kHeader + "0,0,0,0,1,0,0,0\n0,0,0,0,1,0,0,0\n", "path.csv:3: time_s 0 must be later"},
        BadTrajectory{kHeader + "0,0,0,0,0,0,0,0\n", "orientation qw, qx, qy, qz must be neither zero"},
        BadTrajectory{kHeader + "0,0,0,0,1e200,0,0,0\n", "nor larger than 1e150"},
        BadTrajectory{kHeader + "0,0,0,5000,1,0,0,0\n", "the position (0, 0, 5000) is more than 1 km"},
        BadTrajectory{kHeader + "0," + std::string(5000, '7') + "x,0,0,1,0,0,0\n", "x_m \"777"}));

TEST(DeviceTrajectory, ShipsAPressADragAndARelease) {
  Result<DeviceTrajectory> path = DeviceTrajectory::load(CUBESPRING_DATA_DIR "/haptics/press_drag_release.csv");
  ASSERT_TRUE(path.ok()) << path.message();
  EXPECT_GT(path->end_time() - path->start_time(), 2.0);
  EXPECT_FALSE(DeviceTrajectory::load(CUBESPRING_DATA_DIR "/haptics/no_such.csv").ok());
}

}  // namespace
}  // namespace cubespring::haptics
