// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// cubespring bench-voxelize: time to load a mesh file and voxelize it, beside the time assimp alone
// takes to read the same file, so that the cost over assimp is measured in one run ("Mesh to
// tissue": 100k triangles at 128 cells across in under 2 s).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Exporter.hpp>
#include <assimp/Importer.hpp>
#include <nlohmann/json.hpp>

#include "bench_support.h"
#include "commands.h"
#include "cubespring/mesh/load_mesh.h"
#include "cubespring/shapes.h"
#include "cubespring/voxelize.h"
#include "json_output.h"
#include "step_timing.h"

namespace cubespring::app {
namespace {

using Clock = std::chrono::steady_clock;

constexpr double kMajorRadius = 0.1;   // [m] an organ-sized torus
constexpr double kMinorRadius = 0.04;  // [m]
// load_mesh's post-processing (plugins/mesh/src/load_mesh.cpp), so that "assimp alone" does the same work
constexpr unsigned kLoadMeshSteps = aiProcess_ValidateDataStructure | aiProcess_Triangulate | aiProcess_SortByPType;
// the target: this many triangles at this many cells across in under kTargetSeconds
constexpr int kTargetTriangles = 100000;
constexpr int kTargetCellsAcross = 128;
constexpr double kTargetSeconds = 2.0;

struct BenchVoxelizeOptions {
  std::vector<int> triangles{1000, 100000, 1000000};
  std::vector<int> cells_across{32, 64, 128};
  double min_seconds = 0.3;  // per measurement
  bool json = false;
  std::string keep;  // directory for the generated files; empty: a temporary one, removed after
};

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

struct TorusSize {
  int around = 0;
  int tube = 0;
  int triangles() const { return 2 * around * tube; }
};

// around x tube with 2 * around * tube = triangles and around about 1.5 tube (the ring longer
// than the tube is round), exactly when a divisor pair is close enough, else the nearest count.
TorusSize torus_size(int triangles) {
  constexpr double kAspect = 1.5;
  TorusSize best;
  double best_distance = std::log(2.0);  // accept around / tube within [0.75, 3] of kAspect
  const auto consider = [&](long around, long tube) {
    if (around < 3 || tube < 3) return;
    const double distance = std::abs(std::log(static_cast<double>(around) / static_cast<double>(tube) / kAspect));
    if (distance < best_distance) {
      best_distance = distance;
      best = {static_cast<int>(around), static_cast<int>(tube)};
    }
  };
  if (triangles % 2 == 0) {
    const long half = triangles / 2;
    for (long d = 1; d * d <= half; ++d) {
      if (half % d != 0) continue;
      consider(half / d, d);
      consider(d, half / d);
    }
  }
  if (best.around > 0) return best;
  const int tube = std::max(3, static_cast<int>(std::lround(std::sqrt(triangles / (2.0 * kAspect)))));
  const int around = std::max(3, static_cast<int>(std::lround(triangles / (2.0 * tube))));
  return {around, tube};
}

// Writes the mesh as binary PLY through assimp's own exporter (an aiScene of one mesh, one
// material and a root node), so the file is one assimp certainly reads back.
void write_binary_ply(const TriangleMesh& mesh, const std::string& path) {
  aiScene scene;  // its destructor deletes the node, meshes and materials given to it
  scene.mRootNode = new aiNode("torus");
  scene.mRootNode->mNumMeshes = 1;
  scene.mRootNode->mMeshes = new unsigned[1]{0};
  scene.mNumMaterials = 1;
  scene.mMaterials = new aiMaterial* [1] { new aiMaterial() };
  auto* out = new aiMesh();
  scene.mNumMeshes = 1;
  scene.mMeshes = new aiMesh* [1] { out };
  // triangles share vertices: saying so lets the exporter's own steps handle the indexed mesh
  scene.mFlags |= AI_SCENE_FLAGS_NON_VERBOSE_FORMAT;

  out->mName = aiString("torus");
  out->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
  out->mMaterialIndex = 0;
  out->mNumVertices = static_cast<unsigned>(mesh.num_vertices());
  out->mVertices = new aiVector3D[out->mNumVertices];
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    const Eigen::Vector3d p = mesh.vertices.col(v);
    out->mVertices[v] =
        aiVector3D(static_cast<ai_real>(p.x()), static_cast<ai_real>(p.y()), static_cast<ai_real>(p.z()));
  }
  out->mNumFaces = static_cast<unsigned>(mesh.num_triangles());
  out->mFaces = new aiFace[out->mNumFaces];
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    aiFace& face = out->mFaces[t];
    face.mNumIndices = 3;
    face.mIndices = new unsigned[3];
    for (int corner = 0; corner < 3; ++corner) face.mIndices[corner] = static_cast<unsigned>(mesh.triangles(corner, t));
  }

  Assimp::Exporter exporter;
  if (exporter.Export(&scene, "plyb", path) != AI_SUCCESS) {
    throw std::runtime_error(path + ": assimp cannot write it: " + exporter.GetErrorString());
  }
}

// The directory the files go to; a temporary one is removed when this goes out of scope,
// whether the run ends normally or with an error.
class FileDirectory {
 public:
  explicit FileDirectory(const std::string& keep) : remove_(keep.empty()) {
    std::error_code error;
    if (!keep.empty()) {
      path_ = keep;
      std::filesystem::create_directories(path_, error);
      if (error || !std::filesystem::is_directory(path_)) {
        throw std::runtime_error("--keep " + keep + ": cannot create the directory" +
                                 (error ? ": " + error.message() : std::string()));
      }
      return;
    }
    const std::filesystem::path base = std::filesystem::temp_directory_path(error);
    if (error) throw std::runtime_error("no temporary directory: " + error.message());
    std::random_device random;
    for (int attempt = 0; attempt < 100; ++attempt) {
      std::filesystem::path candidate = base / ("cubespring-bench-voxelize-" + std::to_string(random()));
      if (std::filesystem::create_directory(candidate, error)) {
        path_ = candidate;
        return;
      }
    }
    throw std::runtime_error("cannot create a temporary directory in " + base.string());
  }
  ~FileDirectory() {
    std::error_code ignored;
    if (remove_ && !path_.empty()) std::filesystem::remove_all(path_, ignored);
  }
  FileDirectory(const FileDirectory&) = delete;
  FileDirectory& operator=(const FileDirectory&) = delete;

  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  bool remove_;
};

struct Row {
  int triangles = 0;
  int cells_across = 0;
  double assimp_read = 0, load = 0, voxelize = 0;  // [s] per call
  long cells = 0;
  double relative_volume_difference = 0;
  double total() const { return load + voxelize; }
  double ratio() const { return total() / assimp_read; }
};

void check_options(const BenchVoxelizeOptions& o) {
  if (o.triangles.empty() || o.cells_across.empty()) {
    throw std::runtime_error("--triangles and --cells-across each need at least one value");
  }
  for (const int n : o.triangles) {
    if (n < 18)
      throw std::runtime_error("--triangles " + std::to_string(n) + ": each count must be >= 18 (a 3 x 3 torus)");
  }
  for (const int n : o.cells_across) {
    if (n < 1) throw std::runtime_error("--cells-across " + std::to_string(n) + ": each count must be >= 1");
  }
  if (!(o.min_seconds >= 0.0) || !std::isfinite(o.min_seconds)) {
    throw std::runtime_error("--min-seconds " + std::to_string(o.min_seconds) + " must be a finite number >= 0");
  }
}

// Rows for one file: assimp alone, load_mesh, then voxelize at each cells-across.
std::vector<Row> bench_file(const std::string& path, int triangles, const BenchVoxelizeOptions& o) {
  // a call that alone takes min_seconds or more is timed once: the million-triangle cases take
  // about that long, and a warm-up would double the run
  const auto time_per_call = [&](const std::function<void()>& fn) {
    return app::time_per_call(o.min_seconds, fn, FirstCall::kTimedIfLong);
  };
  const double assimp_read = time_per_call([&] {
    // a new importer per call, as load_mesh makes one per call
    Assimp::Importer importer;
    const aiScene* scene = importer.ReadFile(path, kLoadMeshSteps);
    if (scene == nullptr) throw std::runtime_error(path + ": assimp cannot read it: " + importer.GetErrorString());
  });
  TriangleMesh mesh;
  const double load = time_per_call([&] {
    Result<TriangleMesh> loaded = load_mesh(path);
    if (!loaded) throw std::runtime_error(loaded.message());
    mesh = std::move(loaded).value();
  });
  if (mesh.num_triangles() != triangles) {
    throw std::runtime_error(path + ": load_mesh gives " + std::to_string(mesh.num_triangles()) +
                             " triangles, the file was written with " + std::to_string(triangles));
  }
  std::vector<Row> rows;
  for (const int across : o.cells_across) {
    Row row;
    row.triangles = triangles;
    row.cells_across = across;
    row.assimp_read = assimp_read;
    row.load = load;
    VoxelizeOptions voxelize_options;
    voxelize_options.cells_across = across;
    row.voxelize = time_per_call([&] {
      Result<Voxelization> voxels = voxelize(mesh, voxelize_options);
      if (!voxels)
        throw std::runtime_error(path + " at " + std::to_string(across) + " cells across: " + voxels.message());
      row.cells = static_cast<long>(voxels->cells.size());
      row.relative_volume_difference = voxels->relative_volume_difference();
    });
    rows.push_back(row);
    if (!o.json) std::fprintf(stderr, "benched %d triangles at %d cells across\n", triangles, across);
  }
  return rows;
}

void print_table(const std::vector<Row>& rows, const BenchVoxelizeOptions& o) {
  const std::string cpu = cpu_name();
  std::printf("machine: %s, %u hardware threads\n", cpu.empty() ? "unknown CPU" : cpu.c_str(),
              std::thread::hardware_concurrency());
  std::printf(
      "torus R = %g m, r = %g m written as binary PLY by assimp; times per call in ms (mean over >= %.1f s;\n"
      "a call that alone takes longer is timed once)\n",
      kMajorRadius, kMinorRadius, o.min_seconds);
  std::printf("%10s %6s | %10s %10s %11s %10s %8s | %9s %8s\n", "triangles", "across", "assimp_ms", "load_ms",
              "voxelize_ms", "total_ms", "ratio", "cells", "vol_err%");
  for (const Row& r : rows) {
    std::printf("%10d %6d | %10.2f %10.2f %11.2f %10.2f %8.2f | %9ld %8.3f\n", r.triangles, r.cells_across,
                1e3 * r.assimp_read, 1e3 * r.load, 1e3 * r.voxelize, 1e3 * r.total(), r.ratio(), r.cells,
                100.0 * r.relative_volume_difference);
  }
  std::printf(
      "assimp: Importer::ReadFile with load_mesh's post-processing; load: load_mesh (assimp, conversion,\n"
      "joined vertices, validation); total: load + voxelize; ratio: total / assimp;\n"
      "vol_err%%: (voxel volume - mesh volume) / mesh volume.\n");
  for (const Row& r : rows) {
    if (r.triangles != kTargetTriangles || r.cells_across != kTargetCellsAcross) continue;
    std::printf("target: 100k triangles at 128 cells across in < %g s: %.3f s (%s)\n", kTargetSeconds, r.total(),
                r.total() < kTargetSeconds ? "met" : "NOT met");
  }
}

int run_bench_voxelize(const BenchVoxelizeOptions& o) {
  std::vector<Row> rows;
  try {
    check_options(o);
    const FileDirectory directory(o.keep);
    for (const int requested : o.triangles) {
      const TorusSize size = torus_size(requested);
      const TriangleMesh torus = torus_mesh(kMajorRadius, kMinorRadius, size.around, size.tube);
      const std::string path = (directory.path() / ("torus_" + std::to_string(size.triangles()) + ".ply")).string();
      const auto write_start = Clock::now();
      write_binary_ply(torus, path);
      if (!o.json) {
        std::fprintf(stderr, "wrote %s: %d x %d torus, %d triangles%s, in %.2f s\n", path.c_str(), size.around,
                     size.tube, size.triangles(),
                     size.triangles() == requested ? "" : " (the nearest to the count asked)",
                     seconds_since(write_start));
      }
      for (Row& row : bench_file(path, size.triangles(), o)) rows.push_back(row);
    }
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  }

  if (o.json) {
    nlohmann::json out = nlohmann::json::array();
    for (const Row& r : rows) {
      out.push_back({{"triangles", r.triangles},
                     {"cells_across", r.cells_across},
                     {"assimp_read_s", r.assimp_read},
                     {"load_s", r.load},
                     {"voxelize_s", r.voxelize},
                     {"total_s", r.total()},
                     {"ratio_to_assimp", r.ratio()},
                     {"cells", r.cells},
                     {"relative_volume_difference", r.relative_volume_difference}});
    }
    std::cout << json_text(out) << "\n";
    return 0;
  }
  print_table(rows, o);
  return 0;
}

}  // namespace

Command add_bench_voxelize_command(CLI::App& app) {
  auto options = std::make_shared<BenchVoxelizeOptions>();
  CLI::App* cmd = app.add_subcommand(
      "bench-voxelize", "Time loading and voxelizing torus meshes, beside assimp alone reading the same files");
  cmd->add_option("--triangles", options->triangles, "triangle counts of the torus meshes, separated by ','")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--cells-across", options->cells_across, "cells along the longest side, separated by ','")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--min-seconds", options->min_seconds, "time each measurement at least this long [s]")
      ->capture_default_str();
  cmd->add_flag("--json", options->json, "print a JSON array instead of the table");
  cmd->add_option("--keep", options->keep,
                  "write the mesh files to this directory and keep them (default: a temporary one)");
  return [options] { return run_bench_voxelize(*options); };
}

}  // namespace cubespring::app
