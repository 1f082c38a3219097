// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// libFuzzer target: parse_scene on arbitrary text, as if it were a file in the tree's
// data/scenes/ (so the committed meshes resolve, as they do for the demo's scenes). Beyond crashes, hangs and sanitizer
// faults, it stops on a broken message rule (docs/scene-format.md): an error must be one or two lines naming the file,
// and a scene that parses must hold only finite numbers. scripts/fuzz.sh builds and runs it.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "cubespring/scene/scene.h"

#ifndef CUBESPRING_DATA_DIR
#error "build with -DCUBESPRING_DATA_DIR=\"path/to/data\""
#endif

namespace {

[[noreturn]] void fail(const char* rule, const std::string& detail) {
  std::fprintf(stderr, "fuzz_scene: %s: %s\n", rule, detail.c_str());
  std::abort();
}

void check_error(const std::string& message) {
  if (message.rfind("fuzz.json", 0) != 0) fail("the error does not start with the file's name", message);
  std::size_t lines = 1;
  for (const char c : message) lines += c == '\n' ? 1 : 0;
  // a long line is an echo of the input, not a message
  if (lines > 2 || message.size() > 600) fail("the error is longer than two short lines", message);
}

void check_finite(const char* key, double value) {
  if (!std::isfinite(value)) fail("a scene that parses holds a number that is not finite", key);
}

void check_scene(const cubespring::scene::Scene& scene) {
  check_finite("time_step", scene.time_step);
  check_finite("settle_time", scene.settle_time);
  check_finite("duration", scene.duration);
  check_finite("frame_rate", scene.frame_rate);
  check_finite("gravity", scene.gravity.sum());
  check_finite("organ.scale", scene.organ.scale);
  check_finite("organ.cell_size", scene.organ.cell_size);
  check_finite("organ.friction", scene.organ.friction);
  check_finite("organ.contact_offset", scene.organ.contact_offset);
  check_finite("organ.max_added_mass", scene.organ.max_added_mass);
  check_finite("organ.time_step_safety", scene.organ.time_step_safety);
  for (const auto& [name, material] : scene.organ.materials) {
    check_finite("organ.materials young", material.young_modulus);
    check_finite("organ.materials poisson", material.poisson_ratio);
    check_finite("organ.materials density", material.density);
  }
  for (const cubespring::scene::Box& box : scene.organ.fixed_regions)
    check_finite("fixed", box.lower.sum() + box.upper.sum());
  check_finite("table.height", scene.table.height);
  check_finite("table.half_size", scene.table.half_size);
  for (const cubespring::scene::ToolSpec& tool : scene.tools) {
    check_finite("tools.scale", tool.scale);
    check_finite("tools.mass", tool.mass);
    if (tool.capsule) check_finite("tools.capsule", tool.capsule->radius + tool.capsule->length);
    for (const cubespring::scene::Keyframe& key : tool.keyframes) {
      check_finite("tools.keyframes", key.time + key.position.sum() + key.orientation.coeffs().sum());
    }
  }
  check_finite("render.ambient", scene.render.ambient);
  check_finite("render.colour_range", scene.render.colour_range);
  check_finite("render.strain_range", scene.render.strain_range);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const cubespring::scene::SceneContext context{"fuzz.json", CUBESPRING_DATA_DIR "/scenes", CUBESPRING_DATA_DIR};
  const cubespring::Result<cubespring::scene::Scene> scene = cubespring::scene::parse_scene(text, context);
  if (scene.ok()) {
    check_scene(scene.value());
  } else {
    check_error(scene.message());
  }
  return 0;
}
