// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "solve/grid_multigrid.h"

#include <algorithm>
#include <array>
#include <cstdint>

namespace cubespring {
namespace {

// Gauss-Seidel sweeps before and after each coarse correction: 2 took a third fewer iterations
// than 1 on a clamped 32x8x8 beam (dt 1-16 ms), for about the same time a step
constexpr int kSweeps = 2;

// The coarse grid points a node at `relative` (its grid index less the level's lowest) takes its
// value from, with their weights: along each axis its own point halved when even, the two either
// side with half each when odd (trilinear interpolation, up to 8 points).
struct Stencil {
  std::array<Eigen::Vector3i, 8> point;
  std::array<double, 8> weight;
  int size = 0;
};
Stencil interpolation_stencil(const Eigen::Vector3i& relative) {
  std::array<std::array<int, 2>, 3> index{};
  std::array<std::array<double, 2>, 3> weight{};
  std::array<int, 3> count{};
  for (int axis = 0; axis < 3; ++axis) {
    const int r = relative[axis];
    if (r % 2 == 0) {
      index[axis] = {r / 2, 0};
      weight[axis] = {1.0, 0.0};
      count[axis] = 1;
    } else {
      index[axis] = {r / 2, r / 2 + 1};
      weight[axis] = {0.5, 0.5};
      count[axis] = 2;
    }
  }
  Stencil stencil;
  for (int k = 0; k < count[2]; ++k) {
    for (int j = 0; j < count[1]; ++j) {
      for (int i = 0; i < count[0]; ++i) {
        stencil.point[stencil.size] = {index[0][i], index[1][j], index[2][k]};
        stencil.weight[stencil.size] = weight[0][i] * weight[1][j] * weight[2][k];
        ++stencil.size;
      }
    }
  }
  return stencil;
}

// A key that orders grid points z-major, then y, then x (points of a level are >= 0).
std::int64_t grid_key(const Eigen::Vector3i& g) {
  constexpr std::int64_t kSpan = std::int64_t{1} << 21;
  return (static_cast<std::int64_t>(g.z()) * kSpan + g.y()) * kSpan + g.x();
}

}  // namespace

GridMultigrid::GridMultigrid(const Model& model) {
  levels_.emplace_back();
  levels_.back().grid = model.node_grid_index;
  // coarsen while the level is large and coarsening still shrinks it (a body one node thick along
  // an axis stays so there; one that cannot shrink by a third has reached its smallest)
  while (static_cast<int>(levels_.back().grid.size()) > kCoarsestNodes) {
    Level& fine = levels_.back();
    Eigen::Vector3i lowest = fine.grid.front();
    for (const Eigen::Vector3i& g : fine.grid) lowest = lowest.cwiseMin(g);
    std::vector<std::int64_t> keys;
    std::vector<Stencil> stencils;
    stencils.reserve(fine.grid.size());
    for (const Eigen::Vector3i& g : fine.grid) {
      stencils.push_back(interpolation_stencil(g - lowest));
      for (int s = 0; s < stencils.back().size; ++s) keys.push_back(grid_key(stencils.back().point[s]));
    }
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    if (3 * keys.size() > 2 * fine.grid.size()) break;

    Level coarse;
    coarse.grid.reserve(keys.size());
    for (const std::int64_t key : keys) {
      constexpr std::int64_t kMask = (std::int64_t{1} << 21) - 1;
      coarse.grid.emplace_back(static_cast<int>(key & kMask), static_cast<int>((key >> 21) & kMask),
                               static_cast<int>(key >> 42));
    }
    fine.interpolation_begin.assign(1, 0);
    for (const Stencil& stencil : stencils) {
      for (int s = 0; s < stencil.size; ++s) {
        const auto at = std::lower_bound(keys.begin(), keys.end(), grid_key(stencil.point[s]));
        fine.interpolation_source.push_back(static_cast<int>(at - keys.begin()));
        fine.interpolation_weight.push_back(stencil.weight[s]);
      }
      fine.interpolation_begin.push_back(static_cast<int>(fine.interpolation_source.size()));
    }
    levels_.push_back(std::move(coarse));
  }

  for (Level& level : levels_) {
    const int nodes = static_cast<int>(level.grid.size());
    level.rhs.setZero(3 * nodes);
    level.solution.setZero(3 * nodes);
    level.residual.setZero(3 * nodes);
  }
}

bool GridMultigrid::setup(const SparseMatrix& a, const std::vector<std::uint8_t>& fixed) {
  ready_ = false;
  Level& finest = levels_.front();
  if (!finest.matrix.assign(a)) return false;
  // the mask only where some unknown is fixed: without one, the cycle and the products skip it
  finest.free_axes.clear();
  for (std::size_t row = 0; row < fixed.size() && row < 3 * finest.grid.size(); ++row) {
    if (!fixed[row]) continue;
    if (finest.free_axes.empty()) finest.free_axes.assign(finest.grid.size(), Eigen::Vector3d::Ones());
    finest.free_axes[row / 3][static_cast<Eigen::Index>(row % 3)] = 0.0;
  }
  for (std::size_t l = 0; l + 1 < levels_.size(); ++l) {
    if (!galerkin(l)) return false;
  }
  coarsest_.analyzePattern(levels_.back().matrix.to_sparse());  // its ordering, kept by refresh()
  ready_ = factorise_coarsest();
  return ready_;
}

bool GridMultigrid::refresh(const SparseMatrix& a) {
  ready_ = levels_.front().matrix.update(a) && (levels_.size() > 1 || factorise_coarsest());
  return ready_;
}

// The coarse matrix block by block: A_c(I, J) += w_iI w_jJ A(i, j) over the fine blocks and the
// coarse nodes each end interpolates from. Both levels couple only grid neighbours (a fine block
// joins nodes of one cell, and trilinear interpolation keeps that on the coarser grid), so coarse
// row I has its blocks in 27 slots, one per neighbour offset, in the order of the nodes' numbers.
bool GridMultigrid::galerkin(std::size_t l) {
  const Level& fine = levels_[l];
  Level& coarse = levels_[l + 1];
  const int coarse_nodes = static_cast<int>(coarse.grid.size());
  std::vector<Eigen::Matrix3d> slots(27 * static_cast<std::size_t>(coarse_nodes), Eigen::Matrix3d::Zero());
  std::vector<int> slot_node(27 * static_cast<std::size_t>(coarse_nodes), -1);
  const bool masked = !fine.free_axes.empty();
  for (int i = 0; i < fine.matrix.nodes(); ++i) {
    for (int k = fine.matrix.row_begin(i); k < fine.matrix.row_begin(i + 1); ++k) {
      const int j = fine.matrix.column(k);
      Eigen::Matrix3d block = fine.matrix.block(k).cast<double>();
      if (masked)
        block = fine.free_axes[static_cast<std::size_t>(i)].asDiagonal() * block *
                fine.free_axes[static_cast<std::size_t>(j)].asDiagonal();
      for (int p = fine.interpolation_begin[static_cast<std::size_t>(i)];
           p < fine.interpolation_begin[static_cast<std::size_t>(i) + 1]; ++p) {
        const int row = fine.interpolation_source[static_cast<std::size_t>(p)];
        const double row_weight = fine.interpolation_weight[static_cast<std::size_t>(p)];
        for (int q = fine.interpolation_begin[static_cast<std::size_t>(j)];
             q < fine.interpolation_begin[static_cast<std::size_t>(j) + 1]; ++q) {
          const int col = fine.interpolation_source[static_cast<std::size_t>(q)];
          const Eigen::Vector3i offset =
              coarse.grid[static_cast<std::size_t>(col)] - coarse.grid[static_cast<std::size_t>(row)];
          if (offset.cwiseAbs().maxCoeff() > 1) return false;  // not a lattice's matrix
          const int slot = 27 * row + (offset.x() + 1) + 3 * (offset.y() + 1) + 9 * (offset.z() + 1);
          slots[static_cast<std::size_t>(slot)] +=
              row_weight * fine.interpolation_weight[static_cast<std::size_t>(q)] * block;
          slot_node[static_cast<std::size_t>(slot)] = col;
        }
      }
    }
  }
  std::vector<int> row_begin{0}, columns;
  for (int row = 0; row < coarse_nodes; ++row) {
    for (int slot = 27 * row; slot < 27 * row + 27; ++slot) {
      if (slot_node[static_cast<std::size_t>(slot)] >= 0) columns.push_back(slot_node[static_cast<std::size_t>(slot)]);
    }
    row_begin.push_back(static_cast<int>(columns.size()));
  }
  coarse.matrix.start(std::move(row_begin), std::move(columns));
  int k = 0;
  for (int row = 0; row < coarse_nodes; ++row) {
    for (int slot = 27 * row; slot < 27 * row + 27; ++slot) {
      if (slot_node[static_cast<std::size_t>(slot)] < 0) continue;
      Eigen::Matrix3d& block = slots[static_cast<std::size_t>(slot)];
      // an unknown that interpolates to nothing (only fixed unknowns below it) has an empty row
      // and column: the identity's keeps the level invertible, and its value reaches no fine one
      if (slot_node[static_cast<std::size_t>(slot)] == row) {
        for (int a = 0; a < 3; ++a) {
          if (block(a, a) == 0.0) block(a, a) = 1.0;
        }
      }
      coarse.matrix.block(k++) = block.cast<float>();
    }
  }
  return l + 2 == levels_.size() || coarse.matrix.invert_diagonal();
}

bool GridMultigrid::factorise_coarsest() {
  coarsest_.factorize(levels_.back().matrix.to_sparse());
  return coarsest_.info() == Eigen::Success;
}

void GridMultigrid::apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) {
  levels_.front().rhs = r;
  cycle(0);
  z = levels_.front().solution;
}

void GridMultigrid::cycle(std::size_t l) {
  Level& level = levels_[l];
  if (l + 1 == levels_.size()) {
    level.solution = coarsest_.solve(level.rhs);
    return;
  }
  level.solution.setZero();
  for (int i = 0; i < kSweeps; ++i) level.matrix.gauss_seidel(level.rhs, level.solution, true);
  level.matrix.residual(level.rhs, level.solution, level.residual);
  if (!level.free_axes.empty()) {
    for (std::size_t n = 0; n < level.grid.size(); ++n) {
      level.residual.segment<3>(3 * static_cast<Eigen::Index>(n)).array() *= level.free_axes[n].array();
    }
  }
  // restrict (P^T), correct on the coarser level, interpolate its correction back (P)
  Level& coarse = levels_[l + 1];
  coarse.rhs.setZero();
  const int nodes = static_cast<int>(level.grid.size());
  for (int n = 0; n < nodes; ++n) {
    for (int p = level.interpolation_begin[static_cast<std::size_t>(n)];
         p < level.interpolation_begin[static_cast<std::size_t>(n) + 1]; ++p) {
      coarse.rhs.segment<3>(3 * level.interpolation_source[static_cast<std::size_t>(p)]) +=
          level.interpolation_weight[static_cast<std::size_t>(p)] * level.residual.segment<3>(3 * n);
    }
  }
  cycle(l + 1);
  for (int n = 0; n < nodes; ++n) {
    Eigen::Vector3d correction = Eigen::Vector3d::Zero();
    for (int p = level.interpolation_begin[static_cast<std::size_t>(n)];
         p < level.interpolation_begin[static_cast<std::size_t>(n) + 1]; ++p) {
      correction += level.interpolation_weight[static_cast<std::size_t>(p)] *
                    coarse.solution.segment<3>(3 * level.interpolation_source[static_cast<std::size_t>(p)]);
    }
    if (!level.free_axes.empty()) correction.array() *= level.free_axes[static_cast<std::size_t>(n)].array();
    level.solution.segment<3>(3 * n) += correction;
  }
  for (int i = 0; i < kSweeps; ++i) level.matrix.gauss_seidel(level.rhs, level.solution, false);
}

}  // namespace cubespring
