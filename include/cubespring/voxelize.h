// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "cubespring/lattice.h"
#include "cubespring/result.h"
#include "cubespring/surface_repair.h"
#include "cubespring/triangle_mesh.h"

/// Units are SI throughout the API: metres, kilograms, seconds, newtons, pascals.
namespace cubespring {

/// Which boundary cells are in (docs/voxelize.md, section 4).
enum class CellRule {
  kCentreInside,     ///< the cell's centre is inside the surface (default: unbiased volume, fastest)
  kCoveredFraction,  ///< at least min_covered_fraction of samples_per_axis^3 points in the cell are inside
};

struct VoxelizeOptions {
  /// Cell size (hx, hy, hz) [m], each > 0; used when cells_across is 0.
  Eigen::Vector3d cell_size{0.0, 0.0, 0.0};
  /// When > 0: cubic cells, cells_across of them along the longest side of the mesh's bounding box.
  int cells_across = 0;
  CellRule rule = CellRule::kCentreInside;
  double min_covered_fraction = 0.5;  ///< kCoveredFraction: in (0, 1]
  int samples_per_axis = 3;           ///< kCoveredFraction: 1..8
  bool drop_islands = false;          ///< keep only the largest face-connected piece of cells
  /// Refuse grids whose memory estimate exceeds this [bytes]; 0 means half the machine's memory.
  std::uint64_t max_memory_bytes = 0;
};

/// Cells that make unstable or floating pieces (docs/voxelize.md, section 5).
struct CellConnectivity {
  int edge_only_contacts = 0;    ///< cell pairs that share an edge but no face path around it: a hinge
  int corner_only_contacts = 0;  ///< cell pairs that share only a corner: a ball joint
  int islands = 0;               ///< face-connected pieces besides the largest
  int island_cells = 0;          ///< cells in those pieces
  int dropped_cells = 0;         ///< cells removed by drop_islands
};

/// One part of the mesh in the voxels.
struct VoxelPart {
  std::string name;
  std::string material_name;
  int triangles = 0;          ///< after repair
  double mesh_volume = 0.0;   ///< enclosed by the part's surface [m^3]
  double voxel_volume = 0.0;  ///< cells whose inside test says this part, before the inner part wins [m^3]
  int cells = 0;              ///< cells given this part (the inner part wins) after island removal
  /// -1, or the part whose cells this part's surface encloses: parts sharing edges form one
  /// solid (pieces of a tool split by material), labelled by its first part, which carries
  /// the volumes and cells.
  int merged_into = -1;
};

/// A voxelized mesh: the occupied cells of a grid, the part each belongs to, and a report.
struct Voxelization {
  Eigen::Vector3d origin{0, 0, 0};     ///< grid node (0,0,0) [m]: a multiple of the cell size
  Eigen::Vector3d cell_size{0, 0, 0};  ///< [m]
  Eigen::Vector3i grid_size{0, 0, 0};  ///< cells along x, y, z that the grid spans
  std::vector<Eigen::Vector3i> cells;  ///< occupied cells by grid index, x fastest
  std::vector<int> cell_part;          ///< part index of each cell: the smallest solid containing it

  std::vector<VoxelPart> parts;
  SurfaceProblems surface;
  CellConnectivity connectivity;
  double mesh_volume = 0.0;                 ///< parts' volumes, less those of parts lying inside another [m^3]
  double voxel_volume = 0.0;                ///< number of cells times the cell volume [m^3]
  int nodes = 0;                            ///< nodes of the lattice these cells make
  int springs = 0;                          ///< springs of that lattice (edges shared by cells count once)
  int undecided_cells = 0;                  ///< samples (cells, under the centre rule) the axis rays could not
                                            ///< settle, settled by the winding number
  std::uint64_t memory_estimate_bytes = 0;  ///< the simulated body these cells make (Model, State) [bytes]
  std::vector<std::string> warnings;        ///< problems that did not stop voxelizing

  double relative_volume_difference() const {
    return mesh_volume > 0.0 ? (voxel_volume - mesh_volume) / mesh_volume : 0.0;
  }
};

/// Turns a closed surface (one or more parts) into cells. The inside test casts rays along the
/// three grid axes and counts signed crossings exactly, with a vote between the axes and the
/// generalized winding number where the rays disagree (docs/voxelize.md). A cell inside several
/// parts belongs to the one with the smallest volume: a tumour inside a liver stays a tumour.
/// Errors name the value at fault: the cell size, the memory estimate against its limit, a mesh
/// with no triangles or no volume, a surface too open for the inside test to decide.
Result<Voxelization> voxelize(const TriangleMesh& mesh, const VoxelizeOptions& options);

/// A lattice of the voxelized cells with one material per part (part_materials has one entry per
/// part of the voxelization) and the given cell model.
LatticeDesc lattice_from_voxels(const Voxelization& voxels, const std::vector<Material>& part_materials,
                                CellModel model = CellModel::kBaudet2007);

/// Bytes a lattice of these counts takes once built (Model and State), for memory limits.
std::uint64_t estimate_body_bytes(std::uint64_t cells, std::uint64_t nodes, std::uint64_t springs);

/// Half the physical memory of this machine [bytes]: the default memory limit.
std::uint64_t default_memory_limit();

}  // namespace cubespring
