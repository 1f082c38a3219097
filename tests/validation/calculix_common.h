// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
//
// What the CalculiX references share: the C3D20R node order, number formatting for decks, and
// running ccx on a deck and reading the corner-node displacements it prints.

#pragma once

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace cubespring::validation {

/// Local positions of the 20 nodes of a C3D20(R) brick on the doubled grid (0, 1, 2 per axis), in
/// CalculiX/Abaqus order: corners 1-4 on the bottom face (z = 0) counter-clockwise seen from +z,
/// corners 5-8 above them, mid-edge nodes 9-12 on the bottom edges (1-2, 2-3, 3-4, 4-1), 13-16 on
/// the top edges, 17-20 on the vertical edges (1-5, 2-6, 3-7, 4-8). As in CalculiX's shape20h.f.
constexpr std::array<std::array<int, 3>, 20> kBrickNodes{{
    {0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {0, 0, 2}, {2, 0, 2}, {2, 2, 2}, {0, 2, 2}, {1, 0, 0}, {2, 1, 0},
    {1, 2, 0}, {0, 1, 0}, {1, 0, 2}, {2, 1, 2}, {1, 2, 2}, {0, 1, 2}, {0, 0, 1}, {2, 0, 1}, {2, 2, 1}, {0, 2, 1},
}};

/// A number as a deck field: ccx reads each field through its first 20 characters only.
std::string deck_number(double value);
/// A number for a message.
std::string format_double(double value);

/// Displacements [m] of nodes 1..corner_count (node id - 1), or an error naming what failed.
struct CcxResult {
  std::vector<Eigen::Vector3d> corner_displacement;
  /// The summed reaction force [N] of the set run_ccx was asked for, at the end of the step.
  Eigen::Vector3d total_force = Eigen::Vector3d::Constant(NAN);
  std::string error;
};

/// Writes <work_dir>/<job>.inp, runs `ccx -i <job>` there (output to <work_dir>/ccx.log), and reads
/// the last block of displacements of the node set NCORNER from <job>.dat, which must be at the end
/// of the step (time 1). The deck must print that set with *NODE PRINT, NSET=NCORNER / U, and its
/// nodes must be numbered 1..corner_count. With `total_force_set`, also the last summed reaction
/// force of that set (*NODE PRINT, NSET=<set>, TOTALS=ONLY / RF). Never throws.
CcxResult run_ccx(const std::string& work_dir, const std::string& job, const std::string& deck, int corner_count,
                  const std::string& total_force_set = "");

/// True when an executable `ccx` is on PATH.
bool calculix_available();

}  // namespace cubespring::validation
