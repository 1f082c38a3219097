// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "cubespring/result.h"

/// Units are SI throughout the API: metres, kilograms, seconds, newtons, pascals. A CalculiX deck
/// has no units of its own; a result read here is taken to be in metres.
namespace cubespring {

/// A finite-element solution, read from a CalculiX result file to compare a lattice with it or to
/// draw it (the cantilever picture of `cubespring measure cantilever --reference`).
struct FemSolution {
  std::vector<int> node_ids;        ///< CalculiX's node numbers, one per column below
  Eigen::Matrix3Xd rest_positions;  ///< node coordinates [m]
  Eigen::Matrix3Xd displacements;   ///< the last displacement field in the file [m]
  /// The outer faces of the solid elements (faces that no other element shares) on their corner
  /// nodes, as triangles (3 x m) of column indices, counter-clockwise seen from outside.
  Eigen::Matrix3Xi surface;
};

/// Reads an ASCII .frd file as ccx writes it for `*NODE FILE` with `U`: the node block (2C), the
/// element block (3C) and the last DISP block; other result blocks are skipped. Solid elements
/// only (frd types 1-6: 8- and 20-node bricks, 6- and 15-node wedges, 4- and 10-node tetrahedra).
/// Errors name the file and, for a malformed line, its number.
Result<FemSolution> read_calculix_frd(const std::string& path);

}  // namespace cubespring
