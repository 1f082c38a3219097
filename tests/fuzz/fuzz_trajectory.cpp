// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// libFuzzer target: DeviceTrajectory::parse (a haptic device path, docs/haptics.md) on arbitrary
// text. Beyond crashes, hangs and sanitizer faults it stops on a broken rule: an error is one
// short line starting with the file's name; a path that parses has finite samples, times strictly
// increasing, unit quaternions, and plays finite poses anywhere. scripts/fuzz.sh builds and runs it.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "cubespring/haptics/device_trajectory.h"

namespace {

[[noreturn]] void fail(const char* rule, const std::string& detail) {
  std::fprintf(stderr, "fuzz_trajectory: %s: %s\n", rule, detail.c_str());
  std::abort();
}

void check_path(const cubespring::haptics::DeviceTrajectory& path) {
  double last = -INFINITY;
  for (const cubespring::haptics::DeviceSample& sample : path.samples()) {
    if (!(sample.time > last)) fail("times do not increase", std::to_string(sample.time));
    last = sample.time;
    if (!sample.position.allFinite()) fail("a position is not finite", std::to_string(sample.time));
    if (!(std::abs(sample.orientation.norm() - 1.0) < 1e-9)) fail("an orientation is not a unit quaternion", "");
  }
  const double span = path.end_time() - path.start_time();
  for (const double s : {-1.0, 0.0, 0.3, 0.5, 0.999, 1.0, 2.0}) {
    const cubespring::haptics::DeviceState state = path.at(path.start_time() + s * span);
    if (!state.pose.matrix().allFinite() || !state.linear_velocity.allFinite() || !state.angular_velocity.allFinite())
      fail("the path plays a pose that is not finite", std::to_string(s));
  }
}

void check_error(const std::string& message) {
  if (message.rfind("fuzz.csv", 0) != 0) fail("the error does not start with the file's name", message);
  if (message.find('\n') != std::string::npos || message.size() > 300) fail("the error is not one short line", message);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const auto path = cubespring::haptics::DeviceTrajectory::parse(text, "fuzz.csv");
  if (path.ok()) {
    check_path(path.value());
  } else {
    check_error(path.message());
  }
  return 0;
}
