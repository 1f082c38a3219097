// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// What the bench commands share: the machine they ran on, and their list of block sizes.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace cubespring::app {

/// The CPU's name, for the record of "this machine" ("" when the system does not say).
std::string cpu_name();

/// "NX,NY,NZ;NX,NY,NZ;..." as block sizes; throws std::runtime_error naming --sizes.
std::vector<Eigen::Vector3i> parse_size_list(const std::string& text);

}  // namespace cubespring::app
