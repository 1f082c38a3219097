// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// A contact surface as fine as the cells, whatever the visual mesh's tessellation: a flat-faced
// rigid body (a table) meets the surface's vertices only, so where a visual mesh's triangles span
// several cells, the cells between its vertices sank through the table and the cells holding them
// carried the organ's weight as point loads (the shared liver on 4 mm cells blew up).
#pragma once

#include "cubespring/triangle_mesh.h"

namespace cubespring::bullet {

/// The mesh with every edge longer than `max_edge` [m] split at its midpoint, again and again, until
/// none is (conforming: a split edge is split in both its triangles, each triangle cut into 2, 3
/// or 4 counter-clockwise as it was). The mesh's vertices come first, in their order, then the
/// midpoints; the result has one part. `max_edge` > 0; a mesh with no longer edge comes back as it
/// was (with one part).
TriangleMesh split_long_edges(const TriangleMesh& mesh, double max_edge);

}  // namespace cubespring::bullet
