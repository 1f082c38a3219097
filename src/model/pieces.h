// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#pragma once

#include "cubespring/model.h"

namespace cubespring {

/// The pieces a body's cells make, cells sharing a node counted as joined (they move together):
/// more than 1 where a cut went through (cell_removal.h, face_split.h).
int count_pieces(const Model& model);

}  // namespace cubespring
