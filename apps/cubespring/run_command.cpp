// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// cubespring run [SCENE.json]: the headless surgical demo. Without a scene it plays the default
// one from cubespring's data folder (a probe pressing into a liver with a tumour); it writes
// numbered PNG frames, the tools' contact forces as CSV and a plot of them.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "commands.h"
#include "cubespring/bullet/soft_body.h"
#include "default_scene.h"
#include "scene_run.h"

namespace cubespring::app {
namespace {

struct RunCommandOptions {
  std::string scene;  // empty: the default scene
  int frames = 0;     // 0: the scene's
  std::string out;    // empty: the scene's
  int width = 0;      // 0: the scene's
  int height = 0;
  int threads = 1;  // the organ's force passes
};

int run(const RunCommandOptions& options) {
  namespace fs = std::filesystem;
  Result<scene::Scene> loaded = load_scene_or_default(options.scene);
  if (!loaded) {
    std::cerr << "error: " << loaded.message() << "\n";
    return 1;
  }
  scene::Scene scene = std::move(loaded).value();
  if (options.frames > 0) scene.frames = options.frames;  // same duration, fewer or more pictures
  if (!options.out.empty()) scene.output = options.out;
  if (options.width > 0) scene.render.width = options.width;
  if (options.height > 0) scene.render.height = options.height;

  Result<RunOutput> output = run_scene(scene, options.threads);
  if (!output) {
    std::cerr << "error: " << output.message() << "\n";
    return 1;
  }
  std::cout << "wrote " << output->frames << (output->frames == 1 ? " frame" : " frames")
            << ", tool_forces.csv and tool_force.png to " << scene.output;
  if (options.out.empty()) {
    std::error_code ignored;
    std::cout << " (" << fs::absolute(scene.output, ignored).lexically_normal().string()
              << "; --out DIR writes elsewhere)";
  }
  std::cout << "\n";
  return 0;
}

}  // namespace

Command add_run_command(CLI::App& app) {
  auto options = std::make_shared<RunCommandOptions>();
  CLI::App* cmd = app.add_subcommand("run",
                                     "Play a scene (default: a probe pressing into a liver, from data/scenes/) "
                                     "and write PNG frames, tool_forces.csv and tool_force.png; "
                                     "`cubespring` alone does the same");
  cmd->add_option("scene", options->scene, "scene file (JSON, docs/scene-format.md)");
  cmd->add_option("--frames", options->frames, "render N frames evenly over the scene's duration")
      ->check(CLI::Range(1, 1000000));  // as the scene's "frames"
  cmd->add_option("--out", options->out, "output folder (default: the scene's, cubespring-demo-output)");
  cmd->add_option("--width", options->width, "frame width [pixels]")->check(CLI::Range(1, 16384));
  cmd->add_option("--height", options->height, "frame height [pixels]")->check(CLI::Range(1, 16384));
  cmd->add_option("--threads", options->threads,
                  "threads of the organ's force passes; the frames and forces do not depend on it")
      ->check(CLI::Range(1, bullet::SoftBody::kMaxThreads))
      ->capture_default_str();
  return [options] { return run(*options); };
}

}  // namespace cubespring::app
