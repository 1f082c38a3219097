// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// A simulator's own loop over a scene file, from an installed tree (cubespring::scene): a 4 cm
// cube of tissue written here rests on the table while a capsule probe presses 5 mm into its top;
// the tissue must push the probe back and the organ must stay whole.
#include <cmath>
#include <cstdio>
#include <fstream>

#include <cubespring/scene/scene.h>
#include <cubespring/scene/scene_world.h>

namespace {

void write_cube(const char* path, double side) {
  std::ofstream obj(path);
  for (int k = 0; k < 8; ++k)
    obj << "v " << side * (k & 1) - side / 2 << ' ' << side * ((k >> 1) & 1) - side / 2 << ' ' << side * ((k >> 2) & 1)
        << '\n';
  // two triangles per face, counter-clockwise seen from outside
  obj << "f 1 3 4\nf 1 4 2\nf 5 6 8\nf 5 8 7\nf 1 2 6\nf 1 6 5\n"
         "f 3 7 8\nf 3 8 4\nf 1 5 7\nf 1 7 3\nf 2 4 8\nf 2 8 6\n";
}

}  // namespace

int main() {
  write_cube("organ.obj", 0.04);
  std::ofstream("press.json") << R"({
    "organ": {"mesh": "organ.obj", "cell_size": 0.008},
    "tools": [{"name": "probe", "capsule": {"radius": 0.005, "length": 0.1},
               "keyframes": [{"time": 0.0, "position": [0, 0, 0.045]}, {"time": 0.5, "position": [0, 0, 0.035]}]}],
    "time_step": 0.004, "settle_time": 0.3, "duration": 0.6
  })";
  auto scene = cubespring::scene::load_scene("press.json", "");
  if (!scene) {
    std::puts(scene.message().c_str());
    return 1;
  }
  auto built = cubespring::scene::SceneWorld::create(*scene);
  if (!built) {
    std::puts(built.message().c_str());
    return 1;
  }
  cubespring::scene::SceneWorld& world = **built;
  if (auto settled = cubespring::scene::settle(world, *scene); !settled) {
    std::puts(settled.message().c_str());
    return 1;
  }
  const int steps = static_cast<int>(std::lround(scene->duration / scene->time_step));
  for (int n = 1; n <= steps; ++n) {
    world.place_tools(n * scene->time_step);
    if (auto stepped = world.step(scene->time_step); !stepped) {
      std::puts(stepped.message().c_str());
      return 1;
    }
  }
  const double push = world.world().getContactWrench(world.tools().front().body.get()).force.z();
  if (!(push > 0.01)) {
    std::printf("the tissue pushes the probe up by %g N, expected more than 0.01 N\n", push);
    return 1;
  }
  std::printf("scene consumer: the tissue pushes the probe up by %.3f N\n", push);
  return 0;
}
