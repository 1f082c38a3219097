// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// How much a body is strained: the equivalent (von Mises) strain of each cell and its mean at
// the nodes, for colouring it; the volume its cells enclose, for the finite-strain experiments.
#pragma once

#include <Eigen/Core>

#include "cubespring/model.h"

/// Units are SI throughout the API: metres, kilograms, seconds, newtons, pascals. Strains are
/// dimensionless.
namespace cubespring {

/// The equivalent strain of each cell at its centre, sqrt(2/3 dev(E) : dev(E)) with E the
/// Green-Lagrange strain (F^T F - I) / 2 of the cell's mean edges, F = [e_x / hx, e_y / hy, e_z / hz]
/// (the trilinear deformation gradient at the centre). Zero for any rigid motion; epsilon for a
/// volume-preserving stretch by a small epsilon; (2/3)(1 + nu) epsilon for a small uniaxial
/// stretch epsilon with lateral strain -nu epsilon; gamma / sqrt(3) for a small shear gamma.
/// `positions` is (3 x num_nodes) [m]. Returns one value per cell, in Model::cell_nodes order.
Eigen::VectorXd cell_equivalent_strains(const Model& model, const Eigen::Matrix3Xd& positions);

/// The volume [m^3] of a cell whose corners move as `positions` (3 x num_nodes) [m] says and whose
/// faces are the trilinear interpolation of its corners (the cell's own shape function): the
/// integral of det(dx/dX) over the cell, which 2 x 2 x 2 Gauss points give exactly (det is of
/// degree 2 along each axis). Negative for a cell turned inside out.
double trilinear_cell_volume(const Model& model, const Eigen::Matrix3Xd& positions, int cell);

/// The sum of trilinear_cell_volume over the body's cells [m^3]: the volume the body encloses
/// (cells share their faces exactly).
double body_volume(const Model& model, const Eigen::Matrix3Xd& positions);

/// Per-cell values averaged at each node over the cells that share it (a smooth field for
/// interpolation); `cell_values` has one entry per cell.
Eigen::VectorXd node_means_of_cells(const Model& model, const Eigen::VectorXd& cell_values);

}  // namespace cubespring
