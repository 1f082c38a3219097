// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Checks of number flags that CLI11's own let through.
#pragma once

#include <CLI/CLI.hpp>

namespace cubespring::app {

/// A finite number > 0. (CLI11's PositiveNumber lets "nan" and "inf" through: neither is <= 0.)
CLI::Validator finite_positive_number();
/// A finite number (not empty: CLI11 reads "" as 0).
CLI::Validator finite_number();
/// A whole number >= 0 written as digits (CLI11 reads "-1" into an unsigned flag as 2^64 - 1).
CLI::Validator byte_count();
/// A number in (0, 1].
CLI::Validator fraction_number();

}  // namespace cubespring::app
