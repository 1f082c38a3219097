// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Surfaces for tools given by a shape rather than a mesh file, in the tool's own frame.
#pragma once

#include "cubespring/triangle_mesh.h"

namespace cubespring::scene {

/// A closed capsule along +z whose lowest point (the tip) is at the origin [m]: hemispheres of
/// `radius` at both ends, `length` >= 2 radius overall; `around` vertices per ring.
TriangleMesh capsule_mesh(double radius, double length, int around = 24, int cap_rings = 6);

}  // namespace cubespring::scene
