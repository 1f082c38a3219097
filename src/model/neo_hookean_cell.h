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
#include <cmath>

#include <Eigen/Core>

#include "cubespring/cell_law.h"
#include "model/cell_geometry.h"

namespace cubespring {

/// Below this J the term's volume terms go on as their second-order Taylor polynomials from it:
/// finite for a cell turned inside out (J <= 0), where the barrier's steep slope pushes it back out.
inline constexpr double kSmallestVolumeRatio = 0.05;

/// x^(-1/3) for x in [2^-93, 2^93), within a few ulp of 1 / std::cbrt(x), by multiplications and
/// selects alone, so that a loop over cells vectorises without a division and every vector
/// width gives the same bits (the grid passes' clones, vector_clones.h): x brought into [1/2, 2)
/// by powers of 8 and a factor 4 (the last with cbrt(4) rounded: half an ulp), a cubic through
/// Chebyshev points (0.5% off), then three Newton steps (5e-5, 5e-9, rounding).
[[gnu::always_inline]] inline double lattice_inverse_cube_root(double x) {
  constexpr double kCubed[5] = {0x1p48, 0x1p24, 0x1p12, 0x1p6, 0x1p3};
  constexpr double kRoot[5] = {0x1p16, 0x1p8, 0x1p4, 0x1p2, 0x1p1};
  constexpr double kCbrt4 = 1.5874010519681994;  // 4^(1/3)
  double scale = 1.0;
#pragma GCC unroll 5
  for (int i = 0; i < 5; ++i) {  // x = x' 8^(+-k): x^(-1/3) = x'^(-1/3) 2^(-+k)
    const bool big = x >= kCubed[i];
    x = big ? x * (1.0 / kCubed[i]) : x;
    scale = big ? scale * (1.0 / kRoot[i]) : scale;
    const bool small = x < 1.0 / kCubed[i];
    x = small ? x * kCubed[i] : x;
    scale = small ? scale * kRoot[i] : scale;
  }
  const bool big = x >= 2.0, small = x < 0.5;  // [1/8, 8) -> [1/2, 2)
  x = big ? x * 0.25 : (small ? x * 4.0 : x);
  scale = big ? scale * (1.0 / kCbrt4) : (small ? scale * kCbrt4 : scale);
  double y = 1.718882966412687 + x * (-1.1974476838622194 + x * (0.5886707983253736 + x * -0.11086599290587576));
#pragma GCC unroll 3
  for (int step = 0; step < 3; ++step) y = y + y * ((1.0 - x * (y * y * y)) * (1.0 / 3.0));
  return y * scale;
}

/// The term [J] and its gradient dC/dm_p [N] (gradient[p][c], component c of m_p) from the mean
/// edge vectors m[p][c] [m]: the term written once, for neo_hookean_cell_energy and for the grid
/// passes' loop over a layer's cells, which it lets vectorise (no branch: the Taylor continuation
/// below kSmallestVolumeRatio and the barrier below kBarrierVolumeRatio are selects; no call).
/// `Constants` is NeoHookeanConstants, or a plain struct with the fields the term reads (a loop
/// whose cells' materials differ builds one per cell, which an Eigen member would keep scalar).
template <class Constants>
[[gnu::always_inline]] inline double neo_hookean_term(const Constants& k, const double (&m)[3][3],
                                                      double (&gradient)[3][3]) {
  const double inverse_sq[3] = {1.0 / (k.cell_size[0] * k.cell_size[0]), 1.0 / (k.cell_size[1] * k.cell_size[1]),
                                1.0 / (k.cell_size[2] * k.cell_size[2])};  // constants of the loop too
  double i1 = 0.0;
  for (int p = 0; p < 3; ++p) i1 += (m[p][0] * m[p][0] + m[p][1] * m[p][1] + m[p][2] * m[p][2]) * inverse_sq[p];
  double cofactor[3][3];  // V0 dJ/dm_p = m_q x m_r
  for (int p = 0; p < 3; ++p) {
    const double(&q)[3] = m[(p + 1) % 3];
    const double(&r)[3] = m[(p + 2) % 3];
    cofactor[p][0] = q[1] * r[2] - q[2] * r[1];
    cofactor[p][1] = q[2] * r[0] - q[0] * r[2];
    cofactor[p][2] = q[0] * r[1] - q[1] * r[0];
  }
  const double j = (m[0][0] * cofactor[0][0] + m[0][1] * cofactor[0][1] + m[0][2] * cofactor[0][2]) *
                   (1.0 / k.rest_volume);  // a constant of the loop over cells
  // J^(-2/3) and the volume energy as curves of J (value, slope, curvature) at `from`, and on
  // from there as their Taylor polynomials below kSmallestVolumeRatio (d < 0; else d = 0 adds
  // exact zeros)
  const double from = j >= kSmallestVolumeRatio ? j : kSmallestVolumeRatio;  // NaN: d is NaN too
  const double d = j - from;
  const double inverse = 1.0 / from;
  const double inverse_root = lattice_inverse_cube_root(from);
  const double scale_at = inverse_root * inverse_root;
  const double scale_slope_at = -2.0 / 3.0 * scale_at * inverse;
  const double scale_curvature = 10.0 / 9.0 * scale_at * (inverse * inverse);
  const double scale = scale_at + scale_slope_at * d + 0.5 * scale_curvature * d * d;
  const double scale_slope = scale_slope_at + scale_curvature * d;
  // (J - 1)^2 / D1 plus the barrier B (J0 - J)^3 / (J0^2 J) below J0 (u = 0 above: exact zeros)
  constexpr double j0 = kBarrierVolumeRatio;
  const double u = from < j0 ? j0 - from : 0.0;
  const double s = k.barrier / (j0 * j0);
  const double ui = u * inverse;  // u / J
  const double volume_at = k.half_bulk * (from - 1.0) * (from - 1.0) + s * u * u * ui;
  const double volume_slope_at = 2.0 * k.half_bulk * (from - 1.0) - s * ui * ui * (3.0 * from + u);
  const double volume_curvature = 2.0 * k.half_bulk + s * (6.0 * ui + 6.0 * ui * ui + 2.0 * ui * ui * ui);
  const double volume = volume_at + volume_slope_at * d + 0.5 * volume_curvature * d * d;
  const double volume_slope = volume_slope_at + volume_curvature * d;

  double energy = k.rest_volume * (k.c10 * (scale * i1 - 3.0) + volume);
  const double per_j = k.c10 * scale_slope * i1 + volume_slope;  // dW/dJ
  const double along = 2.0 * k.rest_volume * k.c10 * scale;
  for (int p = 0; p < 3; ++p) {
    for (int c = 0; c < 3; ++c) gradient[p][c] = per_j * cofactor[p][c] + (along * inverse_sq[p]) * m[p][c];
  }
  // minus what the 4 diagonals store under the same homogeneous deformation: diagonal d runs from
  // corner d to corner 7 - d, its vector sum_p s_p(7 - d) m_p (the edges' share is
  // neo_hookean_edge_correction's, on their mean lengths)
  constexpr double kSignX[4] = {1.0, -1.0, 1.0, -1.0}, kSignY[4] = {1.0, 1.0, -1.0, -1.0};
#pragma GCC unroll 4
  for (int diagonal = 0; diagonal < 4; ++diagonal) {
    double v[3];
    for (int c = 0; c < 3; ++c) v[c] = kSignX[diagonal] * m[0][c] + kSignY[diagonal] * m[1][c] + m[2][c];
    const double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    const double stretch = length - k.diagonal_length;
    energy -= 0.5 * k.diagonal_stiffness * stretch * stretch;
    const double per_length = length > 0.0 ? k.diagonal_stiffness * stretch / length : 0.0;
    for (int c = 0; c < 3; ++c) {
      const double pull = per_length * v[c];
      gradient[0][c] -= kSignX[diagonal] * pull;
      gradient[1][c] -= kSignY[diagonal] * pull;
      gradient[2][c] -= pull;
    }
  }
  return energy;
}

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
