// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// A PLY file, checked before assimp reads it. assimp 5.2's PLY reader trusts its
// header: without an `end_header` line it reads forever (a 21-byte file hung `voxelize` and a
// scene), a binary file whose `end_header` has one byte changed crashed it, and an element count
// larger than the file allocates gigabytes before it fails.
#pragma once

#include <string>

#include "cubespring/result.h"

namespace cubespring {

/// When the file at `path` is a PLY file to assimp (its extension is .ply, or it begins with
/// `ply`), checks it as far as assimp would trust it: it begins with the line `ply`; its header
/// ends with `end_header` within its first kPlyHeaderLimit bytes; every header line is printable
/// text and one the format has (one `format ... 1.0` before the elements, distinct elements,
/// properties of known types, comments) with whole-number counts; and the body holds the elements
/// as the header lays them out (binary: each scalar's bytes, each list's count and items; ASCII:
/// a word a scalar, a list's count and its words). The error names the file, the header line and
/// what was expected. Any other file passes unread past its first bytes.
Status check_ply_file(const std::string& path);

/// The most of a PLY file read as its header [bytes].
inline constexpr std::size_t kPlyHeaderLimit = 65536;

}  // namespace cubespring
