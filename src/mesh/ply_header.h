// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// A PLY file's header, checked before assimp reads the file. assimp 5.2's PLY reader trusts its
// header: without an `end_header` line it reads forever (a 21-byte file hung `voxelize` and a
// scene), a binary file whose `end_header` has one byte changed crashed it, and an element count
// larger than the file allocates gigabytes before it fails.
#pragma once

#include <string>

#include "cubespring/result.h"

namespace cubespring {

/// When the file at `path` is a PLY file to assimp (its extension is .ply, or it begins with
/// `ply`), checks that it begins with the line `ply`, that its header ends with `end_header` within its
/// first kPlyHeaderLimit bytes, that every header line is one the format has (format, element,
/// property, comment, obj_info) with known types and whole-number counts, and that the elements
/// it declares fit in the bytes after it (each element takes at least its properties' bytes in
/// binary, two characters a property in ASCII). The error names the file, the header line and
/// what was expected. Any other file passes unread past its first bytes.
Status check_ply_header(const std::string& path);

/// The most of a PLY file read as its header [bytes].
inline constexpr std::size_t kPlyHeaderLimit = 65536;

}  // namespace cubespring
