// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// cubespring haptic-replay TRAJECTORY.csv [SCENE.json]: a recorded haptic device path played
// against a scene in real time (docs/haptics.md). The named tool follows the device through a
// virtual coupling; the device's force at its rate goes to device_forces.csv and a plot, and the
// loop's timing to stdout.
#include <iostream>
#include <memory>
#include <string>

#include "commands.h"
#include "cubespring/bullet/soft_body.h"
#include "default_scene.h"
#include "haptic_replay.h"
#include "json_output.h"

namespace cubespring::app {
namespace {

struct ReplayCommandOptions {
  std::string trajectory;
  std::string scene;  // empty: the default scene
  std::string out = "cubespring-haptics-output";
  ReplayOptions replay;
  bool json = false;
};

void print_table(const ReplayResult& r, double rate) {
  const LoopTiming& d = r.device;
  std::printf("device loop at %.0f Hz: %d periods, mean %.3f ms, 99th percentile %.3f ms, longest %.3f ms\n", rate,
              d.periods, 1e3 * d.mean, 1e3 * d.percentile99, 1e3 * d.longest);
  std::printf("  later than 1.5 periods: %d (%.2f%%), later than 5 periods: %d; thread priority %s\n",
              d.later_than_1_5_periods, d.periods > 0 ? 100.0 * d.later_than_1_5_periods / d.periods : 0.0,
              d.later_than_5_periods,
              d.real_time_priority ? "real-time (SCHED_FIFO)" : "normal (real-time not allowed)");
  std::printf(
      "simulation: %d world steps of %.3f ms over %.3f s, physics %.3f s (%.2fx real time), at most %.1f ms "
      "behind the wall clock\n",
      r.world_steps, 1e3 * r.world_step, r.simulated, r.physics_wall,
      r.physics_wall > 0 ? r.simulated / r.physics_wall : 0.0, 1e3 * r.most_behind);
  std::printf("wrote %s and %s\n", r.csv.c_str(), r.plot.c_str());
}

nlohmann::json json_of(const ReplayResult& r, double rate) {
  const LoopTiming& d = r.device;
  return {{"device",
           {{"rate_hz", rate},
            {"periods", d.periods},
            {"mean_period_s", d.mean},
            {"percentile99_period_s", d.percentile99},
            {"longest_period_s", d.longest},
            {"later_than_1_5_periods", d.later_than_1_5_periods},
            {"later_than_5_periods", d.later_than_5_periods},
            {"real_time_priority", d.real_time_priority}}},
          {"simulation",
           {{"world_steps", r.world_steps},
            {"world_step_s", r.world_step},
            {"simulated_s", r.simulated},
            {"physics_wall_s", r.physics_wall},
            {"most_behind_s", r.most_behind}}},
          {"csv", r.csv},
          {"plot", r.plot}};
}

int run(const ReplayCommandOptions& options) {
  Result<haptics::DeviceTrajectory> path = haptics::DeviceTrajectory::load(options.trajectory);
  if (!path) {
    std::cerr << "error: " << path.message() << "\n";
    return 1;
  }
  Result<scene::Scene> scene = load_scene_or_default(options.scene);
  if (!scene) {
    std::cerr << "error: " << scene.message() << "\n";
    return 1;
  }
  Result<ReplayResult> result = replay_device_path(*scene, *path, options.replay, options.out);
  if (!result) {
    std::cerr << "error: " << result.message() << "\n";
    return 1;
  }
  if (options.json) {
    std::cout << json_text(json_of(*result, options.replay.rate)) << "\n";
  } else {
    print_table(*result, options.replay.rate);
  }
  return 0;
}

}  // namespace

Command add_haptic_replay_command(CLI::App& app) {
  auto options = std::make_shared<ReplayCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "haptic-replay",
      "Play a recorded haptic device path (CSV: time_s,x_m,y_m,z_m,qw,qx,qy,qz) against a scene in real time: a "
      "tool follows the device through a virtual coupling; writes device_forces.csv at the device's rate, a plot, "
      "and the loop's timing");
  cmd->add_option("trajectory", options->trajectory, "the device path, e.g. data/haptics/press_drag_release.csv")
      ->required();
  cmd->add_option("scene", options->scene, "scene file (default: the demo's, data/scenes/liver_probe.json)");
  cmd->add_option("--tool", options->replay.tool, "the scene's tool the device drives (default: the first)");
  cmd->add_option("--rate", options->replay.rate, "the device loop's rate [Hz]")
      ->check(CLI::Range(10.0, 20000.0))
      ->capture_default_str();
  cmd->add_option("--out", options->out, "output folder")->capture_default_str();
  cmd->add_option("--stiffness", options->replay.coupling.stiffness, "the coupling's stiffness [N/m]")
      ->check(CLI::Range(1.0, 1e6))
      ->capture_default_str();
  cmd->add_option("--damping-ratio", options->replay.coupling.damping_ratio,
                  "the coupling's damping ratio with the tool's mass (1: critical)")
      ->check(CLI::Range(0.0, 100.0))
      ->capture_default_str();
  cmd->add_option("--force-limit", options->replay.coupling.force_limit, "the most force the device renders [N]")
      ->check(CLI::Range(1e-3, 1e4))
      ->capture_default_str();
  cmd->add_option("--duration", options->replay.duration,
                  "seconds to play (default: the path's; after its end the device holds still)")
      ->check(CLI::Range(1e-3, 86400.0));
  cmd->add_option("--threads", options->replay.threads, "threads of the organ's force passes")
      ->check(CLI::Range(1, bullet::SoftBody::kMaxThreads))
      ->capture_default_str();
  cmd->add_flag("--json", options->json, "print one JSON object instead of the table");
  return [options] { return run(*options); };
}

}  // namespace cubespring::app
