// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Surface to cells (docs/voxelize.md): repair, grid, inside test per part, parts to cells,
// connectivity report.
#include "cubespring/voxelize.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

#include <unistd.h>

#include <Eigen/Geometry>

#include "voxelize/axis_rays.h"
#include "voxelize/cell_connectivity.h"
#include "voxelize/sample_grid.h"
#include "voxelize/winding_number.h"

namespace cubespring {

using voxelize_detail::AxisVotes;
using voxelize_detail::CellGrid;
using voxelize_detail::SampleGrid;

namespace {

// Where the axis rays disagree, the winding number of every undecided sample is summed over all
// triangles of the part; past this many triangle visits the surface is too open to voxelize.
constexpr double kWindingBudget = 2e8;
// A winding number this far from both 0 and 1 means the point is in the mouth of a hole.
constexpr double kAmbiguousBand = 0.25;
// Voxelizing fails when more of the surface cells than this are ambiguous.
constexpr double kMaxAmbiguousFraction = 0.05;

std::string describe_vector(const Eigen::Vector3d& v) {
  std::ostringstream out;
  out << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")";
  return out.str();
}

Status check_options(const VoxelizeOptions& options) {
  if (options.cells_across < 0) {
    return Status::error("cells across = " + std::to_string(options.cells_across) + " must be > 0");
  }
  if (options.cells_across == 0 && !(options.cell_size.array() > 0.0).all()) {
    return Status::error("cell size " + describe_vector(options.cell_size) +
                         " m: each side must be > 0 (or give a number of cells across)");
  }
  if (!options.cell_size.allFinite()) {
    return Status::error("cell size " + describe_vector(options.cell_size) + " m is not finite");
  }
  if (options.rule == CellRule::kCoveredFraction) {
    if (!(options.min_covered_fraction > 0.0 && options.min_covered_fraction <= 1.0)) {
      return Status::error("covered fraction " + std::to_string(options.min_covered_fraction) + " must be in (0, 1]");
    }
    if (options.samples_per_axis < 1 || options.samples_per_axis > 8) {
      return Status::error("samples per axis " + std::to_string(options.samples_per_axis) + " must be in 1..8");
    }
  }
  return {};
}

// Bounding box of the vertices the triangles use.
void triangle_bounds(const TriangleMesh& mesh, Eigen::Vector3d& low, Eigen::Vector3d& high) {
  low.setConstant(std::numeric_limits<double>::infinity());
  high.setConstant(-std::numeric_limits<double>::infinity());
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    for (int corner = 0; corner < 3; ++corner) {
      const auto v = mesh.vertices.col(mesh.triangles(corner, t));
      low = low.cwiseMin(v);
      high = high.cwiseMax(v);
    }
  }
}

// The inside decision of every sample for one part: axis votes, then the winding number where
// they tie. Counts the samples it had to settle and those still ambiguous.
struct PartSamples {
  std::vector<std::uint8_t> inside;
  int undecided = 0;
  int ambiguous = 0;
};

Result<PartSamples> inside_samples(const Eigen::Matrix3Xd& vertices, const Eigen::Matrix3Xi& triangles,
                                   const std::string& name, const SampleGrid& grid, int open_edges) {
  AxisVotes votes(grid.count());
  for (int axis = 0; axis < 3; ++axis) voxelize_detail::cast_axis_rays(vertices, triangles, grid, axis, votes);
  PartSamples result;
  result.inside.assign(static_cast<std::size_t>(grid.count()), 0);
  std::vector<std::int64_t> undecided;
  for (std::int64_t s = 0; s < grid.count(); ++s) {
    const int in = votes.inside[static_cast<std::size_t>(s)];
    const int out = votes.outside(s);
    if (in != out) {
      result.inside[static_cast<std::size_t>(s)] = in > out ? 1 : 0;
    } else {
      undecided.push_back(s);
    }
  }
  result.undecided = static_cast<int>(undecided.size());
  if (static_cast<double>(undecided.size()) * static_cast<double>(triangles.cols()) > kWindingBudget) {
    std::ostringstream out;
    out << "the surface is too open for the inside test: rays through its holes leave " << undecided.size()
        << " samples of part '" << name << "' undecided (the surface has " << open_edges
        << " open edges); close the holes or use a coarser cell size";
    return Status::error(out.str());
  }
  for (const std::int64_t s : undecided) {
    const int i = static_cast<int>(s % grid.size.x());
    const int j = static_cast<int>((s / grid.size.x()) % grid.size.y());
    const int k = static_cast<int>(s / (std::int64_t{grid.size.x()} * grid.size.y()));
    const double w = std::abs(voxelize_detail::winding_number(vertices, triangles, grid.centre(i, j, k)));
    result.inside[static_cast<std::size_t>(s)] = w >= 0.5 ? 1 : 0;
    if (std::abs(w - 0.5) < 0.5 - kAmbiguousBand) ++result.ambiguous;
  }
  return result;
}

// Samples to cells: a cell is in when its centre sample is (one sample per cell), or when enough
// of its samples are.
std::vector<std::uint8_t> cells_from_samples(const std::vector<std::uint8_t>& sample_inside, const SampleGrid& samples,
                                             const Eigen::Vector3i& cells, int per_axis, double min_fraction) {
  if (per_axis == 1) return sample_inside;
  std::vector<int> count(static_cast<std::size_t>(cells.prod()), 0);
  for (int k = 0; k < samples.size.z(); ++k) {
    for (int j = 0; j < samples.size.y(); ++j) {
      for (int i = 0; i < samples.size.x(); ++i) {
        if (!sample_inside[static_cast<std::size_t>(samples.index(i, j, k))]) continue;
        ++count[static_cast<std::size_t>(i / per_axis + cells.x() * (j / per_axis + cells.y() * (k / per_axis)))];
      }
    }
  }
  const double needed = min_fraction * per_axis * per_axis * per_axis;
  std::vector<std::uint8_t> inside(count.size());
  for (std::size_t c = 0; c < count.size(); ++c) inside[c] = count[c] >= needed - 1e-9 ? 1 : 0;
  return inside;
}

// Occupied cells with an empty face neighbour.
int surface_cell_count(const CellGrid& grid) {
  int count = 0;
  for (int k = 0; k < grid.size.z(); ++k)
    for (int j = 0; j < grid.size.y(); ++j)
      for (int i = 0; i < grid.size.x(); ++i)
        if (grid.occupied(i, j, k) &&
            (!grid.occupied(i - 1, j, k) || !grid.occupied(i + 1, j, k) || !grid.occupied(i, j - 1, k) ||
             !grid.occupied(i, j + 1, k) || !grid.occupied(i, j, k - 1) || !grid.occupied(i, j, k + 1)))
          ++count;
  return count;
}

void add_surface_warnings(const SurfaceProblems& problems, std::vector<std::string>& warnings) {
  const auto warn = [&](int count, const char* what) {
    if (count > 0) warnings.push_back(std::to_string(count) + " " + what);
  };
  warn(problems.open_edges, "open edges (holes): the inside test voted past them");
  warn(problems.non_manifold_edges, "non-manifold edges (used by three triangles or more)");
  warn(problems.flipped_triangles, "triangles with inconsistent orientation, turned outward");
  warn(problems.degenerate_triangles, "degenerate triangles (zero area), dropped");
  warn(problems.duplicate_triangles, "duplicated triangles, dropped");
}

void add_connectivity_warnings(const CellConnectivity& c, std::vector<std::string>& warnings) {
  if (c.edge_only_contacts > 0) {
    warnings.push_back(std::to_string(c.edge_only_contacts) + " cell pairs joined only by an edge (hinges)");
  }
  if (c.corner_only_contacts > 0) {
    warnings.push_back(std::to_string(c.corner_only_contacts) + " cell pairs joined only by a corner");
  }
  if (c.islands > 0) {
    warnings.push_back(std::to_string(c.islands) + " islands of " + std::to_string(c.island_cells) +
                       " cells disconnected from the main body" +
                       (c.dropped_cells > 0 ? " (dropped)" : " (keep them fixed, or drop islands)"));
  }
}

}  // namespace

std::uint64_t estimate_body_bytes(std::uint64_t cells, std::uint64_t nodes, std::uint64_t springs) {
  // bytes per item of Model, State and the force workspace (docs/data-layout.md), rounded up
  constexpr std::uint64_t kPerCell = 560;
  constexpr std::uint64_t kPerSpring = 160;
  constexpr std::uint64_t kPerNode = 200;
  return cells * kPerCell + springs * kPerSpring + nodes * kPerNode;
}

std::uint64_t default_memory_limit() {
  const long pages = sysconf(_SC_PHYS_PAGES);
  const long page_size = sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page_size <= 0) return std::uint64_t{4} << 30;  // unknown: 4 GiB
  return static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page_size) / 2;
}

Result<Voxelization> voxelize(const TriangleMesh& input, const VoxelizeOptions& options) {
  if (Status status = validate(input); !status) return status;
  if (Status status = check_options(options); !status) return status;
  if (input.num_triangles() == 0) return Status::error("the mesh has no triangles");

  Voxelization result;
  // a mesh that repeats its vertices per triangle (STL, or a simulator's own arrays) would have
  // no shared edges to orient by
  const RepairedSurface repaired = repair_surface(join_identical_vertices(input));
  const TriangleMesh& mesh = repaired.mesh;
  result.surface = repaired.problems;
  if (mesh.num_triangles() == 0) {
    return Status::error("the mesh has no triangles with an area (" +
                         std::to_string(repaired.problems.degenerate_triangles) + " degenerate)");
  }
  Eigen::Vector3d low;
  Eigen::Vector3d high;
  triangle_bounds(mesh, low, high);
  const double longest = (high - low).maxCoeff();
  const double total_part_volume = std::accumulate(repaired.solid_volume.begin(), repaired.solid_volume.end(), 0.0);
  if (!std::isfinite(longest * longest * longest) || !std::isfinite(total_part_volume)) {
    std::ostringstream out;
    out << "the mesh spans " << describe_vector(high - low)
        << " m: its volume is out of the range of double (is its scale, metres per file unit, right?)";
    return Status::error(out.str());
  }
  if (!(longest > 0.0) || total_part_volume <= 1e-9 * longest * longest * longest) {
    std::ostringstream out;
    out << "the mesh encloses no volume (" << total_part_volume << " m^3 in a bounding box of "
        << describe_vector(high - low) << " m): a flat or open surface cannot be filled with cells";
    return Status::error(out.str());
  }

  // grid: aligned with the world origin, one empty cell of margin around the mesh
  result.cell_size =
      options.cells_across > 0 ? Eigen::Vector3d::Constant(longest / options.cells_across) : options.cell_size;
  const Eigen::Vector3d first = (low.array() / result.cell_size.array()).floor() - 1.0;
  const Eigen::Vector3d last = (high.array() / result.cell_size.array()).ceil() + 1.0;
  const Eigen::Vector3d span = last - first;
  const int per_axis = options.rule == CellRule::kCoveredFraction ? options.samples_per_axis : 1;
  const double samples_per_cell = std::pow(per_axis, 3);
  const double grid_cells = span.prod();
  // working bytes per grid cell: votes (2 per sample), inside flags (1 per sample, 2 live), the
  // cell label and the island pieces; then the body, from the mesh's volume
  const double working_bytes = grid_cells * (4.0 * samples_per_cell + 2.0 + 4.0 + 1.0);
  const double expected_cells = total_part_volume / result.cell_size.prod();
  const double estimate = working_bytes + static_cast<double>(estimate_body_bytes(1, 1, 7)) * expected_cells;
  const std::uint64_t limit = options.max_memory_bytes > 0 ? options.max_memory_bytes : default_memory_limit();
  if (!(estimate <= static_cast<double>(limit)) || span.maxCoeff() > 1e6) {
    std::ostringstream out;
    out << "a grid of " << span.x() << " x " << span.y() << " x " << span.z() << " cells of "
        << describe_vector(result.cell_size) << " m needs about " << estimate / 1e6 << " MB, over the memory limit of "
        << static_cast<double>(limit) / 1e6
        << (options.max_memory_bytes > 0 ? " MB given" : " MB (half of this machine's memory)")
        << ": use a larger cell size or fewer cells across";
    return Status::error(out.str());
  }
  // the grid's cells and samples are indexed by int
  if (grid_cells * samples_per_cell > static_cast<double>(std::numeric_limits<int>::max())) {
    std::ostringstream out;
    out << "a grid of " << span.x() << " x " << span.y() << " x " << span.z() << " cells of "
        << describe_vector(result.cell_size) << " m with " << samples_per_cell
        << " samples a cell has more samples than int indices address (2^31 - 1): use a larger cell size or "
           "fewer cells across";
    return Status::error(out.str());
  }
  result.grid_size = span.cast<int>();
  result.origin = first.cwiseProduct(result.cell_size);
  SampleGrid samples;
  samples.origin = result.origin;
  samples.spacing = result.cell_size / per_axis;
  samples.size = result.grid_size * per_axis;
  samples.origin_index = (first * per_axis).cast<std::int64_t>();

  // the inside test solid by solid, the largest first, so that a smaller solid inside wins; a
  // solid's cells take the part of its first part
  const std::vector<MeshPart>& parts = mesh.parts;
  const std::size_t solid_count = repaired.solid_parts.size();
  std::vector<int> order(solid_count);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return repaired.solid_volume[static_cast<std::size_t>(a)] > repaired.solid_volume[static_cast<std::size_t>(b)];
  });
  if (parts.size() > 32000) {
    return Status::error("the mesh has " + std::to_string(parts.size()) + " parts; at most 32000 are supported");
  }
  CellGrid grid;
  grid.size = result.grid_size;
  grid.label.assign(static_cast<std::size_t>(grid.size.prod()), -1);
  std::vector<std::vector<std::int64_t>> solid_cells(solid_count);  // grid indices, ascending
  result.parts.resize(parts.size());
  int ambiguous = 0;
  for (const int solid : order) {
    const std::vector<int>& members = repaired.solid_parts[static_cast<std::size_t>(solid)];
    const int owner = members.front();
    Eigen::Matrix3Xi triangles(3, 0);
    for (const int p : members) {
      const MeshPart& part = parts[static_cast<std::size_t>(p)];
      triangles.conservativeResize(3, triangles.cols() + part.triangle_count);
      triangles.rightCols(part.triangle_count) = mesh.triangles.middleCols(part.first_triangle, part.triangle_count);
    }
    Result<PartSamples> solid_samples = inside_samples(
        mesh.vertices, triangles, parts[static_cast<std::size_t>(owner)].name, samples, result.surface.open_edges);
    if (!solid_samples) return solid_samples.status();
    result.undecided_cells += solid_samples->undecided;
    ambiguous += solid_samples->ambiguous;
    const std::vector<std::uint8_t> inside =
        cells_from_samples(solid_samples->inside, samples, grid.size, per_axis, options.min_covered_fraction);
    std::vector<std::int64_t>& cells_of_solid = solid_cells[static_cast<std::size_t>(solid)];
    for (std::size_t c = 0; c < inside.size(); ++c) {
      if (!inside[c]) continue;
      grid.label[c] = static_cast<std::int16_t>(owner);
      cells_of_solid.push_back(static_cast<std::int64_t>(c));
    }
    const auto count = static_cast<int>(cells_of_solid.size());
    for (const int p : members) {
      VoxelPart& report = result.parts[static_cast<std::size_t>(p)];
      report.name = parts[static_cast<std::size_t>(p)].name;
      report.material_name = parts[static_cast<std::size_t>(p)].material_name;
      report.triangles = parts[static_cast<std::size_t>(p)].triangle_count;
      report.merged_into = p == owner ? -1 : owner;
      if (p != owner) continue;
      report.mesh_volume = repaired.solid_volume[static_cast<std::size_t>(solid)];
      report.voxel_volume = count * result.cell_size.prod();
    }
  }

  const int surface_cells = surface_cell_count(grid);
  // ambiguous samples counted as cells' worth (a cell holds per_axis^3 samples)
  const double ambiguous_cells = ambiguous / samples_per_cell;
  if (ambiguous_cells > kMaxAmbiguousFraction * (surface_cells + ambiguous_cells)) {
    std::ostringstream out;
    out << "the inside test cannot decide: " << ambiguous << " samples have a winding number between " << kAmbiguousBand
        << " and " << 1.0 - kAmbiguousBand << " (against " << surface_cells
        << " cells on the body's surface); the surface has " << result.surface.open_edges
        << " open edges: close its holes";
    return Status::error(out.str());
  }
  add_surface_warnings(result.surface, result.warnings);

  result.connectivity = voxelize_detail::analyse_connectivity(grid, options.drop_islands);
  add_connectivity_warnings(result.connectivity, result.warnings);

  // a solid lying inside another (all its cells in the other's) is not counted twice in the volume
  result.mesh_volume = 0.0;
  for (std::size_t a = 0; a < solid_count; ++a) {
    bool nested = false;
    for (std::size_t b = 0; b < solid_count && !nested; ++b) {
      if (b == a || repaired.solid_volume[b] <= repaired.solid_volume[a]) continue;
      // both lists ascend: a's cells all in b's
      nested = !solid_cells[a].empty() && std::includes(solid_cells[b].begin(), solid_cells[b].end(),
                                                        solid_cells[a].begin(), solid_cells[a].end());
    }
    if (!nested) result.mesh_volume += repaired.solid_volume[a];
  }

  for (int k = 0; k < grid.size.z(); ++k) {
    for (int j = 0; j < grid.size.y(); ++j) {
      for (int i = 0; i < grid.size.x(); ++i) {
        const std::int16_t label = grid.label[grid.index(i, j, k)];
        if (label < 0) continue;
        result.cells.emplace_back(i, j, k);
        result.cell_part.push_back(label);
        ++result.parts[static_cast<std::size_t>(label)].cells;
      }
    }
  }
  if (result.cells.empty()) {
    return Status::error("no cell is inside the mesh at cell size " + describe_vector(result.cell_size) +
                         " m: the shape is thinner than a cell; use a smaller cell size");
  }
  result.voxel_volume = static_cast<double>(result.cells.size()) * result.cell_size.prod();
  voxelize_detail::count_nodes_and_springs(grid, result.nodes, result.springs);
  result.memory_estimate_bytes = estimate_body_bytes(result.cells.size(), static_cast<std::uint64_t>(result.nodes),
                                                     static_cast<std::uint64_t>(result.springs));
  return result;
}

LatticeDesc lattice_from_voxels(const Voxelization& voxels, const std::vector<Material>& part_materials,
                                CellModel model) {
  LatticeDesc desc;
  desc.cell_size = voxels.cell_size;
  desc.origin = voxels.origin;
  desc.cells = voxels.cells;
  desc.materials = part_materials;
  desc.cell_material = voxels.cell_part;
  desc.model = model;
  return desc;
}

}  // namespace cubespring
