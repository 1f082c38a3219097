// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The neo-Hookean cell term: docs/model-neo-hookean.md gives each formula used here.
#include "model/neo_hookean_cell.h"

#include <cmath>

namespace cubespring {
namespace {

// A function of J with its first two derivatives (the Hessian's; neo_hookean_term has the same
// curves, written as selects).
struct Curve {
  double value, slope, curvature;
};

Curve taylor_from(const Curve& at, double from, double j) {
  const double d = j - from;
  return {at.value + at.slope * d + 0.5 * at.curvature * d * d, at.slope + at.curvature * d, at.curvature};
}

// J^(-2/3), which makes I1 isochoric (I1bar = J^(-2/3) I1).
Curve isochoric_scale(double j) {
  if (!(j >= kSmallestVolumeRatio)) {
    return taylor_from(isochoric_scale(kSmallestVolumeRatio), kSmallestVolumeRatio, j);
  }
  const double inverse_root = lattice_inverse_cube_root(j);  // as neo_hookean_term takes it
  const double value = inverse_root * inverse_root;
  return {value, -2.0 / 3.0 * value / j, 10.0 / 9.0 * value / (j * j)};
}

// The volumetric energy density (J - 1)^2 / D1 plus the barrier B (J0 - J)^3 / (J0^2 J) below J0.
Curve volume_energy(const NeoHookeanConstants& k, double j) {
  if (!(j >= kSmallestVolumeRatio)) {
    return taylor_from(volume_energy(k, kSmallestVolumeRatio), kSmallestVolumeRatio, j);
  }
  Curve e{k.half_bulk * (j - 1.0) * (j - 1.0), 2.0 * k.half_bulk * (j - 1.0), 2.0 * k.half_bulk};
  constexpr double j0 = kBarrierVolumeRatio;
  if (j < j0) {
    const double u = j0 - j;
    const double s = k.barrier / (j0 * j0);
    e.value += s * u * u * u / j;
    e.slope -= s * u * u * (3.0 * j + u) / (j * j);
    e.curvature += s * (6.0 * u / j + 6.0 * u * u / (j * j) + 2.0 * u * u * u / (j * j * j));
  }
  return e;
}

// Diagonal d runs from corner d to corner 7 - d; under a homogeneous F its vector is
// sum_p s_p(7 - d) m_p.
double diagonal_sign(int diagonal, int axis) { return corner_side(7 - diagonal, axis); }

Eigen::Vector3d homogeneous_diagonal(const CellFrame& frame, int diagonal) {
  return diagonal_sign(diagonal, 0) * frame.edge[0] + diagonal_sign(diagonal, 1) * frame.edge[1] +
         diagonal_sign(diagonal, 2) * frame.edge[2];
}

// d2(1/2 k (|v| - L)^2) / dv dv
Eigen::Matrix3d spring_hessian(const Eigen::Vector3d& v, double k, double rest) {
  const double length = v.norm();
  if (length <= 0.0) return k * Eigen::Matrix3d::Identity();
  const Eigen::Vector3d n = v / length;
  const Eigen::Matrix3d nn = n * n.transpose();
  return k * nn + (k * (length - rest) / length) * (Eigen::Matrix3d::Identity() - nn);
}

}  // namespace

double neo_hookean_cell_energy(const NeoHookeanConstants& k, const CellFrame& frame, MeanEdgeGradient* gradient) {
  double m[3][3], g[3][3];
  for (int p = 0; p < 3; ++p) {
    for (int c = 0; c < 3; ++c) m[p][c] = frame.edge[p][c];
  }
  const double energy = neo_hookean_term(k, m, g);
  if (gradient != nullptr) {
    for (int p = 0; p < 3; ++p) (*gradient)[p] = Eigen::Vector3d(g[p][0], g[p][1], g[p][2]);
  }
  return energy;
}

MeanEdgeHessian neo_hookean_cell_hessian(const NeoHookeanConstants& k, const CellFrame& frame) {
  const std::array<Eigen::Vector3d, 3>& m = frame.edge;
  const double v0 = k.rest_volume;
  const Eigen::Array3d inverse_sq = k.cell_size.array().square().inverse();
  const double i1 =
      m[0].squaredNorm() * inverse_sq[0] + m[1].squaredNorm() * inverse_sq[1] + m[2].squaredNorm() * inverse_sq[2];
  Eigen::Matrix<double, 9, 1> dj, di1;  // dJ/dm and dI1/dm
  dj << m[1].cross(m[2]), m[2].cross(m[0]), m[0].cross(m[1]);
  dj /= v0;
  for (int p = 0; p < 3; ++p) di1.segment<3>(3 * p) = 2.0 * inverse_sq[p] * m[p];
  const double j = m[0].dot(m[1].cross(m[2])) / v0;
  const Curve scale = isochoric_scale(j);
  const Curve volume = volume_energy(k, j);

  MeanEdgeHessian h = MeanEdgeHessian::Zero();
  for (int p = 0; p < 3; ++p) {
    h.block<3, 3>(3 * p, 3 * p).diagonal().setConstant(2.0 * v0 * k.c10 * scale.value * inverse_sq[p]);
  }
  h += (v0 * k.c10 * scale.slope) * (di1 * dj.transpose() + dj * di1.transpose());
  h += (v0 * (k.c10 * scale.curvature * i1 + volume.curvature)) * dj * dj.transpose();
  // d2J/dm_p dm_q = -eps_pqr [m_r]x / V0
  const double per_j = k.c10 * scale.slope * i1 + volume.slope;
  for (int p = 0; p < 3; ++p) {
    const int q = (p + 1) % 3;
    const int r = (p + 2) % 3;
    const Eigen::Matrix3d block = -per_j * cross_matrix(m[r]);  // eps_pqr = +1
    h.block<3, 3>(3 * p, 3 * q) += block;
    h.block<3, 3>(3 * q, 3 * p) += block.transpose();
  }
  for (int d = 0; d < 4; ++d) {
    const Eigen::Matrix3d spring =
        spring_hessian(homogeneous_diagonal(frame, d), k.diagonal_stiffness, k.diagonal_length);
    for (int p = 0; p < 3; ++p) {
      for (int q = 0; q < 3; ++q) h.block<3, 3>(3 * p, 3 * q) -= diagonal_sign(d, p) * diagonal_sign(d, q) * spring;
    }
  }
  return h;
}

MeanEdgeHessian neo_hookean_edge_hessian(const NeoHookeanConstants& k, const CellFrame& frame) {
  MeanEdgeHessian h = MeanEdgeHessian::Zero();
  for (int p = 0; p < 3; ++p) {
    h.block<3, 3>(3 * p, 3 * p) = -spring_hessian(frame.edge[p], k.edge_stiffness[p], k.cell_size[p]);
  }
  return h;
}

Eigen::Matrix3d neo_hookean_edge_correction(const NeoHookeanConstants& k) {
  // 1/2 V0 D_pp eps_p^2 = -1/2 (4 k_p) (mean length - h_p)^2, eps_p = mean length / h_p - 1
  return (-k.edge_stiffness.array() * k.cell_size.array().square() / k.rest_volume).matrix().asDiagonal();
}

NeoHookeanConstants neo_hookean_constants(double g, double b, const Eigen::Vector3d& cell_size,
                                          const Eigen::Vector3d& edge_share, double diagonal_stiffness) {
  NeoHookeanConstants k;
  k.rest_volume = cell_size.prod();
  k.cell_size = cell_size;
  k.c10 = 0.5 * g;
  k.half_bulk = 0.5 * b;
  k.barrier = b;
  k.edge_stiffness = kEdgesPerAxis * edge_share;
  k.diagonal_stiffness = diagonal_stiffness;
  k.diagonal_length = cell_size.norm();
  return k;
}

const char* cell_law_name(CellLaw law) {
  switch (law) {
    case CellLaw::kSprings: return "springs";
    case CellLaw::kNeoHookean: return "neo-hookean";
  }
  return "unknown";
}

Result<CellLaw> parse_cell_law(const std::string& name) {
  for (CellLaw law : {CellLaw::kSprings, CellLaw::kNeoHookean}) {
    if (name == cell_law_name(law)) return law;
  }
  return Status::error("unknown cell law '" + name + "': expected springs or neo-hookean");
}

}  // namespace cubespring
