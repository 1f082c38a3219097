// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// A geometric multigrid V-cycle on a lattice's node grid: the implicit step's preconditioner, with
// which conjugate gradients take about as many iterations on any body size and far fewer than with
// Jacobi's where the matrix is stiff (large steps, nu near 0.5). The lattice is its own hierarchy:
// each coarser level takes every other node of the grid along each axis (a coarse cell is 2 x 2 x 2
// cells), values move to the finer level by trilinear interpolation P and back by P^T, and each
// coarse matrix is P^T A P (Galerkin), so the cycle needs no cells on the coarse levels and
// follows any voxelised shape. Each level smooths with node-block Gauss-Seidel (a node's three
// axes, coupled strongly in elasticity, solved together) in the nodes' order, forward before the
// coarse correction and backward after, which keeps the cycle symmetric; the coarsest level is
// solved exactly (sparse LDL^T). One thread runs it.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCholesky>

#include "cubespring/model.h"
#include "cubespring/stiffness.h"
#include "solve/conjugate_gradient.h"
#include "solve/node_block_matrix.h"

namespace cubespring {

/// At most this many nodes on the coarsest level, which is factorised.
inline constexpr int kCoarsestNodes = 256;

class GridMultigrid final : public Preconditioner {
 public:
  /// The levels' node grids and interpolations, from the model's node grid.
  explicit GridMultigrid(const Model& model);

  /// Builds every level's matrix from `a` (3 rows a node, both triangles stored, symmetric
  /// positive definite, coupling only nodes that share a cell) and its smoother. `fixed[row]`
  /// marks unknowns whose row of `a` is the identity's (known values, eliminated): the coarse
  /// levels leave them alone. False when a level cannot be used (a node's diagonal block or the
  /// coarsest level not positive definite); the preconditioner is then not ready.
  bool setup(const SparseMatrix& a, const std::vector<std::uint8_t>& fixed);
  /// Takes `a` (the pattern and fixed unknowns of setup()'s, other values: a later step's
  /// matrix) as the finest level's and keeps the coarse levels: a cycle a little less exact, for
  /// a fraction of setup()'s time. False as setup().
  bool refresh(const SparseMatrix& a);
  bool ready() const { return ready_; }

  /// z = one V-cycle on r from zero. A symmetric positive definite operator, as conjugate
  /// gradients need.
  void apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) override;

  int num_levels() const { return static_cast<int>(levels_.size()); }
  int level_nodes(int level) const { return static_cast<int>(levels_[static_cast<std::size_t>(level)].grid.size()); }

 private:
  struct Level {
    std::vector<Eigen::Vector3i> grid;  // each node's grid index on this level
    // trilinear interpolation from the next coarser level: node n takes weight[k] of coarse node
    // source[k] for k in [begin[n], begin[n + 1])
    std::vector<int> interpolation_begin, interpolation_source;
    std::vector<double> interpolation_weight;
    std::vector<Eigen::Vector3d> free_axes;  // finest level: 1 for a free unknown, 0 for a fixed one
                                             // (empty when none is fixed)
    NodeBlockMatrix matrix;
    Eigen::VectorXd rhs, solution, residual;  // the cycle's vectors on this level
  };
  bool galerkin(std::size_t fine);  // levels_[fine + 1].matrix = P^T A P
  bool factorise_coarsest();
  void cycle(std::size_t level);

  std::vector<Level> levels_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> coarsest_;
  bool ready_ = false;
};

}  // namespace cubespring
