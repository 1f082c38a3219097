// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// What the bench commands share: the machine they ran on, their list of block sizes, and the
// voxelized ball they bench beside the blocks.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "cubespring/lattice.h"

namespace cubespring::app {

/// The CPU's name, for the record of "this machine" ("" when the system does not say).
std::string cpu_name();

/// "NX,NY,NZ;NX,NY,NZ;..." as block sizes; throws std::runtime_error naming --sizes.
std::vector<Eigen::Vector3i> parse_size_list(const std::string& text);

/// "a,b,c" as numbers that each pass `accept`; throws std::runtime_error naming `flag`, the part
/// at fault and `expected` (what a value must be).
std::vector<double> parse_number_list(const std::string& text, const std::string& flag, bool (*accept)(double),
                                      const std::string& expected);

/// The cells of `across`^3 whose centres lie in the ball inscribed in that box and outside the
/// concentric ball of `hollow` times its radius (0: a solid ball), cubes of cell_size [m], one
/// material.
LatticeDesc ball_lattice(int across, double cell_size, const Material& material, double hollow = 0.0);

}  // namespace cubespring::app
