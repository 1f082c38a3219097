// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "default_scene.h"

#include <cstdlib>
#include <filesystem>

namespace cubespring::app {

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

Result<scene::Scene> load_scene_or_default(const std::string& path) {
  namespace fs = std::filesystem;
  const std::string data = data_dir();
  if (!path.empty()) return scene::load_scene(path, data);
  const std::string default_path = (fs::path(data) / "scenes" / "liver_probe.json").string();
  std::error_code ignored;
  if (data.empty() || !fs::is_regular_file(default_path, ignored)) {
    return Status::error("no scene given and the default scene " +
                         (data.empty() ? std::string("scenes/liver_probe.json") : default_path) +
                         " was not found; give a scene file, or set CUBESPRING_DATA_DIR to cubespring's data folder");
  }
  return scene::load_scene(default_path, data);
}

}  // namespace cubespring::app
