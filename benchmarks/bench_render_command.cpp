// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// cubespring bench-render [SCENE.json]: where the demo's time goes, measured in one run on one
// scene (the default one): the physics as simulated time against wall time, and the renderer's
// frames per second at each picture size, drawing alone and with the PNG written.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench_support.h"
#include "commands.h"
#include "cubespring/bullet/soft_body.h"
#include "cubespring/scene/scene_frames.h"
#include "default_scene.h"
#include "json_output.h"
#include "number_checks.h"

namespace cubespring::app {
namespace {

using Clock = std::chrono::steady_clock;

struct BenchRenderOptions {
  std::string scene;   // empty: the default scene
  int frames = 10;     // timed per picture size
  double seconds = 0;  // simulated for the physics figure [s]; 0: the whole story
  std::string sizes = "640x360;1280x720";
  int threads = 1;  // the organ's force passes (as `run` steps it: 1)
  bool json = false;
};

struct Size {
  int width = 0;
  int height = 0;
};

struct RenderTiming {
  Size size;
  double draw_seconds = 0;  // per frame
  double png_seconds = 0;   // per frame
};

// The organ's sub-steps over the story, by part [s] (bullet::SoftBody::Times).
struct PhysicsParts {
  double elastic = 0;
  double surface = 0;
  double contact = 0;
  double planning = 0;
  long sub_steps = 0;
  double sum() const { return elastic + surface + contact + planning; }
  // the contact issue's measure: contact work (the surface refresh included) over the sub-steps
  double contact_share() const { return sum() > 0 ? (surface + contact) / sum() : 0.0; }
};

// The cells the scene's cutting tools took out over the story, and the time it took [s].
struct Cuts {
  int steps = 0;  // world steps that cut
  int cells = 0;
  double seconds = 0;
  double longest = 0;
  // what a cut adds to the world's time: the cut, and the step after it over the step before it
  // (the body's force engine, contact caches and arrays are made again on its first step)
  double longest_extra = 0;
};

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// "WxH;WxH;..."; an error names --sizes and the part at fault.
Result<std::vector<Size>> parse_picture_sizes(const std::string& text) {
  std::vector<Size> sizes;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = std::min(text.find(';', start), text.size());
    const std::string part = text.substr(start, end - start);
    Size size;
    char tail = 0;
    if (std::sscanf(part.c_str(), "%dx%d%c", &size.width, &size.height, &tail) != 2 || size.width < 16 ||
        size.height < 16 || size.width > 4096 || size.height > 4096) {
      return Status::error("--sizes: '" + part + "' is not WIDTHxHEIGHT with each in [16, 4096] pixels");
    }
    sizes.push_back(size);
    start = end + 1;
  }
  return sizes;
}

// Draws and writes `frames` pictures of the world as it is, timing each part.
Result<RenderTiming> time_render(const scene::Scene& scene, scene::SceneWorld& world, const Eigen::Matrix3Xd& rest,
                                 Size size, int frames, const std::filesystem::path& folder) {
  scene::Scene sized = scene;
  sized.render.width = size.width;
  sized.render.height = size.height;
  Result<scene::SceneFrames> made = scene::SceneFrames::create(sized);
  if (!made) return made.status();
  made->set_rest(rest);
  Result<Image> image = made->render(world, 0.0);  // the first frame builds what later ones reuse
  if (!image) return image.status();
  RenderTiming timing;
  timing.size = size;
  const Clock::time_point drawing = Clock::now();
  for (int f = 0; f < frames; ++f) {
    image = made->render(world, 0.0);
    if (!image) return image.status();
  }
  timing.draw_seconds = seconds_since(drawing) / frames;
  const Clock::time_point writing = Clock::now();
  for (int f = 0; f < frames; ++f) {
    const std::string path = (folder / ("frame_" + std::to_string(f) + ".png")).string();
    if (Status written = write_png(*image, path); !written) return written;
  }
  timing.png_seconds = seconds_since(writing) / frames;
  return timing;
}

int run(const BenchRenderOptions& o) {
  Result<std::vector<Size>> sizes = parse_picture_sizes(o.sizes);
  Result<scene::Scene> loaded = sizes ? load_scene_or_default(o.scene) : Result<scene::Scene>(sizes.status());
  if (!loaded) {
    std::cerr << "error: " << loaded.message() << "\n";
    return sizes ? 1 : 2;
  }
  const scene::Scene& scene = *loaded;
  Result<std::unique_ptr<scene::SceneWorld>> built = scene::SceneWorld::create(scene);
  Status ready = built ? scene::settle(**built, scene) : built.status();
  if (!ready) {
    std::cerr << "error: " << ready.message() << "\n";
    return 1;
  }
  scene::SceneWorld& world = **built;
  if (Status threads = world.organ().set_threads(o.threads); !threads) {
    std::cerr << "error: --threads: " << threads.message() << "\n";
    return 2;
  }
  const Eigen::Matrix3Xd rest = scene::SceneFrames::organ_vertices(world);

  // the story, or its first seconds, as `run` plays it
  const double story = o.seconds > 0 ? o.seconds : scene.duration;
  const int steps = std::max(1, static_cast<int>(std::lround(story / scene.time_step)));
  const bullet::SoftBody::Times before = world.organ().times();
  const Clock::time_point physics = Clock::now();
  Cuts cuts;
  double step_before_cut = 0.0, last_cut = -1.0;  // [s]; no cut waits for its step after
  for (int n = 1; n <= steps; ++n) {
    world.place_tools(n * scene.time_step);
    const Clock::time_point stepping = Clock::now();
    if (Status stepped = world.step(scene.time_step); !stepped) {
      std::cerr << "error: " << stepped.message() << "\n";
      return 1;
    }
    const double step_seconds = seconds_since(stepping);
    if (last_cut >= 0.0) cuts.longest_extra = std::max(cuts.longest_extra, last_cut + step_seconds - step_before_cut);
    last_cut = -1.0;
    // the cutting tools' cells taken out, as `run` does
    const std::vector<scene::ToolCut> due = world.cuts_due();
    if (due.empty()) continue;
    const Clock::time_point cutting = Clock::now();
    Result<bullet::SoftBody::Cut> cut = world.apply_cuts(due);
    if (!cut) {
      std::cerr << "error: " << cut.message() << "\n";
      return 1;
    }
    const double took = seconds_since(cutting);
    ++cuts.steps;
    cuts.cells += cut->removed_cells;
    cuts.seconds += took;
    cuts.longest = std::max(cuts.longest, took);
    cuts.longest_extra = std::max(cuts.longest_extra, took);  // the last step's cut has no step after
    step_before_cut = step_seconds;
    last_cut = took;
  }
  const double physics_wall = seconds_since(physics);
  const double simulated = steps * scene.time_step;
  // the organ's sub-steps by part; the rest is Bullet's own step, the tools and the bookkeeping
  const bullet::SoftBody::Times& after = world.organ().times();
  const PhysicsParts parts{after.elastic - before.elastic, after.surface - before.surface,
                           after.contact - before.contact, after.planning - before.planning,
                           after.sub_steps - before.sub_steps};

  namespace fs = std::filesystem;
  std::error_code error;
  const fs::path folder = fs::temp_directory_path(error) / ("cubespring-bench-render-" + std::to_string(::getpid()));
  fs::create_directories(folder, error);
  std::vector<RenderTiming> timings;
  for (const Size& size : *sizes) {
    Result<RenderTiming> timing = time_render(scene, world, rest, size, o.frames, folder);
    if (!timing) {
      fs::remove_all(folder, error);
      std::cerr << "error: " << timing.message() << "\n";
      return 1;
    }
    timings.push_back(*timing);
  }
  fs::remove_all(folder, error);

  const scene::OrganSummary& organ = world.summary();
  if (o.json) {
    nlohmann::json out;
    out["machine"] = cpu_name();
    out["scene"] = scene.source;
    out["organ"] = {{"cells", organ.cells}, {"nodes", organ.nodes}, {"sub_step", organ.sub_step}};
    out["physics"] = {{"simulated_seconds", simulated},
                      {"wall_seconds", physics_wall},
                      {"real_time_factor", simulated / physics_wall},
                      {"threads", o.threads},
                      {"sub_steps", parts.sub_steps},
                      {"elastic_seconds", parts.elastic},
                      {"surface_seconds", parts.surface},
                      {"contact_seconds", parts.contact},
                      {"planning_seconds", parts.planning},
                      {"other_seconds", physics_wall - parts.sum()},
                      {"contact_share_of_sub_steps", parts.contact_share()},
                      {"cut_steps", cuts.steps},
                      {"cells_removed", cuts.cells},
                      {"cut_seconds", cuts.seconds},
                      {"longest_cut_seconds", cuts.longest},
                      {"longest_cut_extra_seconds", cuts.longest_extra},
                      {"world_step_seconds", scene.time_step}};
    out["render"] = nlohmann::json::array();
    for (const RenderTiming& t : timings) {
      out["render"].push_back({{"width", t.size.width},
                               {"height", t.size.height},
                               {"frames", o.frames},
                               {"draw_ms", 1e3 * t.draw_seconds},
                               {"png_ms", 1e3 * t.png_seconds},
                               {"fps", 1.0 / t.draw_seconds},
                               {"fps_with_png", 1.0 / (t.draw_seconds + t.png_seconds)}});
    }
    std::cout << json_text(out) << "\n";
    return 0;
  }
  std::printf("%s: %d cells, %d nodes, sub-step %.3g ms; %s\n", scene.source.c_str(), organ.cells, organ.nodes,
              1e3 * organ.sub_step, cpu_name().c_str());
  std::printf("physics: %.2f simulated s in %.2f wall s: %.2fx real time on %d thread%s\n", simulated, physics_wall,
              simulated / physics_wall, o.threads, o.threads == 1 ? "" : "s");
  std::printf(
      "  %ld sub-steps: elastic %.0f%%, surface %.0f%%, contact %.0f%%, planning %.0f%%, other %.0f%% "
      "(contact and surface: %.0f%% of the sub-steps)\n",
      parts.sub_steps, 100 * parts.elastic / physics_wall, 100 * parts.surface / physics_wall,
      100 * parts.contact / physics_wall, 100 * parts.planning / physics_wall,
      100 * (physics_wall - parts.sum()) / physics_wall, 100 * parts.contact_share());
  if (cuts.steps > 0) {
    std::printf(
        "  cutting: %d cells in %d steps, %.2f s (in 'other'), the longest cut %.1f ms for world steps of %.1f ms; "
        "with its step after it, at most %.1f ms more than the step before\n",
        cuts.cells, cuts.steps, cuts.seconds, 1e3 * cuts.longest, 1e3 * scene.time_step, 1e3 * cuts.longest_extra);
  }
  std::printf("%-10s %8s %8s %8s %14s\n", "picture", "draw ms", "png ms", "fps", "fps with png");
  for (const RenderTiming& t : timings) {
    char size[32];
    std::snprintf(size, sizeof size, "%dx%d", t.size.width, t.size.height);
    std::printf("%-10s %8.1f %8.1f %8.1f %14.1f\n", size, 1e3 * t.draw_seconds, 1e3 * t.png_seconds,
                1.0 / t.draw_seconds, 1.0 / (t.draw_seconds + t.png_seconds));
  }
  return 0;
}

}  // namespace

Command add_bench_render_command(CLI::App& app) {
  auto options = std::make_shared<BenchRenderOptions>();
  CLI::App* cmd = app.add_subcommand("bench-render",
                                     "Time the demo's parts on one scene: the physics against real "
                                     "time, and frames per second of the renderer at each size");
  cmd->add_option("scene", options->scene, "scene file (JSON, docs/scene-format.md); default: the demo's scene");
  cmd->add_option("--frames", options->frames, "frames timed per picture size")
      ->check(CLI::Range(1, 10000))
      ->capture_default_str();
  cmd->add_option("--seconds", options->seconds,
                  "simulated time for the physics figure [s] (default: the scene's "
                  "whole story, after it settles)")
      ->check(finite_positive_number());
  cmd->add_option("--sizes", options->sizes, "picture sizes WIDTHxHEIGHT;...")->capture_default_str();
  cmd->add_option("--threads", options->threads,
                  "threads of the organ's force passes during the physics figure (after settling; the "
                  "results do not depend on it)")
      ->check(CLI::Range(1, bullet::SoftBody::kMaxThreads))
      ->capture_default_str();
  cmd->add_flag("--json", options->json, "print one JSON object instead of the table");
  return [options] { return run(*options); };
}

}  // namespace cubespring::app
