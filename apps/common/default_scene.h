// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The scene that `cubespring run` and `cubespring bench-render` play when given none.
#pragma once

#include <string>

#include "cubespring/scene/scene.h"

namespace cubespring::app {

/// Where the default scene and meshes are: $CUBESPRING_DATA_DIR, else the source tree's data/.
std::string data_dir();

/// Reads the scene at `path`, or the default scene (data/scenes/liver_probe.json) when `path` is
/// empty. Errors say which file was missing and how to point at the data folder.
Result<scene::Scene> load_scene_or_default(const std::string& path);

}  // namespace cubespring::app
