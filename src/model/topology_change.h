// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// What a change of a body's cells (cell_removal.h, face_split.h) checks and reports.
#pragma once

#include "cubespring/constraints.h"
#include "cubespring/model.h"
#include "cubespring/result.h"
#include "cubespring/state.h"

namespace cubespring {

/// The pieces a body's cells make, cells sharing a node counted as joined (they move together):
/// more than 1 where a cut went through (cell_removal.h, face_split.h).
int count_pieces(const Model& model);

/// An error naming the counts when `state` or `constraints` is not for `model`'s nodes.
Status check_body_sizes(const Model& model, const State& state, const Constraints& constraints);

}  // namespace cubespring
