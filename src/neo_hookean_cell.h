// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The neo-Hookean cell term (docs/model-neo-hookean.md), written once: the force passes, the
// energies and the stiffness all call these functions. Its variables are the cell's three mean
// edge vectors m_p = 1/4 sum_k s_p(k) x_k (CellFrame), so F = [m_x / hx, m_y / hy, m_z / hz] is
// the deformation gradient at the cell's centre; the term is
//   C(m) = V0 W(F) - S(m),
// W the neo-Hookean energy density with its inversion barrier, S what the cell's diagonals store
// when the cell deforms homogeneously with that F; the edges' share of what the springs store
// is a correction on the mean edge lengths (neo_hookean_edge_correction).
#pragma once

#include <array>

#include <Eigen/Core>

#include "cell_geometry.h"
#include "cubespring/cell_law.h"

namespace cubespring {

/// The derivative of the term with respect to each mean edge vector [N].
using MeanEdgeGradient = std::array<Eigen::Vector3d, 3>;
/// Its second derivatives, mean edge vectors x, y, z stacked [N/m].
using MeanEdgeHessian = Eigen::Matrix<double, 9, 9>;

/// The term's energy [J]; with `gradient`, also dC/dm_p.
double neo_hookean_cell_energy(const NeoHookeanConstants& constants, const CellFrame& frame,
                               MeanEdgeGradient* gradient);

/// d2C/dm dm at the frame (the exact Hessian: indefinite at rest, as the paper's correction is).
MeanEdgeHessian neo_hookean_cell_hessian(const NeoHookeanConstants& constants, const CellFrame& frame);

/// What the edges' share of S would add to that Hessian were it a function of the mean edge
/// vectors, -d2/dm dm sum_p 1/2 (4 k_p) (|m_p| - h_p)^2: the positive semi-definite approximation
/// projects the two together, as it did before the share moved to the mean lengths (at rest the
/// two forms agree to second order).
MeanEdgeHessian neo_hookean_edge_hessian(const NeoHookeanConstants& constants, const CellFrame& frame);

/// The edges' share of S as a correction on the cell's mean edge strains (Model::cell_correction):
/// D = diag(-4 k_p h_p^2 / V0), so that 1/2 V0 eps^T D eps = -sum_p 1/2 (4 k_p) (mean length_p - h_p)^2.
/// On the mean of the 4 edges' lengths rather than on |m_p|: under compression the term then takes
/// the edges' tension off each edge, not off the mean deformation only, and the edges' compression
/// no longer softens the cell's non-affine modes (docs/model-neo-hookean.md section 3).
Eigen::Matrix3d neo_hookean_edge_correction(const NeoHookeanConstants& constants);

/// The force on each of the cell's 8 corners [N] from the gradient: f_k = -1/4 sum_p s_p(k) dC/dm_p.
inline std::array<Eigen::Vector3d, kCornersPerCell> corner_forces(const MeanEdgeGradient& gradient) {
  std::array<Eigen::Vector3d, kCornersPerCell> forces;
  for (int corner = 0; corner < kCornersPerCell; ++corner) {
    forces[corner] = -0.25 * (corner_side(corner, 0) * gradient[0] + corner_side(corner, 1) * gradient[1] +
                              corner_side(corner, 2) * gradient[2]);
  }
  return forces;
}

/// The constants for a material of shear modulus g and bulk modulus b [Pa] on cells of the given
/// size [m], whose springs are the per-cell edge share along each axis and the diagonal [N/m].
NeoHookeanConstants neo_hookean_constants(double g, double b, const Eigen::Vector3d& cell_size,
                                          const Eigen::Vector3d& edge_share, double diagonal_stiffness);

}  // namespace cubespring
