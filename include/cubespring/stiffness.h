// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "cubespring/forces.h"
#include "cubespring/model.h"
#include "cubespring/result.h"

/// Units are SI throughout the API: metres, kilograms, seconds, newtons, pascals.
namespace cubespring {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;

/// Which stiffness matrix to assemble.
enum class StiffnessKind {
  /// The exact Hessian of the elastic energy (tested against finite differences). Can be
  /// indefinite: compressed springs, the correction's D (indefinite for every nu != 1/4, though
  /// springs plus D are not), the curvature of the inversion term, the neo-Hookean cell term.
  kExact,
  /// A positive semi-definite approximation for implicit steps (docs/model-baudet2007.md section 6):
  /// compressive geometric terms dropped and the correction's D, or the neo-Hookean cell term's
  /// Hessian, replaced by its PSD part.
  kPositiveSemiDefinite,
};

/// Whether the body's stiffness matrix fits the int indices of SparseMatrix (up to about 8 million
/// nodes): an error naming the node and entry counts when it does not. StiffnessAssembler throws
/// std::length_error with that message; check here first to get it as a Status.
Status check_stiffness_size(const Model& model);

/// Assembles stiffness_scale * K + damping_scale * K_beta into a sparsity pattern built once:
/// K the stiffness at the given positions [N/m], K_beta its Rayleigh damping part (each spring's
/// and cell's material stiffness times the material's beta) [N s/m]. Rows and columns are
/// 3 * node + axis; every pair of nodes that share a cell or a spring has a 3x3 block.
class StiffnessAssembler {
 public:
  /// Throws std::length_error, naming the node count, when the matrix would hold more entries
  /// than its int indices address (check_stiffness_size() says so first); the implicit step and
  /// the static solver report that as their failure.
  explicit StiffnessAssembler(const Model& model);

  /// `threads` share the rows (from 1024 nodes a thread); the matrix has the same bits on any
  /// thread count. Throws std::invalid_argument, naming both counts, for positions without one
  /// column per node or a model of other counts than the one the assembler was built for.
  void assemble(const Model& model, const Eigen::Matrix3Xd& positions, StiffnessKind kind, double stiffness_scale,
                double damping_scale, SparseMatrix& matrix, int threads = 1);

  /// The same matrix, assembled into the pattern itself rather than a copy of it: for a caller
  /// that needs one matrix (the stable-step helper), one copy of the matrix in memory instead of
  /// two. Hands the pattern over: `std::move(assembler).assemble_once(...)`; a later assemble()
  /// builds it again. (An assembler serves the model it was built for, in both calls.)
  SparseMatrix assemble_once(const Model& model, const Eigen::Matrix3Xd& positions, StiffnessKind kind,
                             double stiffness_scale, double damping_scale) &&;

  /// The matrix with the pattern and every value zero.
  const SparseMatrix& pattern() const { return pattern_; }

 private:
  void require_fits(const Model& model, const Eigen::Matrix3Xd& positions, const char* caller) const;
  void rebuild_pattern_if_handed_over(const Model& model);
  // The rows of nodes [begin, end): one thread's part of the matrix.
  struct NodeRows {
    int begin = 0, end = 0;
    bool has(int node) const { return node >= begin && node < end; }
  };
  void add_values(const Model& model, const Eigen::Matrix3Xd& x, StiffnessKind kind, double stiffness_scale,
                  double damping_scale, SparseMatrix& matrix, int threads);
  void add_rows(const Model& model, const Eigen::Matrix3Xd& x, StiffnessKind kind, double stiffness_scale,
                double damping_scale, const NodeRows& rows, SparseMatrix& matrix) const;
  void add_block(SparseMatrix& matrix, const NodeRows& rows, int row_node, int position,
                 const Eigen::Matrix3d& block) const;
  // A cell's 8 x 8 corner blocks (corner p's row, corner q's column at p * 8 + q): its terms add
  // into them, and they go into the matrix once (add_cell_blocks).
  using CornerBlocks = std::array<Eigen::Matrix3d, 64>;
  void add_twist(const Model& model, const Eigen::Matrix3Xd& x, int cell, bool exact, double stiffness,
                 CornerBlocks& blocks) const;
  void add_neo_hookean(const Model& model, const Eigen::Matrix3Xd& x, int cell, bool exact, double stiffness_scale,
                       CornerBlocks& blocks) const;
  void add_inversion_recovery(const Model& model, const Eigen::Matrix3Xd& x, int cell, bool exact,
                              double stiffness_scale, CornerBlocks& blocks) const;
  void add_cell_blocks(const Model& model, int cell, const CornerBlocks& blocks, const NodeRows& rows,
                       SparseMatrix& matrix) const;

  SparseMatrix pattern_;
  bool pattern_handed_over_ = false;                  // by assemble_once
  std::vector<int> diagonal_position_;                // per node: own position in its row
  std::vector<std::array<int, 2>> spring_position_;   // per spring: j in row i, i in row j
  std::vector<std::array<int, 64>> cell_position_;    // per cell: corner q in row of corner p
  std::vector<Eigen::Matrix3d> positive_correction_;  // per cell: PSD part of D
  std::vector<Eigen::Matrix3d> positive_of_;          // per cell: the D it is the part of
  int spring_span_ = 0;                               // the most nodes between a spring's two ends
  int cell_span_ = 0;                                 // the most nodes between a cell's lowest and highest corner
  ForceWorkspace tensions_;  // the springs' and cells' tensions at the positions, kept: an implicit
                             // step or Newton iteration allocates no per-spring arrays
};

}  // namespace cubespring
