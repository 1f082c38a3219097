// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// cubespring voxelize MESH: load a surface file, turn it into cells, and report what a simulation
// of it would hold and every problem found on the way.
#include <cstdio>
#include <iostream>
#include <memory>
#include <set>

#include <nlohmann/json.hpp>

#include "arguments.h"
#include "commands.h"
#include "cubespring/mesh/load_mesh.h"
#include "cubespring/voxelize.h"
#include "json_output.h"
#include "number_checks.h"

namespace cubespring::app {
namespace {

struct VoxelizeCommandOptions {
  std::string mesh;
  std::string cell_size;  // empty: use cells_across
  int cells_across = 32;
  double scale = 1.0;
  std::string rule = "centre";
  double min_fraction = 0.5;
  int samples = 3;
  bool drop_islands = false;
  std::uint64_t max_memory = 0;
  bool json = false;
};

nlohmann::json vector_json(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

nlohmann::json problems_json(const Voxelization& v) {
  return {{"open_edges", v.surface.open_edges},
          {"non_manifold_edges", v.surface.non_manifold_edges},
          {"inconsistent_orientation", v.surface.flipped_triangles},
          {"degenerate_triangles", v.surface.degenerate_triangles},
          {"duplicate_triangles", v.surface.duplicate_triangles},
          {"edge_only_contacts", v.connectivity.edge_only_contacts},
          {"corner_only_contacts", v.connectivity.corner_only_contacts},
          {"islands", v.connectivity.islands},
          {"island_cells", v.connectivity.island_cells},
          {"dropped_cells", v.connectivity.dropped_cells}};
}

nlohmann::json report_json(const VoxelizeCommandOptions& options, const Voxelization& v) {
  nlohmann::json parts = nlohmann::json::array();
  for (const VoxelPart& p : v.parts) {
    parts.push_back(
        {{"name", p.name},
         {"material", p.material_name},
         {"triangles", p.triangles},
         {"mesh_volume", p.mesh_volume},
         {"voxel_volume", p.voxel_volume},
         {"relative_volume_difference", p.mesh_volume > 0 ? p.voxel_volume / p.mesh_volume - 1.0 : 0.0},
         {"cells", p.cells},
         {"merged_into", p.merged_into >= 0 ? nlohmann::json(v.parts[static_cast<std::size_t>(p.merged_into)].name)
                                            : nlohmann::json(nullptr)}});
  }
  return {{"file", options.mesh},
          {"scale", options.scale},
          {"parts", parts},
          {"mesh_volume", v.mesh_volume},
          {"voxel_volume", v.voxel_volume},
          {"relative_volume_difference", v.relative_volume_difference()},
          {"cell_size", vector_json(v.cell_size)},
          {"grid_size", {v.grid_size.x(), v.grid_size.y(), v.grid_size.z()}},
          {"origin", vector_json(v.origin)},
          {"cells", v.cells.size()},
          {"nodes", v.nodes},
          {"springs", v.springs},
          {"memory_estimate_bytes", v.memory_estimate_bytes},
          {"undecided_cells", v.undecided_cells},
          {"problems", problems_json(v)},
          {"warnings", v.warnings}};
}

// Parts that only together with `owner` close a surface (a tool split by material): one line.
void print_merged_parts(const Voxelization& v, int owner) {
  int count = 0;
  int triangles = 0;
  std::set<std::string> materials;
  for (const VoxelPart& p : v.parts) {
    if (p.merged_into != owner) continue;
    ++count;
    triangles += p.triangles;
    materials.insert(p.material_name);
  }
  if (count == 0) return;
  std::string names;
  for (const std::string& m : materials) names += (names.empty() ? "" : ", ") + m;
  std::printf("    + %d more parts (%d triangles; materials %s) close its surface: one solid, its cells\n", count,
              triangles, names.c_str());
}

void print_report(const VoxelizeCommandOptions& options, const TriangleMesh& mesh, const Voxelization& v) {
  std::printf("mesh %s: %zu parts, %d triangles (scale %g)\n", options.mesh.c_str(), v.parts.size(),
              mesh.num_triangles(), options.scale);
  std::printf("  %-20s %-20s %10s %14s %14s %8s %9s\n", "part", "material", "triangles", "mesh [m^3]", "voxels [m^3]",
              "diff", "cells");
  for (const VoxelPart& p : v.parts) {
    const double diff = p.mesh_volume > 0 ? 100.0 * (p.voxel_volume / p.mesh_volume - 1.0) : 0.0;
    if (p.merged_into >= 0) continue;  // summed up under the part whose cells they share
    std::printf("  %-20s %-20s %10d %14.6g %14.6g %+7.2f%% %9d\n", p.name.c_str(), p.material_name.c_str(), p.triangles,
                p.mesh_volume, p.voxel_volume, diff, p.cells);
    print_merged_parts(v, static_cast<int>(&p - v.parts.data()));
  }
  std::printf("mesh volume   %.6g m^3\n", v.mesh_volume);
  std::printf("voxel volume  %.6g m^3 (%+.2f%%)\n", v.voxel_volume, 100.0 * v.relative_volume_difference());
  std::printf("grid          %d x %d x %d cells of %g x %g x %g m, origin (%g, %g, %g) m\n", v.grid_size.x(),
              v.grid_size.y(), v.grid_size.z(), v.cell_size.x(), v.cell_size.y(), v.cell_size.z(), v.origin.x(),
              v.origin.y(), v.origin.z());
  std::printf("body          %zu cells, %d nodes, %d springs\n", v.cells.size(), v.nodes, v.springs);
  std::printf("memory        %.1f MB (estimate)\n", static_cast<double>(v.memory_estimate_bytes) / 1e6);
  if (v.warnings.empty()) {
    std::printf("problems      none\n");
  } else {
    std::printf("problems\n");
    for (const std::string& w : v.warnings) std::printf("  - %s\n", w.c_str());
  }
}

// The voxelizer's options from the flags, or the message of the first flag at fault (the
// command line's fuzz target calls this alone: it reads no mesh).
Result<VoxelizeOptions> plan_voxelize(const VoxelizeCommandOptions& options) {
  VoxelizeOptions voxelize_options;
  if (!options.cell_size.empty()) {
    Result<Eigen::Vector3d> size = parse_sizes("--cell-size", options.cell_size);
    if (!size) return size.status();
    voxelize_options.cell_size = *size;
  } else {
    voxelize_options.cells_across = options.cells_across;
  }
  voxelize_options.rule = options.rule == "fraction" ? CellRule::kCoveredFraction : CellRule::kCentreInside;
  voxelize_options.min_covered_fraction = options.min_fraction;
  voxelize_options.samples_per_axis = options.samples;
  voxelize_options.drop_islands = options.drop_islands;
  voxelize_options.max_memory_bytes = options.max_memory;
  return voxelize_options;
}

int run_voxelize(const VoxelizeCommandOptions& options) {
  Result<VoxelizeOptions> planned = plan_voxelize(options);
  if (!planned) {
    std::cerr << "error: " << planned.message() << "\n";
    return 2;
  }
  const VoxelizeOptions& voxelize_options = planned.value();

  LoadOptions load_options;
  load_options.scale = options.scale;
  Result<TriangleMesh> mesh = load_mesh(options.mesh, load_options);
  if (!mesh) {
    std::cerr << "error: " << mesh.message() << "\n";
    return 2;
  }
  Result<Voxelization> voxels = voxelize(*mesh, voxelize_options);
  if (!voxels) {
    std::cerr << "error: " << options.mesh << ": " << voxels.message() << "\n";
    return 2;
  }
  if (options.json) {
    std::cout << json_text(report_json(options, *voxels)) << "\n";
  } else {
    print_report(options, *mesh, *voxels);
  }
  return 0;
}

}  // namespace

CheckedCommand add_checked_voxelize_command(CLI::App& app) {
  auto options = std::make_shared<VoxelizeCommandOptions>();
  CLI::App* cmd = app.add_subcommand("voxelize",
                                     "Turn a surface mesh file into cube cells and report volumes, "
                                     "counts, memory and the mesh's problems");
  cmd->add_option("mesh", options->mesh, "surface mesh file: OBJ, STL, PLY, OFF, glTF or COLLADA")->required();
  CLI::Option* size = cmd->add_option("--cell-size", options->cell_size, "cell size H or HX,HY,HZ [m]");
  CLI::Option* across =
      cmd->add_option("--cells-across", options->cells_across, "cubic cells, this many along the mesh's longest side")
          ->check(CLI::Range(1, 100000))
          ->capture_default_str();
  size->excludes(across);
  cmd->add_option("--scale", options->scale, "metres per file unit (0.001 for millimetres)")
      ->check(finite_positive_number())
      ->capture_default_str();
  cmd->add_option("--rule", options->rule, "which boundary cells are in: centre (the centre is inside) or fraction")
      ->check(CLI::IsMember({"centre", "fraction"}))
      ->capture_default_str();
  // checked here, so that the errors name the flags before the mesh is read
  cmd->add_option("--min-fraction", options->min_fraction,
                  "rule fraction: the covered fraction a cell needs, in (0, 1]")
      ->check(fraction_number())
      ->capture_default_str();
  cmd->add_option("--samples", options->samples, "rule fraction: samples per cell along each axis, 1..8")
      ->check(CLI::Range(1, 8))
      ->capture_default_str();
  cmd->add_flag("--drop-islands", options->drop_islands, "keep only the largest face-connected piece of cells");
  cmd->add_option("--max-memory", options->max_memory,
                  "refuse grids whose estimate exceeds BYTES (default: half "
                  "of this machine's memory)")
      ->check(byte_count());
  cmd->add_flag("--json", options->json, "print one JSON object on stdout");
  return {[options] { return plan_voxelize(*options).status(); }, [options] { return run_voxelize(*options); }};
}

Command add_voxelize_command(CLI::App& app) { return add_checked_voxelize_command(app).run; }

}  // namespace cubespring::app
