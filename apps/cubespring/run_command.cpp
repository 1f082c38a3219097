// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// cubespring run [SCENE.json]: the headless surgical demo. Without a scene it plays the default
// one from cubespring's data folder (a probe pressing into a liver with a tumour); it writes
// numbered PNG frames, the tools' contact forces as CSV and a plot of them.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "commands.h"
#include "scene.h"
#include "scene_run.h"

namespace cubespring::app {
namespace {

struct RunCommandOptions {
  std::string scene;  // empty: the default scene
  int frames = 0;     // 0: the scene's
  std::string out;    // empty: the scene's
  int width = 0;      // 0: the scene's
  int height = 0;
};

// Where the default scene and meshes are: $CUBESPRING_DATA_DIR, else the source tree's data/.
std::string data_dir() {
  if (const char* from_environment = std::getenv("CUBESPRING_DATA_DIR"); from_environment && *from_environment) {
    return from_environment;
  }
#ifdef CUBESPRING_DATA_DIR
  return CUBESPRING_DATA_DIR;
#else
  return "";
#endif
}

int run(const RunCommandOptions& options) {
  namespace fs = std::filesystem;
  const std::string data = data_dir();
  std::string path = options.scene;
  if (path.empty()) {
    path = (fs::path(data) / "scenes" / "liver_probe.json").string();
    std::error_code ignored;
    if (data.empty() || !fs::is_regular_file(path, ignored)) {
      std::cerr << "error: no scene given and the default scene " << (data.empty() ? "scenes/liver_probe.json" : path)
                << " was not found; give a scene file, or set CUBESPRING_DATA_DIR to cubespring's data folder\n";
      return 1;
    }
  }
  Result<Scene> loaded = load_scene(path, data);
  if (!loaded) {
    std::cerr << "error: " << loaded.message() << "\n";
    return 1;
  }
  Scene scene = std::move(loaded).value();
  if (options.frames > 0) scene.frames = options.frames;  // same duration, fewer or more pictures
  if (!options.out.empty()) scene.output = options.out;
  if (options.width > 0) scene.render.width = options.width;
  if (options.height > 0) scene.render.height = options.height;

  Result<RunOutput> output = run_scene(scene);
  if (!output) {
    std::cerr << "error: " << output.message() << "\n";
    return 1;
  }
  std::cout << "wrote " << output->frames << " frames, tool_forces.csv and tool_force.png to " << scene.output;
  if (options.out.empty()) {
    std::error_code ignored;
    std::cout << " (" << fs::absolute(scene.output, ignored).lexically_normal().string() << "; --out DIR writes elsewhere)";
  }
  std::cout << "\n";
  return 0;
}

}  // namespace

Command add_run_command(CLI::App& app) {
  auto options = std::make_shared<RunCommandOptions>();
  CLI::App* cmd = app.add_subcommand("run", "Play a scene (default: a probe pressing into a liver, from data/scenes/) "
                                            "and write PNG frames, tool_forces.csv and tool_force.png; "
                                            "`cubespring` alone does the same");
  cmd->add_option("scene", options->scene, "scene file (JSON, docs/scene-format.md)");
  cmd->add_option("--frames", options->frames, "render N frames evenly over the scene's duration")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--out", options->out, "output folder (default: the scene's, cubespring-demo-output)");
  cmd->add_option("--width", options->width, "frame width [pixels]")->check(CLI::PositiveNumber);
  cmd->add_option("--height", options->height, "frame height [pixels]")->check(CLI::PositiveNumber);
  return [options] { return run(*options); };
}

}  // namespace cubespring::app
