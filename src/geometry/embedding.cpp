// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "cubespring/embedding.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <unordered_map>
#include <vector>

#include <Eigen/Geometry>

namespace cubespring {

namespace {

std::int64_t cell_key(const Eigen::Vector3i& index) {
  // 21 bits per axis, offset so that negative indices map to distinct keys
  constexpr std::int64_t kOffset = std::int64_t{1} << 20;
  return ((index.x() + kOffset) << 42) | ((index.y() + kOffset) << 21) | (index.z() + kOffset);
}

// Squared distance from a point to the box of a cell, in cell units scaled by the cell size.
double squared_distance_to_cell(const Eigen::Vector3d& local, const Eigen::Vector3i& cell, const Eigen::Vector3d& h) {
  const Eigen::Vector3d lower = cell.cast<double>();
  const Eigen::Vector3d outside =
      (lower - local).cwiseMax(local - lower - Eigen::Vector3d::Ones()).cwiseMax(0.0).cwiseProduct(h);
  return outside.squaredNorm();
}

// The lattice's cells span [low, high] (grid indices); only cells in there can be occupied (and
// only their keys are distinct).
struct CellBox {
  Eigen::Vector3i low, high;
  bool contains(const Eigen::Vector3i& cell) const {
    return (cell.array() >= low.array()).all() && (cell.array() <= high.array()).all();
  }
};

// The model's cell at a grid index, or -1: a table over the cells' box when it is not much larger
// than the cells (a lattice voxelized from an organ), else a hash (a few cells far apart). Every
// vertex of a surface asks, most of them outside the lattice many times over (nearest_cell).
class CellLookup {
 public:
  CellLookup(const Model& model, const CellBox& box) : box_(box), extent_((box.high - box.low).array() + 1) {
    const double volume = extent_.cast<double>().prod();
    if (volume <= kMaxTableCellsPerCell * model.num_cells()) {
      table_.assign(static_cast<std::size_t>(volume), -1);
      for (int c = 0; c < model.num_cells(); ++c) table_[slot(model.cell_grid_index[static_cast<std::size_t>(c)])] = c;
    } else {
      for (int c = 0; c < model.num_cells(); ++c)
        hash_.emplace(cell_key(model.cell_grid_index[static_cast<std::size_t>(c)]), c);
    }
  }
  int find(const Eigen::Vector3i& cell) const {
    if (!box_.contains(cell)) return -1;
    if (!table_.empty()) return table_[slot(cell)];
    const auto found = hash_.find(cell_key(cell));
    return found == hash_.end() ? -1 : found->second;
  }

 private:
  static constexpr double kMaxTableCellsPerCell = 64.0;
  std::size_t slot(const Eigen::Vector3i& cell) const {
    const Eigen::Vector3i at = cell - box_.low;
    return (static_cast<std::size_t>(at.z()) * static_cast<std::size_t>(extent_.y()) +
            static_cast<std::size_t>(at.y())) *
               static_cast<std::size_t>(extent_.x()) +
           static_cast<std::size_t>(at.x());
  }
  CellBox box_;
  Eigen::Vector3i extent_;
  std::vector<int> table_;
  std::unordered_map<std::int64_t, int> hash_;
};

// The occupied cell nearest to a point given in grid units, by rings (the shells of cubes) of
// growing radius around the grid cell that contains it; stops once no farther ring can hold a
// nearer cell.
int nearest_cell(const CellLookup& cell_of, const CellBox& box, const Eigen::Vector3d& local, const Eigen::Vector3d& h,
                 int max_radius) {
  const Eigen::Vector3i home = local.array().floor().cast<int>();
  int best = -1;
  double best_distance = std::numeric_limits<double>::infinity();
  for (int radius = 0; radius <= max_radius; ++radius) {
    // every cell of a ring is at least (radius - 1) cells away along one axis
    if (best >= 0 && (radius - 1) * h.minCoeff() > std::sqrt(best_distance)) break;
    for (int dz = -radius; dz <= radius; ++dz) {
      for (int dy = -radius; dy <= radius; ++dy) {
        // inside the shell's top and bottom and its sides along y, only its two x-ends
        const bool whole_row = std::abs(dz) == radius || std::abs(dy) == radius;
        const int dx_step = whole_row || radius == 0 ? 1 : 2 * radius;
        for (int dx = -radius; dx <= radius; dx += dx_step) {
          const Eigen::Vector3i cell = home + Eigen::Vector3i(dx, dy, dz);
          if (!box.contains(cell)) continue;
          const int found = cell_of.find(cell);
          if (found < 0) continue;
          const double distance = squared_distance_to_cell(local, cell, h);
          if (distance < best_distance) {  // ties keep the first in a fixed order: deterministic
            best_distance = distance;
            best = found;
          }
        }
      }
    }
  }
  return best;
}

// Weight of corner c, at offset (c & 1, c >> 1 & 1, c >> 2 & 1), at trilinear coordinates u.
double trilinear_weight(int corner, const Eigen::Vector3d& u) {
  double weight = 1.0;
  for (int axis = 0; axis < 3; ++axis) weight *= ((corner >> axis) & 1) ? u[axis] : 1.0 - u[axis];
  return weight;
}

}  // namespace

Result<Embedding> embed_mesh(const Model& model, const TriangleMesh& visual) {
  if (Status status = validate(visual); !status) return status;
  if (model.num_cells() == 0) return Status::error("cannot embed a mesh in a model with no cells");
  CellBox box{model.cell_grid_index.front(), model.cell_grid_index.front()};
  for (int c = 0; c < model.num_cells(); ++c) {
    box.low = box.low.cwiseMin(model.cell_grid_index[static_cast<std::size_t>(c)]);
    box.high = box.high.cwiseMax(model.cell_grid_index[static_cast<std::size_t>(c)]);
  }
  const CellLookup cell_of(model, box);
  // a vertex bound to a cell farther than the lattice is long would move by extrapolation, not
  // with the tissue (and finding its cell would take long): most likely another unit or place
  const int longest = (box.high - box.low).maxCoeff() + 1;
  Embedding embedding;
  embedding.triangles = visual.triangles;
  embedding.vertex_cell.resize(static_cast<std::size_t>(visual.num_vertices()));
  embedding.vertex_local.resize(3, visual.num_vertices());
  for (int v = 0; v < visual.num_vertices(); ++v) {
    // position in grid units: cell (i, j, k) spans [i, i + 1) x [j, j + 1) x [k, k + 1)
    const Eigen::Vector3d local = (visual.vertices.col(v) - model.origin).cwiseQuotient(model.cell_size);
    const Eigen::Vector3d home_cell = local.array().floor();
    const Eigen::Vector3d beyond = (box.low.cast<double>() - home_cell).cwiseMax(home_cell - box.high.cast<double>());
    if (!(beyond.maxCoeff() <= longest)) {  // NaN too
      std::ostringstream message;
      message << "vertex " << v << " at (" << visual.vertices.col(v).transpose() << ") m lies " << beyond.maxCoeff()
              << " cells outside the lattice, which is " << longest
              << " cells long: is the visual mesh in the lattice's units and place?";
      return Status::error(message.str());
    }
    const Eigen::Vector3i home = home_cell.cast<int>();
    int cell = cell_of.find(home);
    if (cell < 0) {
      const Eigen::Vector3i reach = (home - box.low).cwiseAbs().cwiseMax((home - box.high).cwiseAbs());
      cell = nearest_cell(cell_of, box, local, model.cell_size, reach.maxCoeff() + 1);
    }
    embedding.vertex_cell[static_cast<std::size_t>(v)] = cell;
    embedding.vertex_local.col(v) = local - model.cell_grid_index[static_cast<std::size_t>(cell)].cast<double>();
  }
  return embedding;
}

void embedded_positions(const Model& model, const Embedding& embedding, const Eigen::Matrix3Xd& node_positions,
                        Eigen::Matrix3Xd& vertices) {
  vertices.resize(3, embedding.num_vertices());
  for (int v = 0; v < embedding.num_vertices(); ++v) {
    const auto& corners =
        model.cell_nodes[static_cast<std::size_t>(embedding.vertex_cell[static_cast<std::size_t>(v)])];
    const Eigen::Vector3d u = embedding.vertex_local.col(v);
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
    for (int corner = 0; corner < kCornersPerCell; ++corner) {
      position += trilinear_weight(corner, u) * node_positions.col(corners[static_cast<std::size_t>(corner)]);
    }
    vertices.col(v) = position;
  }
}

void embedded_values(const Model& model, const Embedding& embedding, const Eigen::VectorXd& node_values,
                     Eigen::VectorXd& vertex_values) {
  vertex_values.resize(embedding.num_vertices());
  for (int v = 0; v < embedding.num_vertices(); ++v) {
    const auto& corners =
        model.cell_nodes[static_cast<std::size_t>(embedding.vertex_cell[static_cast<std::size_t>(v)])];
    const Eigen::Vector3d u = embedding.vertex_local.col(v);
    double value = 0.0;
    for (int corner = 0; corner < kCornersPerCell; ++corner) {
      value += trilinear_weight(corner, u) * node_values[corners[static_cast<std::size_t>(corner)]];
    }
    vertex_values[v] = value;
  }
}

void vertex_normals(const Eigen::Matrix3Xd& vertices, const Eigen::Matrix3Xi& triangles, Eigen::Matrix3Xd& normals) {
  normals.setZero(3, vertices.cols());
  for (Eigen::Index t = 0; t < triangles.cols(); ++t) {
    const Eigen::Vector3d a = vertices.col(triangles(0, t));
    // the cross product's length is twice the area: the weighting comes for free
    const Eigen::Vector3d n = (vertices.col(triangles(1, t)) - a).cross(vertices.col(triangles(2, t)) - a);
    for (int corner = 0; corner < 3; ++corner) normals.col(triangles(corner, t)) += n;
  }
  for (Eigen::Index v = 0; v < normals.cols(); ++v) {
    const double length = normals.col(v).norm();
    if (length > 0.0) normals.col(v) /= length;
  }
}

}  // namespace cubespring
