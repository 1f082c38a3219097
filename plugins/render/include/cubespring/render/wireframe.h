// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#pragma once

#include <Eigen/Core>

#include "cubespring/model.h"

/// Units are SI throughout the API: metres, kilograms, seconds, newtons, pascals.
namespace cubespring {

/// The lattice as lines: every cell edge once (an edge shared by 4 cells is still one segment),
/// without the body diagonals. `points` is node_positions (3 x num_nodes) [m], e.g.
/// State::positions; `segments` (2 x num_edges) are node indices into it, ordered by spring index.
void lattice_wireframe(const Model& model, const Eigen::Matrix3Xd& node_positions, Eigen::Matrix3Xd& points,
                       Eigen::Matrix2Xi& segments);

}  // namespace cubespring
