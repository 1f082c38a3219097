// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Real-world meshes (../shared/meshes, from the SOFA framework) and the demo's own meshes: loaded
// through assimp and voxelized, with volumes against each mesh's own enclosed volume.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "cubespring/mesh/load_mesh.h"
#include "cubespring/voxelize.h"

namespace cubespring {
namespace {

struct FileCase {
  const char* path;
  int cells_across;
  double volume_tolerance;  ///< on the relative voxel / mesh volume difference
  int open_edges;           ///< as the file has them
};

void expect_voxelizes(const std::string& directory, const FileCase& c) {
  const std::string path = directory + "/" + c.path;
  const Result<TriangleMesh> mesh = load_mesh(path);
  ASSERT_TRUE(mesh.ok()) << mesh.message();
  VoxelizeOptions options;
  options.cells_across = c.cells_across;
  const Result<Voxelization> v = voxelize(*mesh, options);
  ASSERT_TRUE(v.ok()) << path << ": " << v.message();
  EXPECT_GT(v->cells.size(), 100u) << path;
  EXPECT_LT(std::abs(v->relative_volume_difference()), c.volume_tolerance)
      << path << ": voxels " << v->voxel_volume << " m^3, mesh " << v->mesh_volume << " m^3";
  EXPECT_EQ(v->surface.open_edges, c.open_edges) << path;
  if (c.open_edges > 0) {
    EXPECT_FALSE(v->warnings.empty()) << path;
  }
}

TEST(VoxelizeFiles, SharedRealWorldMeshes) {
  const std::string directory = CUBESPRING_SHARED_MESHES_DIR;
  if (!std::filesystem::is_directory(directory)) GTEST_SKIP() << "no shared meshes at " << directory;
  // the stylus is 142 pieces (one per material change) that close one surface together; the
  // dental instrument is a thin tool with 22 open edges: its voxel volume comes down to the
  // mesh's slowly (+24%, +16%, +9% at 300, 400, 600 cells across)
  for (const FileCase& c : {FileCase{"cube.obj", 20, 0.03, 0}, FileCase{"sphere.obj", 20, 0.03, 0},
                            FileCase{"torus.obj", 32, 0.03, 0}, FileCase{"liver.obj", 32, 0.03, 0},
                            FileCase{"stylus.obj", 64, 0.03, 4}, FileCase{"dental_instrument.obj", 400, 0.2, 22}}) {
    expect_voxelizes(directory, c);
  }
}

TEST(VoxelizeFiles, DemoOrganAndProbe) {
  expect_voxelizes(CUBESPRING_DATA_DIR, {"liver.obj", 32, 0.03, 0});
  // the probe is 5 mm thick and 0.2 m long: 300 cells across make it 7.5 cells thick
  expect_voxelizes(CUBESPRING_DATA_DIR, {"probe.obj", 300, 0.03, 0});
}

}  // namespace
}  // namespace cubespring
