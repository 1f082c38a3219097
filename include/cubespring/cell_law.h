// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#pragma once

#include <string>

#include <Eigen/Core>

#include "cubespring/result.h"

/// Units are SI throughout the API: metres, kilograms, seconds, newtons, pascals.
namespace cubespring {

/// What a cell's per-cell term makes of large strain (docs/model-neo-hookean.md).
enum class CellLaw {
  /// The cell model's own correction: springs linear in length plus a correction quadratic in
  /// the mean edge strains. Exact at small strain; under a compressive stress of a fraction of E
  /// cells give way (they keep a finite energy when crushed flat).
  kSprings,
  /// Compressible neo-Hookean, in the form CalculiX solves: W = C10 (I1bar - 3) + (J - 1)^2 / D1,
  /// C10 = G / 2, D1 = 2 / B, plus an inversion barrier that is zero for J >= kBarrierVolumeRatio
  /// and unbounded as J -> 0. The cell term is W of the cell's mean deformation gradient minus
  /// what its springs store under that gradient, so that any homogeneous deformation stores
  /// exactly W; the springs keep the non-homogeneous modes. E, nu, G, B are exact at small
  /// strain for either cell model.
  kNeoHookean,
};
/// The name used in flags, scene files and JSON ("springs", "neo-hookean").
const char* cell_law_name(CellLaw law);
/// The law of a name, or an error listing the names.
Result<CellLaw> parse_cell_law(const std::string& name);

/// J below which the inversion barrier acts [-]: the barrier's energy is
/// B (J0 - J)^3 / (J0^2 J) per rest volume, zero with its first two derivatives at J0.
inline constexpr double kBarrierVolumeRatio = 0.5;

/// Constants of the neo-Hookean cell term for one material on one cell shape (built by
/// build_model; docs/model-neo-hookean.md).
struct NeoHookeanConstants {
  double rest_volume = 0;                   ///< V0 [m^3]
  Eigen::Vector3d cell_size{0, 0, 0};       ///< (hx, hy, hz) [m]
  double c10 = 0;                           ///< G / 2 [Pa]
  double half_bulk = 0;                     ///< 1 / D1 = B / 2 [Pa]
  double barrier = 0;                       ///< the barrier's modulus, B [Pa]
  Eigen::Vector3d edge_stiffness{0, 0, 0};  ///< the cell's 4 edges along each axis together [N/m]
  double diagonal_stiffness = 0;            ///< each of the 4 body diagonals [N/m]
  double diagonal_length = 0;               ///< rest length of a body diagonal [m]
};

}  // namespace cubespring
