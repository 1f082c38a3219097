// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The closed list of mesh formats load_mesh reads. assimp reads some forty; each reader is code a
// malformed file can crash or hang (its PLY, OFF and COLLADA readers did), so load_mesh lets
// through only the formats the project checks and fuzzes, and names them when it refuses a file.
#pragma once

#include <string>

#include "cubespring/result.h"

namespace cubespring {

enum class MeshFormat { kObj, kStl, kPly, kOff, kGltf, kCollada };

/// The list as an error message gives it: "OBJ (.obj), STL (.stl), ...".
const char* supported_mesh_formats();

/// The format of the file at `path`: by its extension when that names one of the list; else,
/// when its extension is one no reader of assimp's claims (none, or an unknown one), by its
/// first bytes as assimp would recognise it (a `ply` or `off` line, `solid`, the glTF binary's
/// magic, a `<COLLADA` element). An error names the file, its extension and the list: a format
/// off the list (an FBX file), or a file that is none of them.
Result<MeshFormat> mesh_format_of(const std::string& path);

}  // namespace cubespring
