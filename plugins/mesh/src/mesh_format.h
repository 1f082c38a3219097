// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The closed list of mesh formats load_mesh reads. assimp reads some forty; each reader is code a
// malformed file can crash or hang (its PLY, OFF and COLLADA readers did), so load_mesh lets
// through only the formats the project checks and fuzzes, and names them when it refuses a file.
#pragma once

#include <string>

#include "cubespring/result.h"

namespace Assimp {
class Importer;
}

namespace cubespring {

enum class MeshFormat { kObj, kStl, kPly, kOff, kGltf, kCollada };

/// The list as an error message gives it: "OBJ (.obj), STL (.stl), ...".
const char* supported_mesh_formats();

/// The format of the file at `path`: by its extension (from the last dot of its name) when that
/// names one of the list; else, when its extension is one no reader of assimp's claims (none, or an
/// unknown one), by a mark at its start (its first word `ply`, `off` or `solid`, the glTF binary's
/// magic, a `<COLLADA` element in its first 200 bytes: stricter than assimp's own sniffing). An error
/// names the file, its extension and the list: a format off the list (an FBX file), a file that is
/// none of them, or one that cannot be opened.
Result<MeshFormat> mesh_format_of(const std::string& path);

/// Leaves `importer` only the readers of `format` (both of glTF's), so that no other reader of
/// assimp's sees the file, whatever its name or content: assimp tries every reader by content when
/// the one its extension names declines, and for a file of an unknown extension it asks them in its
/// own order (its 3DS reader before the COLLADA one).
void keep_only_readers_of(Assimp::Importer& importer, MeshFormat format);

}  // namespace cubespring
