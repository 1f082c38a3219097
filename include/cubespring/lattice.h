// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#pragma once

#include <vector>

#include <Eigen/Core>

#include "cubespring/material.h"

/// Units are SI throughout the API: metres, kilograms, seconds, newtons, pascals.
namespace cubespring {

/// Which calibrated cell model turns a material into springs and correction forces.
enum class CellModel {
  kBaudet2007,  ///< Baudet, Beuve, Jaillet, Shariat, Zara (2007): 12 edge + 4 body-diagonal springs
                ///< plus the mean-strain correction of docs/model-baudet2007.md.
};
/// The name used in command-line flags and JSON output ("baudet2007").
const char* cell_model_name(CellModel model);

/// A body as a set of occupied cells of a regular grid. Cells that touch share nodes.
struct LatticeDesc {
  Eigen::Vector3d cell_size{0.01, 0.01, 0.01};  ///< (hx, hy, hz) [m], each > 0.
  Eigen::Vector3d origin{0.0, 0.0, 0.0};        ///< Position of grid node (0,0,0) [m].
  std::vector<Eigen::Vector3i> cells;           ///< Occupied cells, by grid index (no duplicates).
  std::vector<Material> materials{Material{}};  ///< Materials; cells refer to them by index.
  std::vector<int> cell_material;               ///< Material index per cell; empty means all 0.
  CellModel model = CellModel::kBaudet2007;
};

/// A box of counts.x() x counts.y() x counts.z() cells spanning
/// [0, nx hx] x [0, ny hy] x [0, nz hz], all of one material.
LatticeDesc box_lattice(const Eigen::Vector3i& counts, const Eigen::Vector3d& cell_size,
                        const Material& material);

}  // namespace cubespring
