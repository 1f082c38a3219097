// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Gershgorin's row sums of a body's stiffness at rest: what the explicit stable step, selective
// mass scaling and each cell's stable step read. Summing them assembles the whole stiffness; a
// body that is cut keeps them, so that a cut sums again only the rows it changed.
#pragma once

#include <Eigen/Core>

#include "cubespring/cell_removal.h"
#include "cubespring/model.h"

/// Units are SI throughout the API: metres, kilograms, seconds, newtons, pascals.
namespace cubespring {

/// Each node's largest sum of |K_ij| over its three rows of the body's stiffness at rest [N/m].
/// Assembles the whole stiffness (0.3 s for 64x16x16 cells). Throws std::length_error for a body
/// too large for the matrix's int indices (check_stiffness_size() in stiffness.h).
Eigen::VectorXd stiffness_row_sums(const Model& model);

/// stiffness_row_sums(removal.model), from `before_sums`, the sums of `before`, the model the
/// removal took cells from: a node none of whose cells left has the rows it had (every cell that
/// adds to them remains), and the nodes of the removed cells are summed again from a model of
/// just the cells that share a node with them. Equal to summing the whole body again up to the
/// order of the additions (1e-15 relative); a cut of a few cells of the 2,456-cell demo liver
/// costs a fraction of a millisecond where the whole sum costs about 15. Throws
/// std::invalid_argument when `before_sums` or the removal's maps do not fit `before`.
Eigen::VectorXd stiffness_row_sums_after(const Model& before, const Eigen::VectorXd& before_sums,
                                         const CellRemoval& removal);

}  // namespace cubespring
