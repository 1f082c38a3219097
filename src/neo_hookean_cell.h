// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The neo-Hookean cell term (docs/model-neo-hookean.md), written once: the force passes, the
// energies and the stiffness all call these functions. Its variables are the cell's three mean
// edge vectors m_p = 1/4 sum_k s_p(k) x_k (CellFrame), so F = [m_x / hx, m_y / hy, m_z / hz] is
// the deformation gradient at the cell's centre; the term is
//   C(m) = V0 W(F) - S(m),
// W the neo-Hookean energy density with its inversion barrier, S what the cell's springs store
// when the cell deforms homogeneously with that F.
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
