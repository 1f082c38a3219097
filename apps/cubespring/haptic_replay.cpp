// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "haptic_replay.h"

#include <pthread.h>
#include <sched.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <thread>
#include <vector>

#include "cubespring/haptics/coupled_tool.h"
#include "cubespring/haptics/device_link.h"
#include "cubespring/render/force_plot.h"
#include "cubespring/render/image.h"
#include "cubespring/scene/scene_world.h"

namespace cubespring::app {

const char* const kDeviceForceCsvHeader =
    "time_s,force_x_N,force_y_N,force_z_N,torque_x_Nm,torque_y_Nm,torque_z_Nm,device_x_m,device_y_m,device_z_m,"
    "tool_x_m,tool_y_m,tool_z_m";

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

Clock::time_point after(Clock::time_point start, double seconds) {
  return start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
}

// One period of the device loop, as the device saw it.
struct DeviceRow {
  double time = 0.0;  // since the replay started [s]
  haptics::Wrench felt;
  Eigen::Vector3d device{0, 0, 0};
  Eigen::Vector3d tool{0, 0, 0};  // the tool's tip where the simulation last left it
};

// The device's servo loop: wakes at each period, reads the path at the wall clock's time as a
// device reads its encoders, exchanges with the simulation and keeps the row. It allocates
// nothing while it runs (the rows are reserved).
void run_device_loop(const haptics::DeviceTrajectory& path, haptics::DeviceLink& link,
                     const haptics::VirtualCoupling& coupling, double rate, double duration, Clock::time_point start,
                     const std::atomic<bool>& stop, std::vector<DeviceRow>& rows) {
  const double period = 1.0 / rate;
  for (long k = 0; !stop.load(std::memory_order_relaxed); ++k) {
    std::this_thread::sleep_until(after(start, static_cast<double>(k) * period));
    const double t = seconds_since(start);
    if (t > duration || rows.size() == rows.capacity()) return;
    // after a stall, the next wake-up is the next period's, not a burst of the missed ones
    k = std::max(k, static_cast<long>(t / period));
    haptics::DeviceState device = path.at(path.start_time() + t);
    device.time = t;
    DeviceRow row;
    row.time = t;
    row.felt = link.exchange(device);
    row.device = device.pose.translation();
    if (const std::optional<haptics::PublishedTool> tool = link.tool())
      row.tool = (tool->body.pose * coupling.tool().tip).translation();
    rows.push_back(row);
  }
}

LoopTiming timing_of(const std::vector<DeviceRow>& rows, double rate) {
  LoopTiming timing;
  timing.nominal = 1.0 / rate;
  std::vector<double> periods;
  for (size_t i = 1; i < rows.size(); ++i) periods.push_back(rows[i].time - rows[i - 1].time);
  timing.periods = static_cast<int>(periods.size());
  if (periods.empty()) return timing;
  for (const double p : periods) {
    timing.mean += p / static_cast<double>(periods.size());
    timing.later_than_1_5_periods += p > 1.5 * timing.nominal;
    timing.later_than_5_periods += p > 5.0 * timing.nominal;
  }
  std::sort(periods.begin(), periods.end());
  timing.longest = periods.back();
  timing.percentile99 =
      periods[std::min(periods.size() - 1, static_cast<size_t>(0.99 * static_cast<double>(periods.size())))];
  return timing;
}

Status write_outputs(const std::vector<DeviceRow>& rows, const std::string& out, ReplayResult& result) {
  std::error_code error;
  fs::create_directories(out, error);
  if (error) return Status::error("cannot create the output folder " + out + ": " + error.message());
  result.csv = (fs::path(out) / "device_forces.csv").string();
  std::ofstream csv(result.csv);
  if (!csv) return Status::error("cannot write " + result.csv);
  csv << kDeviceForceCsvHeader << "\n";
  ForceSeries series{"device", {}, {}};
  for (const DeviceRow& row : rows) {
    char line[400];
    std::snprintf(line, sizeof line, "%.6f,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", row.time,
                  row.felt.force.x(), row.felt.force.y(), row.felt.force.z(), row.felt.torque.x(), row.felt.torque.y(),
                  row.felt.torque.z(), row.device.x(), row.device.y(), row.device.z(), row.tool.x(), row.tool.y(),
                  row.tool.z());
    csv << line;
    series.time.push_back(row.time);
    series.magnitude.push_back(row.felt.force.norm());
  }
  if (!csv.flush()) return Status::error("cannot write " + result.csv);
  result.plot = (fs::path(out) / "device_force.png").string();
  if (Status s = write_png(plot_forces({series}), result.plot); !s) return s;
  return {};
}

}  // namespace

Result<ReplayResult> replay_device_path(const scene::Scene& scene, const haptics::DeviceTrajectory& path,
                                        const ReplayOptions& options, const std::string& out) {
  if (scene.tools.empty()) return Status::error(scene.source + ": the scene has no tool for the device to drive");
  const auto chosen = options.tool.empty()
                          ? scene.tools.begin()
                          : std::find_if(scene.tools.begin(), scene.tools.end(),
                                         [&](const scene::ToolSpec& t) { return t.name == options.tool; });
  if (chosen == scene.tools.end()) {
    std::string names;
    for (const scene::ToolSpec& t : scene.tools) names += (names.empty() ? "" : ", ") + t.name;
    return Status::error("--tool " + options.tool + ": " + scene.source + " has no such tool (it has " + names + ")");
  }
  Result<std::unique_ptr<scene::SceneWorld>> created = scene::SceneWorld::create(scene);
  if (!created) return created.status();
  scene::SceneWorld& world = **created;
  if (Status s = world.organ().set_threads(options.threads); !s) return s;
  if (Status s = settle(world, scene); !s) return s;

  scene::SceneTool* taken = world.take_tool(chosen->name);
  if (taken == nullptr) return Status::error("tool \"" + chosen->name + "\": not in the scene's world");
  Result<haptics::CoupledTool> coupled = haptics::CoupledTool::create(world.world(), *taken->body, chosen->mass,
                                                                      taken->shape_offset.inverse(), options.coupling);
  if (!coupled) return Status::error("tool \"" + chosen->name + "\": " + coupled.message());
  haptics::CoupledTool& tool = *coupled;
  // the world's step: the scene's, split until the coupling is stable at it
  ReplayResult result;
  constexpr double kMostSplits = 1000;  // a step of a microsecond for the demo's 4 ms: a coupling far too stiff
  const double splits = std::ceil(scene.time_step / tool.coupling().longest_stable_step());
  result.world_step = scene.time_step / std::clamp(splits, 1.0, kMostSplits);
  if (Status s = tool.coupling().check_step(result.world_step); !s) return s;

  haptics::DeviceLink link(tool.coupling());
  tool.place_at(path.at(path.start_time()));
  link.publish_tool(tool.state(), 0.0);
  const double duration = options.duration > 0 ? options.duration : path.end_time() - path.start_time();
  // the rows are kept in memory (about 100 bytes a period) so that the loop never allocates
  constexpr double kMostPeriods = 1e7;
  if (!(duration * options.rate <= kMostPeriods)) {
    char what[160];
    std::snprintf(what, sizeof what, "%.4g s at %.4g Hz (--duration, --rate) are %.4g device periods, more than %.0e",
                  duration, options.rate, duration * options.rate, kMostPeriods);
    return Status::error(std::string(what) + ": play a shorter stretch of the path");
  }
  std::vector<DeviceRow> rows;
  rows.reserve(static_cast<size_t>(duration * options.rate) + 16);
  std::atomic<bool> stop{false};
  const Clock::time_point start = after(Clock::now(), 0.01);
  std::thread device_thread(run_device_loop, std::cref(path), std::ref(link), std::cref(tool.coupling()), options.rate,
                            duration, start, std::cref(stop), std::ref(rows));
  // whatever ends the simulation's loop (an exception too) stops the device's first
  struct Joined {
    std::atomic<bool>& stop;
    std::thread& thread;
    ~Joined() {
      stop = true;
      if (thread.joinable()) thread.join();
    }
  } joined{stop, device_thread};
  // a device's servo loop runs at real-time priority where the system allows it (root, or
  // CAP_SYS_NICE): the simulation's thread then cannot delay its wake-ups; else it runs as is
  sched_param priority{};
  priority.sched_priority = sched_get_priority_min(SCHED_FIFO) + 10;
  result.device.real_time_priority = pthread_setschedparam(device_thread.native_handle(), SCHED_FIFO, &priority) == 0;

  Status failed;
  std::this_thread::sleep_until(start);
  double t = 0.0;
  while (t < duration) {
    // at the wall clock's pace: a step starts once its start time has come
    std::this_thread::sleep_until(after(start, t));
    const Clock::time_point began = Clock::now();
    world.place_tools(t + result.world_step);  // the others follow their key frames
    tool.couple(link.device().value_or(path.at(path.start_time())));
    failed = world.step(result.world_step);
    result.physics_wall += seconds_since(began);
    if (!failed) break;
    t += result.world_step;
    ++result.world_steps;
    link.publish_tool(tool.state(), t);
    result.most_behind = std::max(result.most_behind, seconds_since(start) - t);
  }
  stop = true;
  device_thread.join();  // the rows are the device thread's until it has ended
  result.simulated = t;
  const bool real_time = result.device.real_time_priority;
  result.device = timing_of(rows, options.rate);
  result.device.real_time_priority = real_time;
  const Status written = write_outputs(rows, out, result);
  if (!failed) {
    char when[64];
    std::snprintf(when, sizeof when, " (at t = %.3f s of the device path", t);
    return Status::error(failed.message() + when +
                         (written ? "; the device's rows until then are in " + result.csv + ")" : std::string(")")));
  }
  if (!written) return written;
  return result;
}

}  // namespace cubespring::app
