// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Hessian of the elastic energy (docs/model-baudet2007.md section 6):
//   spring s:   k n n^T + (t / l)(I - n n^T), t the total tension including the correction;
//   correction: V0 sum_ab D_ab g_a g_b^T with g_a = d(eps_a)/dx;
//   inversion:  k_inv / V0 grad V grad V^T + k_inv (V / V0 - phi) hess V, for crushed cells;
//   the exact-bending twist (docs/model-exact-bending.md section 3) and the neo-Hookean cell term
//   (docs/model-neo-hookean.md section 4). A cell's terms add into its 8 x 8 corner blocks, which
//   go into the matrix once.
#include "cubespring/stiffness.h"

#include <algorithm>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>

#include <Eigen/Eigenvalues>

#include "cubespring/forces.h"
#include "forces/force_passes.h"
#include "forces/input_checks.h"
#include "forces/twist.h"
#include "model/cell_geometry.h"
#include "model/neo_hookean_cell.h"
#include "thread_shares.h"

namespace cubespring {
namespace {

Eigen::Matrix3d positive_part(const Eigen::Matrix3d& m) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(m);
  const Eigen::Vector3d values = solver.eigenvalues().cwiseMax(0.0);
  return solver.eigenvectors() * values.asDiagonal() * solver.eigenvectors().transpose();
}

int position_in(const std::vector<int>& sorted, int value) {
  return static_cast<int>(std::lower_bound(sorted.begin(), sorted.end(), value) - sorted.begin());
}

// Per node, sorted: the node itself, the other end of each spring, every node that shares a cell.
std::vector<std::vector<int>> sorted_neighbours(const Model& model) {
  std::vector<std::vector<int>> neighbours(model.num_nodes());
  for (int n = 0; n < model.num_nodes(); ++n) neighbours[n].push_back(n);
  for (const auto& ends : model.spring_nodes) {
    neighbours[ends[0]].push_back(ends[1]);
    neighbours[ends[1]].push_back(ends[0]);
  }
  for (const auto& corners : model.cell_nodes) {
    for (int p : corners) neighbours[p].insert(neighbours[p].end(), corners.begin(), corners.end());
  }
  for (auto& list : neighbours) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  return neighbours;
}

std::size_t pattern_entries(const std::vector<std::vector<int>>& neighbours) {
  std::size_t entries = 0;
  for (const auto& list : neighbours) entries += 9 * list.size();
  return entries;
}

std::string pattern_size_error(int num_nodes, std::size_t entries) {
  if (entries <= static_cast<std::size_t>(std::numeric_limits<int>::max())) return {};
  return "the stiffness matrix of " + std::to_string(num_nodes) + " nodes would hold " + std::to_string(entries) +
         " entries, more than its int indices can address (at most " + std::to_string(std::numeric_limits<int>::max()) +
         ")";
}

// A 3x3 block of zeros for each node and each of its neighbours, compressed. The rows are written
// in place, in order: a list of triplets (16 bytes an entry) and setFromTriplets' transposed copy
// had tripled the memory (2.9 GB and 22 s for 64^3 cells).
void build_pattern(const std::vector<std::vector<int>>& neighbours, SparseMatrix& pattern) {
  const int num_nodes = static_cast<int>(neighbours.size());
  const std::size_t entries = pattern_entries(neighbours);
  if (const std::string error = pattern_size_error(num_nodes, entries); !error.empty()) throw std::length_error(error);
  pattern.resize(3 * num_nodes, 3 * num_nodes);
  pattern.makeCompressed();
  pattern.resizeNonZeros(static_cast<Eigen::Index>(entries));
  int* row_start = pattern.outerIndexPtr();
  int* column = pattern.innerIndexPtr();
  int entry = 0;
  for (int n = 0; n < num_nodes; ++n) {
    for (int a = 0; a < 3; ++a) {
      row_start[3 * n + a] = entry;
      for (int m : neighbours[n]) {
        for (int b = 0; b < 3; ++b) column[entry++] = 3 * m + b;
      }
    }
  }
  row_start[3 * num_nodes] = entry;
  std::fill(pattern.valuePtr(), pattern.valuePtr() + pattern.nonZeros(), 0.0);
}

}  // namespace

Status check_stiffness_size(const Model& model) {
  const std::string error = pattern_size_error(model.num_nodes(), pattern_entries(sorted_neighbours(model)));
  return error.empty() ? Status() : Status::error(error);
}

StiffnessAssembler::StiffnessAssembler(const Model& model) {
  const int num_nodes = model.num_nodes();
  const std::vector<std::vector<int>> neighbours = sorted_neighbours(model);
  build_pattern(neighbours, pattern_);

  diagonal_position_.resize(num_nodes);
  for (int n = 0; n < num_nodes; ++n) diagonal_position_[n] = position_in(neighbours[n], n);
  spring_position_.resize(model.num_springs());
  for (int s = 0; s < model.num_springs(); ++s) {
    const int i = model.spring_nodes[s][0];
    const int j = model.spring_nodes[s][1];
    spring_position_[s] = {position_in(neighbours[i], j), position_in(neighbours[j], i)};
  }
  for (const auto& ends : model.spring_nodes) spring_span_ = std::max(spring_span_, ends[1] - ends[0]);
  for (const auto& corners : model.cell_nodes) {
    const auto [lowest, highest] = std::minmax_element(corners.begin(), corners.end());
    cell_span_ = std::max(cell_span_, *highest - *lowest);
  }
  // the PSD parts of the corrections are made when first assembled (add_values): NaN equals no D
  positive_correction_.resize(model.num_cells());
  positive_of_.assign(model.num_cells(), Eigen::Matrix3d::Constant(std::numeric_limits<double>::quiet_NaN()));
  cell_position_.resize(model.num_cells());
  for (int c = 0; c < model.num_cells(); ++c) {
    for (int p = 0; p < kCornersPerCell; ++p) {
      for (int q = 0; q < kCornersPerCell; ++q) {
        cell_position_[c][p * kCornersPerCell + q] =
            position_in(neighbours[model.cell_nodes[c][p]], model.cell_nodes[c][q]);
      }
    }
  }
}

void StiffnessAssembler::add_block(SparseMatrix& matrix, const NodeRows& rows, int row_node, int position,
                                   const Eigen::Matrix3d& block) const {
  if (!rows.has(row_node)) return;  // another thread's row
  const int* outer = matrix.outerIndexPtr();
  double* values = matrix.valuePtr();
  for (int a = 0; a < 3; ++a) {
    double* row = values + outer[3 * row_node + a] + 3 * position;
    for (int b = 0; b < 3; ++b) row[b] += block(a, b);
  }
}

// Twist term (docs/model-exact-bending.md section 3): W = 1/2 k h^3 sum_d w_d^2 with w_d = g_1 - g_0
// and g = a . c / h^2 bilinear in the corners, a = sum_k alpha_k x_k, c = sum_k kappa_k x_k. Then
// grad_k w = sum_side s (alpha_k c + kappa_k a) / h^2 and hess_km w = sum_side s (alpha_k kappa_m +
// kappa_k alpha_m) I / h^2; the approximation keeps only the Gauss-Newton part grad w grad w^T.
void StiffnessAssembler::add_twist(const Model& model, const Eigen::Matrix3Xd& x, int c, bool exact, double k,
                                   CornerBlocks& blocks) const {
  const double h = model.cell_size.x();
  std::array<Eigen::Vector3d, kEdgesPerCell> edges;
  for (int e = 0; e < kEdgesPerCell; ++e) {
    const int axis = e / kEdgesPerAxis;
    const int rank = e % kEdgesPerAxis;
    const int lower = ((rank >> axis) << (axis + 1)) | (rank & ((1 << axis) - 1));
    edges[e] = x.col(model.cell_nodes[c][lower | (1 << axis)]) - x.col(model.cell_nodes[c][lower]);
  }
  // corner coefficients of the mean of two edges
  const auto coefficients = [](const std::array<int, 2>& slots) {
    std::array<double, kCornersPerCell> weights{};
    for (int slot : slots) {
      const int axis = slot / kEdgesPerAxis;
      const int rank = slot % kEdgesPerAxis;
      const int lower = ((rank >> axis) << (axis + 1)) | (rank & ((1 << axis) - 1));
      weights[lower | (1 << axis)] += 0.5;
      weights[lower] -= 0.5;
    }
    return weights;
  };
  // each direction's grad w and w, then every corner block once with the three directions summed
  // (a block each per direction had been most of the twist's time)
  const auto& faces = twist_faces();
  std::array<std::array<Eigen::Vector3d, kCornersPerCell>, 3> gradient;
  std::array<std::array<std::array<double, kCornersPerCell>, 2>, 3> alpha, kappa;
  std::array<double, 3> w{};
  for (int d = 0; d < 3; ++d) {
    gradient[d].fill(Eigen::Vector3d::Zero());
    std::array<double, 2> gamma{};
    for (int side = 0; side < 2; ++side) {
      const double sign = side == 0 ? -1.0 : 1.0;
      const FaceMeans means = face_means(faces[d][side], edges);
      alpha[d][side] = coefficients(faces[d][side].a_edges);
      kappa[d][side] = coefficients(faces[d][side].c_edges);
      gamma[side] = means.a.dot(means.c) / (h * h);
      for (int p = 0; p < kCornersPerCell; ++p) {
        gradient[d][p] += sign * (alpha[d][side][p] * means.c + kappa[d][side][p] * means.a) / (h * h);
      }
    }
    w[d] = gamma[1] - gamma[0];
  }
  const double scale = k * h * h * h;
  // element by element: Eigen's 3x3 temporaries here were written to the stack and read back
  // across the write, which stalled on the store (most of this function's time)
  for (int p = 0; p < kCornersPerCell; ++p) {
    for (int q = 0; q < kCornersPerCell; ++q) {
      Eigen::Matrix3d& block = blocks[p * kCornersPerCell + q];
      for (int a = 0; a < 3; ++a) {
        for (int b = 0; b < 3; ++b) {
          block(a, b) += scale * (gradient[0][p][a] * gradient[0][q][b] + gradient[1][p][a] * gradient[1][q][b] +
                                  gradient[2][p][a] * gradient[2][q][b]);
        }
      }
      if (exact) {
        double curvature = 0.0;  // sum over d of w_d hess_pq w_d (a multiple of I)
        for (int d = 0; d < 3; ++d) {
          curvature += w[d] * ((alpha[d][1][p] * kappa[d][1][q] + kappa[d][1][p] * alpha[d][1][q]) -
                               (alpha[d][0][p] * kappa[d][0][q] + kappa[d][0][p] * alpha[d][0][q]));
        }
        for (int a = 0; a < 3; ++a) block(a, a) += scale * curvature / (h * h);
      }
    }
  }
}

// Neo-Hookean cell term (docs/model-neo-hookean.md section 4): the 9x9 Hessian H in the mean
// edge vectors m_p = 1/4 sum_k s_p(k) x_k gives the corner blocks sum_pq s_p(k) s_q(l) / 16 H_pq;
// the approximation takes H's positive part (its negative eigenvalues set to zero).
void StiffnessAssembler::add_neo_hookean(const Model& model, const Eigen::Matrix3Xd& x, int c, bool exact,
                                         double stiffness_scale, CornerBlocks& blocks) const {
  const NeoHookeanConstants& constants = model.law_constants[model.cell_material[c]];
  const CellFrame frame = cell_frame(model, x, c);
  MeanEdgeHessian h = neo_hookean_cell_hessian(constants, frame);
  if (!exact) {
    // the edges' share as a function of the mean edge vectors, projected with the rest (its exact
    // form, on the mean edge lengths, is the cell's correction, which the approximation leaves out)
    h += neo_hookean_edge_hessian(constants, frame);
    const Eigen::SelfAdjointEigenSolver<MeanEdgeHessian> solver(h);
    h = solver.eigenvectors() * solver.eigenvalues().cwiseMax(0.0).asDiagonal() * solver.eigenvectors().transpose();
  }
  h *= stiffness_scale / 16.0;
  // corner p's row of the sum, s(p)^T H: three blocks (one per mean edge b); then each corner
  // block once, element by element (no 3x3 temporaries, as in add_twist)
  double row[kCornersPerCell][3][3][3];  // [p][b][i][j]
  for (int p = 0; p < kCornersPerCell; ++p) {
    for (int b = 0; b < 3; ++b) {
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
          row[p][b][i][j] = corner_side(p, 0) * h(i, 3 * b + j) + corner_side(p, 1) * h(3 + i, 3 * b + j) +
                            corner_side(p, 2) * h(6 + i, 3 * b + j);
        }
      }
    }
  }
  for (int p = 0; p < kCornersPerCell; ++p) {
    for (int q = 0; q < kCornersPerCell; ++q) {
      Eigen::Matrix3d& block = blocks[p * kCornersPerCell + q];
      const double s0 = corner_side(q, 0), s1 = corner_side(q, 1), s2 = corner_side(q, 2);
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) block(i, j) += s0 * row[p][0][i][j] + s1 * row[p][1][i][j] + s2 * row[p][2][i][j];
      }
    }
  }
}

// The springs law's inversion recovery of a crushed cell (kCrushedVolumeFraction): k_inv / V0
// grad V grad V^T, and with the exact kind k_inv (V / V0 - phi) hess V.
void StiffnessAssembler::add_inversion_recovery(const Model& model, const Eigen::Matrix3Xd& x, int c, bool exact,
                                                double stiffness_scale, CornerBlocks& blocks) const {
  const double rest_volume = model.rest_cell_volume();
  const CellFrame frame = cell_frame(model, x, c);
  const double ratio = frame.volume() / rest_volume;
  if (ratio >= kCrushedVolumeFraction) return;
  const double k_inv = stiffness_scale * model.cell_inversion_stiffness[c];
  const auto gradient = frame.volume_gradient();
  // second derivatives of V = a . (b x c) with respect to the mean edge vectors
  std::array<std::array<Eigen::Matrix3d, 3>, 3> hess;
  hess[0][0] = hess[1][1] = hess[2][2] = Eigen::Matrix3d::Zero();
  hess[0][1] = -cross_matrix(frame.edge[2]);
  hess[0][2] = cross_matrix(frame.edge[1]);
  hess[1][2] = -cross_matrix(frame.edge[0]);
  hess[1][0] = hess[0][1].transpose();
  hess[2][0] = hess[0][2].transpose();
  hess[2][1] = hess[1][2].transpose();
  const double curvature_scale = exact ? k_inv * (ratio - kCrushedVolumeFraction) : 0.0;
  for (int p = 0; p < kCornersPerCell; ++p) {
    for (int q = 0; q < kCornersPerCell; ++q) {
      Eigen::Matrix3d block = (k_inv / rest_volume) * gradient[p] * gradient[q].transpose();
      if (curvature_scale != 0.0) {
        for (int a = 0; a < 3; ++a) {
          for (int b = 0; b < 3; ++b) {
            block += curvature_scale * corner_side(p, a) * corner_side(q, b) / 16.0 * hess[a][b];
          }
        }
      }
      blocks[p * kCornersPerCell + q] += block;
    }
  }
}

void StiffnessAssembler::add_cell_blocks(const Model& model, int c, const CornerBlocks& blocks, const NodeRows& rows,
                                         SparseMatrix& matrix) const {
  for (int p = 0; p < kCornersPerCell; ++p) {
    if (!rows.has(model.cell_nodes[c][p])) continue;
    for (int q = 0; q < kCornersPerCell; ++q) {
      add_block(matrix, rows, model.cell_nodes[c][p], cell_position_[c][p * kCornersPerCell + q],
                blocks[p * kCornersPerCell + q]);
    }
  }
}

void StiffnessAssembler::assemble(const Model& model, const Eigen::Matrix3Xd& x, StiffnessKind kind,
                                  double stiffness_scale, double damping_scale, SparseMatrix& matrix, int threads) {
  require_fits(model, x, "StiffnessAssembler::assemble");
  rebuild_pattern_if_handed_over(model);
  if (matrix.nonZeros() != pattern_.nonZeros() || matrix.rows() != pattern_.rows()) {
    matrix = pattern_;
  } else {
    std::fill(matrix.valuePtr(), matrix.valuePtr() + matrix.nonZeros(), 0.0);
  }
  add_values(model, x, kind, stiffness_scale, damping_scale, matrix, threads);
}

SparseMatrix StiffnessAssembler::assemble_once(const Model& model, const Eigen::Matrix3Xd& x, StiffnessKind kind,
                                               double stiffness_scale, double damping_scale) && {
  require_fits(model, x, "StiffnessAssembler::assemble_once");
  rebuild_pattern_if_handed_over(model);
  SparseMatrix matrix;
  matrix.swap(pattern_);  // its values are zeros (swapped: Eigen 3.4's SparseMatrix has no move)
  pattern_handed_over_ = true;
  add_values(model, x, kind, stiffness_scale, damping_scale, matrix, 1);
  return matrix;
}

void StiffnessAssembler::require_fits(const Model& model, const Eigen::Matrix3Xd& x, const char* caller) const {
  if (diagonal_position_.size() != static_cast<std::size_t>(model.num_nodes()) ||
      spring_position_.size() != static_cast<std::size_t>(model.num_springs()) ||
      cell_position_.size() != static_cast<std::size_t>(model.num_cells())) {
    throw std::invalid_argument(
        std::string(caller) + ": the assembler was built for a body of " + std::to_string(diagonal_position_.size()) +
        " nodes, " + std::to_string(spring_position_.size()) + " springs and " + std::to_string(cell_position_.size()) +
        " cells; this one has " + std::to_string(model.num_nodes()) + ", " + std::to_string(model.num_springs()) +
        " and " + std::to_string(model.num_cells()));
  }
  require_node_columns(model, x, (std::string(caller) + ": positions").c_str());
}

void StiffnessAssembler::rebuild_pattern_if_handed_over(const Model& model) {
  if (!pattern_handed_over_) return;
  build_pattern(sorted_neighbours(model), pattern_);
  pattern_handed_over_ = false;
}

void StiffnessAssembler::add_values(const Model& model, const Eigen::Matrix3Xd& x, StiffnessKind kind,
                                    double stiffness_scale, double damping_scale, SparseMatrix& matrix, int threads) {
  require_law_constants(model, "StiffnessAssembler");
  // the model's springs are read at every call; the cells' PSD parts are kept, made for each
  // correction the first time it is seen (a changed one, a stiffer region say, too): a compare
  // per cell
  if (kind == StiffnessKind::kPositiveSemiDefinite) {
    for (int c = 0; c < model.num_cells(); ++c) {
      if (model.cell_correction[c] == positive_of_[c]) continue;
      positive_correction_[c] = positive_part(model.cell_correction[c]);
      positive_of_[c] = model.cell_correction[c];
    }
  }
  measure_tensions(model, x, tensions_);
  const int num_nodes = model.num_nodes();
  // each thread the rows of a range of nodes, from the springs and cells that reach them taken
  // in the order one thread takes them: every entry sums the same terms in the same order
  run_shares(std::min(threads, num_nodes / kMinNodesPerThread), [&](int share, int shares, const auto&) {
    const ShareRange nodes = equal_share(num_nodes, share, shares);
    add_rows(model, x, kind, stiffness_scale, damping_scale, NodeRows{nodes.begin, nodes.end}, matrix);
  });
}

void StiffnessAssembler::add_rows(const Model& model, const Eigen::Matrix3Xd& x, StiffnessKind kind,
                                  double stiffness_scale, double damping_scale, const NodeRows& rows,
                                  SparseMatrix& matrix) const {
  const bool exact = kind == StiffnessKind::kExact;
  const ForceWorkspace& ws = tensions_;

  // springs: material and geometric parts; those that reach the rows start at most spring_span_
  // nodes before them (springs are sorted by their first node)
  const int first_spring = model.node_first_spring[std::max(0, rows.begin - spring_span_)];
  const int spring_end = model.node_first_spring[rows.end];
  for (int s = first_spring; s < spring_end; ++s) {
    const double length = ws.spring_length[s];
    if (length <= 0.0) continue;
    const int i = model.spring_nodes[s][0];
    const int j = model.spring_nodes[s][1];
    if (!rows.has(i) && !rows.has(j)) continue;
    const Eigen::Vector3d n = (x.col(j) - x.col(i)) / length;
    const Eigen::Matrix3d nn = n * n.transpose();
    const double tension = exact ? ws.spring_tension[s] : std::max(ws.spring_tension[s], 0.0);
    const Eigen::Matrix3d block =
        (stiffness_scale * model.spring_stiffness[s] + damping_scale * model.spring_damping[s]) * nn +
        (stiffness_scale * tension / length) * (Eigen::Matrix3d::Identity() - nn);
    add_block(matrix, rows, i, diagonal_position_[i], block);
    add_block(matrix, rows, j, diagonal_position_[j], block);
    add_block(matrix, rows, i, spring_position_[s][0], -block);
    add_block(matrix, rows, j, spring_position_[s][1], -block);
  }

  // cells: their correction, neo-Hookean, twist and inversion terms; those that reach the rows have their
  // corner 0 (their lowest node: cells come in node order) at most cell_span_ nodes before them
  const double rest_volume = model.rest_cell_volume();
  const auto corner_0_below = [&](int node) {
    const auto below = [node](const std::array<int, kCornersPerCell>& corners) { return corners[0] < node; };
    return static_cast<int>(std::partition_point(model.cell_nodes.begin(), model.cell_nodes.end(), below) -
                            model.cell_nodes.begin());
  };
  const int cell_end = corner_0_below(rows.end);
  CornerBlocks blocks;
  for (int c = corner_0_below(rows.begin - cell_span_); c < cell_end; ++c) {
    const auto& corners = model.cell_nodes[c];
    if (std::none_of(corners.begin(), corners.end(), [&](int n) { return rows.has(n); })) continue;
    const bool neo_hookean = model.cell_law == CellLaw::kNeoHookean;
    // the neo-Hookean term's edge correction is exact only: its approximation is add_neo_hookean's
    const Eigen::Matrix3d& d = exact ? model.cell_correction[c] : positive_correction_[c];
    // and it has no damping (the law adds none)
    const double beta = neo_hookean ? 0.0 : model.materials[model.cell_material[c]].stiffness_damping;
    const Eigen::Matrix3d weighted = rest_volume * (stiffness_scale + damping_scale * beta) * d;
    // strain_gradient[p] column a = d(eps_a)/d(x_p)
    std::array<Eigen::Matrix3d, kCornersPerCell> strain_gradient;
    for (int p = 0; p < kCornersPerCell; ++p) {
      for (int axis = 0; axis < 3; ++axis) {
        const int low = p & ~(1 << axis);
        const Eigen::Vector3d edge = x.col(model.cell_nodes[c][low | (1 << axis)]) - x.col(model.cell_nodes[c][low]);
        const double length = edge.norm();
        strain_gradient[p].col(axis) =
            length > 0.0
                ? Eigen::Vector3d(corner_side(p, axis) * edge / (length * kEdgesPerAxis * model.cell_size[axis]))
                : Eigen::Vector3d::Zero();
      }
    }
    // the correction's blocks start the cell's (element by element, as add_twist's)
    for (int p = 0; p < kCornersPerCell; ++p) {
      const Eigen::Matrix3d left = strain_gradient[p] * weighted;
      for (int q = 0; q < kCornersPerCell; ++q) {
        Eigen::Matrix3d& block = blocks[p * kCornersPerCell + q];
        const Eigen::Matrix3d& right = strain_gradient[q];
        for (int a = 0; a < 3; ++a) {
          for (int b = 0; b < 3; ++b) {
            block(a, b) = left(a, 0) * right(b, 0) + left(a, 1) * right(b, 1) + left(a, 2) * right(b, 2);
          }
        }
      }
    }
    if (neo_hookean) add_neo_hookean(model, x, c, exact, stiffness_scale, blocks);

    if (model.has_twist && model.cell_twist_stiffness[c] > 0.0) {
      add_twist(model, x, c, exact, stiffness_scale * model.cell_twist_stiffness[c], blocks);
    }
    if (!neo_hookean) add_inversion_recovery(model, x, c, exact, stiffness_scale, blocks);
    add_cell_blocks(model, c, blocks, rows, matrix);
  }
}

}  // namespace cubespring
