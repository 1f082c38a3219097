// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Builds the flat arrays of a Model from a set of cells: nodes shared by touching cells, edge
// springs shared by up to four cells (stiffness summed), four body diagonals per cell.
#include "cubespring/model.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <numeric>
#include <sstream>
#include <utility>

#include "model/cell_geometry.h"
#include "model/neo_hookean_cell.h"
#include "model/node_copies.h"

namespace cubespring {
namespace {

// Grid indices are packed into one sortable key; 21 bits per axis allow +-1e6 cells.
constexpr std::int64_t kAxisBits = 21;
constexpr std::int64_t kAxisOffset = std::int64_t{1} << (kAxisBits - 1);
constexpr int kMaxGridIndex = static_cast<int>(kAxisOffset) - 2;

// Keys sort major_axis-major, the axis after it fastest (Model::major_axis), so that node order
// follows the memory order of a box's grid.
std::int64_t grid_key(const Eigen::Vector3i& index, int major_axis) {
  const int fast = (major_axis + 1) % 3, middle = (major_axis + 2) % 3;
  return ((index[major_axis] + kAxisOffset) << (2 * kAxisBits)) | ((index[middle] + kAxisOffset) << kAxisBits) |
         (index[fast] + kAxisOffset);
}
Eigen::Vector3i grid_index_of_key(std::int64_t key, int major_axis) {
  const std::int64_t mask = (std::int64_t{1} << kAxisBits) - 1;
  Eigen::Vector3i index;
  index[(major_axis + 1) % 3] = static_cast<int>((key & mask) - kAxisOffset);
  index[(major_axis + 2) % 3] = static_cast<int>(((key >> kAxisBits) & mask) - kAxisOffset);
  index[major_axis] = static_cast<int>((key >> (2 * kAxisBits)) - kAxisOffset);
  return index;
}

// The axis along which the cells' bounding box has the most nodes (z, then y, on a tie), if the
// layers across it hold kMinMajorLayerNodes or more; else z (Model::major_axis).
int choose_major_axis(const std::vector<Eigen::Vector3i>& cells) {
  Eigen::Vector3i lower = cells.front(), upper = lower;
  for (const Eigen::Vector3i& cell : cells) {
    lower = lower.cwiseMin(cell);
    upper = upper.cwiseMax(cell);
  }
  const Eigen::Vector3d nodes = (upper - lower).cast<double>().array() + 2.0;
  int longest = 2;
  for (int axis : {1, 0}) {
    if (nodes[axis] > nodes[longest]) longest = axis;
  }
  return nodes.prod() / nodes[longest] >= kMinMajorLayerNodes ? longest : 2;
}

Status check_desc(const LatticeDesc& desc) {
  if (!desc.cell_size.allFinite() || desc.cell_size.minCoeff() <= 0.0) {
    std::ostringstream message;
    message << "cell_size = (" << desc.cell_size.transpose() << ") m: each side must be > 0";
    return Status::error(message.str());
  }
  if (!desc.origin.allFinite()) return Status::error("origin is not finite");
  if (desc.cells.empty()) return Status::error("the lattice has no cells");
  if (desc.cells.size() > kMaxCells) {
    return Status::error("the lattice has " + std::to_string(desc.cells.size()) + " cells: a body may have at most " +
                         std::to_string(kMaxCells) + " (its springs are indexed by int)");
  }
  // the cell volume and the stiffnesses come from products of the sizes
  if (!std::isnormal(desc.cell_size.prod())) {
    std::ostringstream message;
    message << "cell_size = (" << desc.cell_size.transpose() << ") m: the cell volume " << desc.cell_size.prod()
            << " m^3 is out of the range of double";
    return Status::error(message.str());
  }
  if (desc.materials.empty()) return Status::error("the lattice has no material");
  for (std::size_t m = 0; m < desc.materials.size(); ++m) {
    if (Status status = validate(desc.materials[m]); !status) {
      return Status::error("material " + std::to_string(m) + ": " + status.message());
    }
  }
  if (!desc.cell_material.empty() && desc.cell_material.size() != desc.cells.size()) {
    return Status::error("cell_material has " + std::to_string(desc.cell_material.size()) + " entries for " +
                         std::to_string(desc.cells.size()) + " cells");
  }
  for (std::size_t c = 0; c < desc.cell_material.size(); ++c) {
    const int m = desc.cell_material[c];
    if (m < 0 || m >= static_cast<int>(desc.materials.size())) {
      return Status::error("cell " + std::to_string(c) + " refers to material " + std::to_string(m) +
                           ", but there are " + std::to_string(desc.materials.size()));
    }
  }
  for (std::size_t c = 0; c < desc.cells.size(); ++c) {
    if (desc.cells[c].cwiseAbs().maxCoeff() > kMaxGridIndex) {
      return Status::error("cell " + std::to_string(c) + " has a grid index beyond +-" + std::to_string(kMaxGridIndex));
    }
  }
  return {};
}

// Sorts records (each with a node0 in [0, num_nodes)) by `less`, which orders by node0 first: a
// counting sort by node0, then each node's few records sorted on their own. The same order as
// std::sort for a `less` under which no two records are equal, in linear time (the full sort of
// a body's edges took a third of build_model(), which a cut runs again).
template <typename Record, typename Less>
void sort_by_first_node(std::vector<Record>& records, int num_nodes, Less less) {
  std::vector<int> first(static_cast<std::size_t>(num_nodes) + 1, 0);
  for (const Record& record : records) ++first[static_cast<std::size_t>(record.node0) + 1];
  for (std::size_t n = 0; n < static_cast<std::size_t>(num_nodes); ++n) first[n + 1] += first[n];
  std::vector<Record> sorted(records.size());
  std::vector<int> fill(first.begin(), first.end() - 1);
  for (const Record& record : records)
    sorted[static_cast<std::size_t>(fill[static_cast<std::size_t>(record.node0)]++)] = record;
  for (std::size_t n = 0; n < static_cast<std::size_t>(num_nodes); ++n)
    std::sort(sorted.begin() + first[n], sorted.begin() + first[n + 1], less);
  records = std::move(sorted);
}

// The sorted lists merged into one sorted list, pairwise (as many passes as the log of their count).
template <std::size_t Count>
std::vector<std::int64_t> merged(const std::array<std::vector<std::int64_t>, Count>& lists) {
  std::vector<std::vector<std::int64_t>> round(lists.begin(), lists.end());
  while (round.size() > 1) {
    std::vector<std::vector<std::int64_t>> next;
    for (std::size_t i = 0; i + 1 < round.size(); i += 2) {
      std::vector<std::int64_t> both(round[i].size() + round[i + 1].size());
      std::merge(round[i].begin(), round[i].end(), round[i + 1].begin(), round[i + 1].end(), both.begin());
      next.push_back(std::move(both));
    }
    if (round.size() % 2 == 1) next.push_back(std::move(round.back()));
    round = std::move(next);
  }
  return round.front();
}

struct EdgeRecord {
  int node0, node1;
  int cell, slot;  // slot: the edge's place in the cell's 12, axis * 4 + rank of its lower corner
  double stiffness, damping;
};

}  // namespace

std::uint64_t Model::next_revision() {
  // one counter for the process: two models never share a revision unless one is the other's copy
  static std::atomic<std::uint64_t> next{1};
  return next.fetch_add(1, std::memory_order_relaxed);
}

void Model::mark_changed() { revision = next_revision(); }

LatticeDesc lattice_desc(const Model& model) {
  LatticeDesc desc;
  desc.cell_size = model.cell_size;
  desc.origin = model.origin;
  desc.cells = model.cell_grid_index;
  desc.materials = model.materials;
  desc.cell_material = model.cell_material;
  desc.model = model.cell_model;
  desc.exact_bending = model.exact_bending;
  desc.law = model.cell_law;
  desc.split_faces = model.split_faces;
  return desc;
}

void update_grid_layout(Model& model, double /*min_fill*/) { model.mark_changed(); }

int Model::node_at(const Eigen::Vector3i& grid_index) const {
  const std::int64_t key = grid_key(grid_index, major_axis);
  auto it = std::lower_bound(sorted_node_keys_.begin(), sorted_node_keys_.end(), key);
  if (it == sorted_node_keys_.end() || *it != key) return -1;
  return static_cast<int>(it - sorted_node_keys_.begin());
}

std::vector<int> Model::nodes_in_box(const Eigen::Vector3d& lower, const Eigen::Vector3d& upper) const {
  std::vector<int> nodes;
  for (int n = 0; n < num_nodes(); ++n) {
    const Eigen::Vector3d p = rest_positions.col(n);
    if ((p.array() >= lower.array()).all() && (p.array() <= upper.array()).all()) nodes.push_back(n);
  }
  return nodes;
}

Result<Model> build_model(const LatticeDesc& desc) {
  if (Status status = check_desc(desc); !status) return status;
  Model model;
  model.cell_model = desc.model;
  model.cell_law = desc.law;
  model.exact_bending = desc.exact_bending;
  model.cell_size = desc.cell_size;
  model.origin = desc.origin;
  model.materials = desc.materials;
  model.major_axis = choose_major_axis(desc.cells);
  const int major_axis = model.major_axis;

  // calibrate each material once for this cell shape
  std::vector<CellCalibration> calibrations;
  for (std::size_t m = 0; m < desc.materials.size(); ++m) {
    Result<CellCalibration> calibration =
        calibrate_cell(desc.model, desc.materials[m], desc.cell_size, desc.exact_bending);
    if (!calibration) return Status::error("material " + std::to_string(m) + ": " + calibration.message());
    calibrations.push_back(calibration.value());
    if (desc.law == CellLaw::kNeoHookean) {
      const CellCalibration& c = calibrations.back();
      model.law_constants.push_back(neo_hookean_constants(shear_modulus(desc.materials[m]),
                                                          bulk_modulus(desc.materials[m]), desc.cell_size,
                                                          c.edge_stiffness, c.diagonal_stiffness));
    }
  }
  const bool springs_law = desc.law == CellLaw::kSprings;

  // cells in grid order, duplicates refused
  std::vector<std::int64_t> cell_keys(desc.cells.size());
  for (std::size_t c = 0; c < cell_keys.size(); ++c) cell_keys[c] = grid_key(desc.cells[c], major_axis);
  std::vector<int> cell_order(desc.cells.size());
  for (std::size_t c = 0; c < cell_order.size(); ++c) cell_order[c] = static_cast<int>(c);
  // a model's own cells (lattice_desc(), a cut) come in order already
  if (!std::is_sorted(cell_keys.begin(), cell_keys.end())) {
    std::sort(cell_order.begin(), cell_order.end(), [&](int a, int b) { return cell_keys[a] < cell_keys[b]; });
  }
  for (std::size_t c = 1; c < cell_order.size(); ++c) {
    if (desc.cells[cell_order[c]] == desc.cells[cell_order[c - 1]]) {
      std::ostringstream message;
      message << "cell (" << desc.cells[cell_order[c]].transpose() << ") is listed twice";
      return Status::error(message.str());
    }
  }

  // nodes: the sorted set of every cell corner. Along the cells in grid order the key of corner
  // o grows (it is the cell's key plus o's), so the 8 corners' keys are 8 sorted lists to merge
  std::array<std::vector<std::int64_t>, kCornersPerCell> corner_keys;
  for (int corner = 0; corner < kCornersPerCell; ++corner) {
    std::vector<std::int64_t>& list = corner_keys[static_cast<std::size_t>(corner)];
    list.resize(cell_order.size());
    for (std::size_t c = 0; c < cell_order.size(); ++c)
      list[c] = grid_key(desc.cells[cell_order[c]] + corner_offset(corner), major_axis);
  }
  std::vector<std::int64_t> points = merged(corner_keys);
  points.erase(std::unique(points.begin(), points.end()), points.end());

  // a point whose node split faces part has copies of it, one after another (node_copies.h); a
  // cell's corner there takes its group's copy
  std::vector<int> first_node(points.size() + 1);  // of each point
  std::iota(first_node.begin(), first_node.end(), 0);
  std::array<std::vector<int>, kCornersPerCell> corner_copy;
  if (!desc.split_faces.empty()) {
    std::vector<Eigen::Vector3i> ordered(cell_order.size());
    for (std::size_t c = 0; c < ordered.size(); ++c) ordered[c] = desc.cells[cell_order[c]];
    Result<std::vector<PointCopies>> copies = split_point_copies(ordered, desc.split_faces);
    if (!copies) return copies.status();
    std::vector<int> count(points.size(), 1);
    for (auto& list : corner_copy) list.assign(cell_order.size(), 0);
    for (const PointCopies& at : *copies) {
      const auto point = std::lower_bound(points.begin(), points.end(), grid_key(at.point, major_axis));
      count[static_cast<std::size_t>(point - points.begin())] = at.count;
      for (std::size_t k = 0; k < corner_copy.size(); ++k) {
        if (at.cell[k] >= 0) corner_copy[k][static_cast<std::size_t>(at.cell[k])] = at.copy[k];
      }
    }
    for (std::size_t u = 0; u < points.size(); ++u) first_node[u + 1] = first_node[u] + count[u];
    model.split_faces = desc.split_faces;
    std::sort(model.split_faces.begin(), model.split_faces.end(), [&](const CellFace& a, const CellFace& b) {
      const std::int64_t ka = grid_key(a.cell, major_axis), kb = grid_key(b.cell, major_axis);
      return ka != kb ? ka < kb : a.axis < b.axis;
    });
  }
  const int num_nodes = first_node.back();
  std::vector<std::int64_t>& keys = model.sorted_node_keys_;  // one a node: a point's copies alike
  keys.resize(static_cast<std::size_t>(num_nodes));
  for (std::size_t u = 0; u < points.size(); ++u)
    std::fill(keys.begin() + first_node[u], keys.begin() + first_node[u + 1], points[u]);
  model.rest_positions.resize(3, num_nodes);
  model.node_grid_index.resize(num_nodes);
  for (int n = 0; n < num_nodes; ++n) {
    const Eigen::Vector3i index = grid_index_of_key(keys[n], major_axis);
    model.node_grid_index[n] = index;
    model.rest_positions.col(n) = desc.origin + index.cast<double>().cwiseProduct(desc.cell_size);
  }
  model.mass = Eigen::VectorXd::Zero(num_nodes);
  model.mass_damping = Eigen::VectorXd::Zero(num_nodes);

  // each corner's node for every cell: one walk over the points along each sorted list
  std::array<std::vector<int>, kCornersPerCell> corner_node;
  for (std::size_t corner = 0; corner < corner_node.size(); ++corner) {
    corner_node[corner].resize(cell_order.size());
    std::size_t at = 0;
    for (std::size_t c = 0; c < cell_order.size(); ++c) {
      while (points[at] < corner_keys[corner][c]) ++at;
      corner_node[corner][c] = first_node[at] + (corner_copy[corner].empty() ? 0 : corner_copy[corner][c]);
    }
  }

  // cells: corners, material, correction, lumped mass; edges collected for merging
  const int num_cells = static_cast<int>(cell_order.size());
  const double volume = desc.cell_size.prod();
  model.cell_grid_index.resize(num_cells);
  model.cell_nodes.resize(num_cells);
  model.cell_edges.resize(num_cells);
  model.cell_material.resize(num_cells);
  model.cell_correction.resize(num_cells);
  model.cell_inversion_stiffness.resize(num_cells);
  model.cell_twist_stiffness.resize(num_cells);
  std::vector<EdgeRecord> edges;
  edges.reserve(static_cast<std::size_t>(num_cells) * kEdgesPerCell);
  for (int c = 0; c < num_cells; ++c) {
    const int source = cell_order[c];
    const int m = desc.cell_material.empty() ? 0 : desc.cell_material[source];
    const Material& material = desc.materials[m];
    const CellCalibration& calibration = calibrations[m];
    model.cell_grid_index[c] = desc.cells[source];
    model.cell_material[c] = m;
    model.cell_correction[c] =
        springs_law ? calibration.correction : neo_hookean_edge_correction(model.law_constants[m]);
    model.cell_inversion_stiffness[c] = springs_law ? kInversionStiffnessFactor * material.young_modulus : 0.0;
    model.cell_twist_stiffness[c] = calibration.twist_stiffness;
    model.has_twist |= calibration.twist_stiffness > 0.0;
    for (int corner = 0; corner < kCornersPerCell; ++corner) {
      const int node = corner_node[static_cast<std::size_t>(corner)][static_cast<std::size_t>(c)];
      model.cell_nodes[c][corner] = node;
      model.mass[node] += material.density * volume / kCornersPerCell;
      model.mass_damping[node] += material.mass_damping * material.density * volume / kCornersPerCell;
    }
    for (int axis = 0; axis < 3; ++axis) {
      int rank = 0;
      for (int corner = 0; corner < kCornersPerCell; ++corner) {
        if (corner & (1 << axis)) continue;
        const int node0 = model.cell_nodes[c][corner];
        const int node1 = model.cell_nodes[c][corner | (1 << axis)];
        const double k = calibration.edge_stiffness[axis];
        edges.push_back({node0, node1, c, axis * kEdgesPerAxis + rank++, k, material.stiffness_damping * k});
      }
    }
  }

  // springs: merged edges plus diagonals, sorted by (first node, second node) for streaming
  sort_by_first_node(edges, num_nodes, [](const EdgeRecord& a, const EdgeRecord& b) {
    return a.node0 != b.node0 ? a.node0 < b.node0 : (a.node1 != b.node1 ? a.node1 < b.node1 : a.cell < b.cell);
  });
  struct SpringRecord {
    int node0, node1;
    double stiffness, damping;
    std::size_t first_edge, edge_count;  // into edges; 0 count for a diagonal
  };
  std::vector<SpringRecord> springs;
  model.cell_diagonals.resize(num_cells);
  for (std::size_t e = 0; e < edges.size();) {
    SpringRecord spring{edges[e].node0, edges[e].node1, 0.0, 0.0, e, 0};
    for (; e < edges.size() && edges[e].node0 == spring.node0 && edges[e].node1 == spring.node1; ++e) {
      spring.stiffness += edges[e].stiffness;
      spring.damping += edges[e].damping;
      ++spring.edge_count;
    }
    springs.push_back(spring);
  }
  // a diagonal runs from its end with the lower node index, as every spring does
  const auto diagonal_ends = [&](int c, int corner) {
    const int a = model.cell_nodes[c][corner], b = model.cell_nodes[c][7 - corner];
    return std::array<int, 2>{std::min(a, b), std::max(a, b)};
  };
  for (int c = 0; c < num_cells; ++c) {
    const CellCalibration& calibration = calibrations[model.cell_material[c]];
    const Material& material = desc.materials[model.cell_material[c]];
    for (int corner = 0; corner < 4; ++corner) {
      const std::array<int, 2> ends = diagonal_ends(c, corner);
      springs.push_back({ends[0], ends[1], calibration.diagonal_stiffness,
                         material.stiffness_damping * calibration.diagonal_stiffness, 0, 0});
    }
  }
  // no two springs join the same nodes: an edge is merged once, a diagonal spans one cell
  sort_by_first_node(springs, num_nodes, [](const SpringRecord& a, const SpringRecord& b) {
    return a.node0 != b.node0 ? a.node0 < b.node0 : a.node1 < b.node1;
  });

  const int num_springs = static_cast<int>(springs.size());
  model.spring_nodes.resize(num_springs);
  model.spring_rest_length.resize(num_springs);
  model.spring_stiffness.resize(num_springs);
  model.spring_damping.resize(num_springs);
  model.spring_cell_offset.assign(num_springs + 1, 0);
  model.spring_cell_tension.reserve(edges.size());
  for (int s = 0; s < num_springs; ++s) {
    const SpringRecord& spring = springs[s];
    model.spring_nodes[s] = {spring.node0, spring.node1};
    model.spring_rest_length[s] =
        (model.rest_positions.col(spring.node1) - model.rest_positions.col(spring.node0)).norm();
    model.spring_stiffness[s] = spring.stiffness;
    model.spring_damping[s] = spring.damping;
    for (std::size_t e = spring.first_edge; e < spring.first_edge + spring.edge_count; ++e) {
      const EdgeRecord& edge = edges[e];
      model.spring_cell_tension.push_back(edge.cell * 3 + edge.slot / kEdgesPerAxis);
      model.cell_edges[edge.cell][edge.slot] = s;
    }
    model.spring_cell_offset[s + 1] = static_cast<int>(model.spring_cell_tension.size());
  }

  model.node_first_spring.assign(num_nodes + 1, 0);
  for (const auto& ends : model.spring_nodes) ++model.node_first_spring[ends[0] + 1];
  for (int n = 0; n < num_nodes; ++n) model.node_first_spring[n + 1] += model.node_first_spring[n];
  // diagonals of each cell, found by their end nodes among the springs of the first
  for (int c = 0; c < num_cells; ++c) {
    for (int corner = 0; corner < 4; ++corner) {
      const std::array<int, 2> ends = diagonal_ends(c, corner);
      const auto first = model.spring_nodes.begin();
      const auto it = std::lower_bound(first + model.node_first_spring[ends[0]],
                                       first + model.node_first_spring[ends[0] + 1], ends);
      model.cell_diagonals[c][corner] = static_cast<int>(it - first);
    }
  }
  for (const Material& material : desc.materials) {
    model.has_stiffness_damping |= material.stiffness_damping > 0.0;
    model.has_mass_damping |= material.mass_damping > 0.0;
  }

  model.mark_changed();
  return model;
}

}  // namespace cubespring
