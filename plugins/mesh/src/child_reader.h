// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// A reader that a malformed file can crash or hang, run in a child process with a time and a
// memory limit: assimp's COLLADA and glTF readers, which nothing checks before they read, and its
// PLY reader, which a checked file still made ask for 34 GB (docs/voxelize.md section 1). The
// child reads the mesh and sends it back through a pipe; a crash, a hang or a runaway allocation
// in it is an error naming the file and the reader, and the caller's process goes on.
#pragma once

#include <functional>
#include <string>

#include "cubespring/result.h"
#include "cubespring/triangle_mesh.h"

namespace cubespring {

struct ChildLimits {
  double seconds = 10.0;           ///< wall time the reader may take [s]
  std::uint64_t memory_bytes = 0;  ///< address space it may take [bytes]; 0: no limit
};

/// `read()` run in a child process of this one, its result brought back. `reader` names the
/// reader in messages ("assimp's COLLADA reader"), `path` the file.
Result<TriangleMesh> read_in_child(const std::string& path, const std::string& reader, const ChildLimits& limits,
                                   const std::function<Result<TriangleMesh>()>& read);

}  // namespace cubespring
