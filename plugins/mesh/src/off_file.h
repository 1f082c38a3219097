// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// An OFF file, checked before assimp reads it. assimp 5.2's OFF reader copies each line into a
// buffer of 4096 bytes without a bound (a 100,000-character comment line among the faces crashed
// it) and allocates the vertices and faces its counts declare before it reads them.
#pragma once

#include <cstddef>
#include <string>

#include "cubespring/result.h"

namespace cubespring {

/// The longest line assimp's OFF reader takes [characters, without the line end].
inline constexpr std::size_t kOffLineLimit = 4095;

/// When the file at `path` is an OFF file (its extension is .off, or its first word ends in OFF:
/// OFF, COFF, NOFF, STOFF, 4OFF, nOFF..., which is how assimp knows one), checks that no line is
/// longer than kOffLineLimit, that its vertex and face counts are whole numbers that the lines
/// after them can hold (one line each, empty lines skipped, as assimp reads them), and that each
/// face has 1 to 9 corners, each a vertex index below the vertex count. The error names the file,
/// the line and what was expected.
/// Any other file passes.
Status check_off_file(const std::string& path);

}  // namespace cubespring
