// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Plays a scene to its end: steps the world, records every tool's contact force, renders the
// frames, then plots the forces. What `cubespring run` does once the scene is read.
#pragma once

#include <string>

#include "cubespring/result.h"
#include "cubespring/scene/scene.h"
#include "cubespring/scene/scene_world.h"

namespace cubespring::app {

/// What a finished run wrote, in scene.output.
struct RunOutput {
  int frames = 0;
  std::string csv;   ///< tool_forces.csv
  std::string plot;  ///< tool_force.png
};

/// Runs the scene, the organ's force passes on `threads` threads (its results do not depend on
/// them); progress and a summary of the organ go to stderr. Errors name what failed (a mesh, the
/// output folder, an unstable organ and when).
Result<RunOutput> run_scene(const scene::Scene& scene, int threads = 1);

/// The header of tool_forces.csv (docs/scene-format.md).
extern const char* const kToolForceCsvHeader;

}  // namespace cubespring::app
