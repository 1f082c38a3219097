// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Parsing of the list-valued flags shared by the commands ("16,4,4", "0.01" or "0.01,0.01,0.02").
#pragma once

#include <string>

#include <Eigen/Core>

#include "cubespring/result.h"

namespace cubespring::app {

/// "NX,NY,NZ" with each count a whole number >= 1; flag names the argument in the error.
Result<Eigen::Vector3i> parse_counts(const std::string& flag, const std::string& text);
/// "H" (a cube) or "HX,HY,HZ", each a number > 0 [m].
Result<Eigen::Vector3d> parse_sizes(const std::string& flag, const std::string& text);

}  // namespace cubespring::app
