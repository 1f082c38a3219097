// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "cubespring/cell_law.h"
#include "cubespring/material.h"
#include "cubespring/result.h"

/// Units are SI throughout the API: metres, kilograms, seconds, newtons, pascals.
namespace cubespring {

/// Which calibrated cell model turns a material into springs and correction forces.
enum class CellModel {
  kBaudet2007,    ///< Baudet, Beuve, Jaillet, Shariat, Zara (2007): 12 edge + 4 body-diagonal springs
                  ///< plus the mean-strain correction of docs/model-baudet2007.md.
  kExactBending,  ///< the same springs with edge stiffness beta E h, the correction recomputed so
                  ///< that E, nu, B, G stay exact, and a twist term against the zero-energy modes
                  ///< (docs/model-exact-bending.md). Cubic cells only.
};
/// The name used in command-line flags and JSON output ("baudet2007", "exact-bending").
const char* cell_model_name(CellModel model);
/// The model of a name, or an error listing the names.
Result<CellModel> parse_cell_model(const std::string& name);

/// The two parameters of the exact-bending model (docs/model-exact-bending.md).
struct ExactBendingParameters {
  /// beta: per-cell edge stiffness as a fraction of E h [-], > 0. 1/12 makes a cell's bending
  /// energy exact; 0.07 (the default) also absorbs the coarse mesh's error in cantilevers.
  double edge_fraction = 0.07;
  /// zeta: twist stiffness as a fraction of G [-], >= 0. 1/12 is the continuum energy of the
  /// twist mode; 1/48 (the default) is chosen by the validation table (README): it moves
  /// cantilevers by under 0.2% and brings torsion and the L-shaped body closer to finite
  /// elements (1.7% and 0.7% against 4.7% and 3.8%). 0 leaves the three checkerboard zero modes.
  double twist_factor = 1.0 / 48.0;
};

/// The face between the cell at grid index `cell` and the one after it along `axis` (0, 1, 2:
/// x, y, z), the cell at cell + e_axis.
struct CellFace {
  Eigen::Vector3i cell{0, 0, 0};
  int axis = 0;
};

/// A body as a set of occupied cells of a regular grid. Cells that touch share nodes, except
/// where split_faces part them.
struct LatticeDesc {
  Eigen::Vector3d cell_size{0.01, 0.01, 0.01};  ///< (hx, hy, hz) [m], each > 0.
  Eigen::Vector3d origin{0.0, 0.0, 0.0};        ///< Position of grid node (0,0,0) [m].
  std::vector<Eigen::Vector3i> cells;           ///< Occupied cells, by grid index (no duplicates).
  std::vector<Material> materials{Material{}};  ///< Materials; cells refer to them by index.
  std::vector<int> cell_material;               ///< Material index per cell; empty means all 0.
  CellModel model = CellModel::kBaudet2007;
  ExactBendingParameters exact_bending;  ///< used by CellModel::kExactBending
  /// What the cells make of large strain (cell_law.h): kSprings, the cell model as calibrated
  /// (the default), or kNeoHookean, for soft tissue at large strain.
  CellLaw law = CellLaw::kSprings;
  /// Faces between two cells of the body that are split (a blade's cut, face_split.h): the cells
  /// either side no longer hold together there. Around each grid point, the cells that share a
  /// face not split, or that touch along an edge or at the point with no cell between them, share
  /// a node; each group of cells the splits part gets a node of its own, a copy at the same place.
  /// Both cells of each face must be cells of the body; no face twice. Empty (the default): every
  /// touching cell shares its nodes.
  std::vector<CellFace> split_faces;
};

/// The most cells a body may have: its springs (up to 16 a cell) are indexed by int.
inline constexpr std::uint64_t kMaxCells = 0x7fffffff / 16;

/// Whether a body of `cells` cells can be built here: at most kMaxCells (which build_model()
/// checks), and the memory it takes once built (estimate_body_bytes, voxelize.h) within
/// `memory_limit` bytes (0: half this machine's memory, default_memory_limit()). The error gives
/// the count, the estimate and the limit. Check it before box_lattice() for counts from a user
/// (the count as a double: a product of three counts can pass 2^64).
Status check_lattice_size(double cells, std::uint64_t memory_limit = 0);

/// A box of counts.x() x counts.y() x counts.z() cells spanning
/// [0, nx hx] x [0, ny hy] x [0, nz hz], all of one material.
LatticeDesc box_lattice(const Eigen::Vector3i& counts, const Eigen::Vector3d& cell_size, const Material& material);

}  // namespace cubespring
