// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// `cubespring haptic-replay`, as a user runs it: a recorded device path pressing the default
// scene's probe into the liver through the coupling, in real time, and the errors a wrong tool, a
// bad path or a scene without tools give. Label slow (the replay takes its path's wall time).
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli/tool_run.h"

namespace {

namespace fs = std::filesystem;
using cubespring::test::run_tool;
using cubespring::test::ToolRun;

class HapticReplay : public ::testing::Test {
 protected:
  HapticReplay() {
    std::string pattern = (fs::temp_directory_path() / "cubespring_haptics_XXXXXX").string();
    dir_ = mkdtemp(pattern.data());
  }
  ~HapticReplay() override {
    std::error_code ignored;
    fs::remove_all(dir_, ignored);
  }
  std::string write(const std::string& name, const std::string& text) {
    const fs::path path = dir_ / name;
    std::ofstream(path) << text;
    return path.string();
  }
  fs::path dir_;
};

// The default scene's probe over the liver (its surface there at about z = 7.2 cm): held above,
// pressed 1.8 cm down over 0.6 s, held.
const std::string kPress =
    "time_s,x_m,y_m,z_m,qw,qx,qy,qz\n"
    "0.0,0.010,0,0.085,1,0,0,0\n"
    "0.2,0.010,0,0.085,1,0,0,0\n"
    "0.8,0.010,0,0.062,1,0,0,0\n"
    "1.5,0.010,0,0.062,1,0,0,0\n";

std::vector<std::vector<double>> read_rows(const fs::path& csv, std::string& header) {
  std::ifstream file(csv);
  std::getline(file, header);
  std::vector<std::vector<double>> rows;
  std::string line;
  while (std::getline(file, line)) {
    std::vector<double> row;
    std::stringstream fields(line);
    std::string field;
    while (std::getline(fields, field, ',')) row.push_back(std::stod(field));
    rows.push_back(row);
  }
  return rows;
}

TEST_F(HapticReplay, TheDeviceFeelsTheLiverPushBackAtItsRate) {
  const std::string path = write("press.csv", kPress);
  const fs::path out = dir_ / "out";
  const ToolRun run = run_tool("haptic-replay " + path + " --out " + out.string() + " --json", false);
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const nlohmann::json report = nlohmann::json::parse(run.out);
  // 1.5 s at 1 kHz; a period the machine lost still counts once
  EXPECT_GT(report["device"]["periods"].get<int>(), 1200);
  EXPECT_LE(report["device"]["periods"].get<int>(), 1500);
  for (const char* key : {"percentile99_period_s", "longest_period_s", "later_than_1_5_periods", "later_than_5_periods",
                          "real_time_priority"})
    EXPECT_TRUE(report["device"].contains(key)) << key;
  EXPECT_GE(report["simulation"]["simulated_s"].get<double>(), 1.5 - 1e-9);
  // the scene's 4 ms steps split for a 1000 N/m coupling on a 20 g probe
  EXPECT_LE(report["simulation"]["world_step_s"].get<double>(), 0.0019);

  std::string header;
  const std::vector<std::vector<double>> rows = read_rows(out / "device_forces.csv", header);
  EXPECT_EQ(header,
            "time_s,force_x_N,force_y_N,force_z_N,torque_x_Nm,torque_y_Nm,torque_z_Nm,device_x_m,device_y_m,device_z_m,"
            "tool_x_m,tool_y_m,tool_z_m");
  ASSERT_GT(rows.size(), 1000u);
  double held = 0.0;  // the hold's mean upward force
  int count = 0;
  for (const std::vector<double>& row : rows) {
    ASSERT_EQ(row.size(), 13u);
    for (const double value : row) ASSERT_TRUE(std::isfinite(value));
    if (row[0] < 0.15) {
      EXPECT_LT(std::abs(row[3]), 1e-3) << "nothing touches above the liver, t = " << row[0];
    }
    if (row[0] > 1.2) {
      held += row[3];
      ++count;
      EXPECT_GT(row[12], row[9] + 1e-4) << "the liver stops the probe above the device, t = " << row[0];
      EXPECT_GT(row[3], 0.0) << "the device is pushed back up, t = " << row[0];
    }
  }
  ASSERT_GT(count, 100);
  held /= count;
  // steady in the hold: the last period's force is the hold's mean
  const std::vector<double>& last = rows.back();
  EXPECT_NEAR(last[3], held, 0.05 * held);
  EXPECT_GT(held, 0.2);
  EXPECT_LT(held, 10.0) << "under the coupling's force limit";
  EXPECT_TRUE(fs::exists(out / "device_force.png"));
}

TEST_F(HapticReplay, AWrongToolABadPathAndASceneWithoutToolsAreNamed) {
  const std::string path = write("press.csv", kPress);
  ToolRun run = run_tool("haptic-replay " + path + " --tool scalpel --out " + (dir_ / "out").string());
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.out.find("error: --tool scalpel: "), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("has no such tool (it has probe)"), std::string::npos) << run.out;

  const std::string bad = write("bad.csv", "time_s,x_m,y_m,z_m,qw,qx,qy,qz\n0,0,0,0,1,0,0,0\n0.1,0,zero,0,1,0,0,0\n");
  run = run_tool("haptic-replay " + bad);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.out.find("bad.csv:3: y_m \"zero\" is not a finite number"), std::string::npos) << run.out;

  const std::string scene =
      write("no_tools.json", "{\"organ\": {\"mesh\": \"" + std::string(CUBESPRING_DATA_DIR) + "/liver.obj\"}}");
  run = run_tool("haptic-replay " + path + " " + scene);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.out.find("the scene has no tool for the device to drive"), std::string::npos) << run.out;

  run = run_tool("haptic-replay " + path + " --stiffness 0");
  EXPECT_EQ(run.exit_code, 2) << run.out;
  EXPECT_NE(run.out.find("--stiffness"), std::string::npos) << run.out;
}

}  // namespace
