// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#pragma once

#include <Eigen/Core>

#include "cubespring/triangle_mesh.h"

/// Units are SI throughout the API: metres, kilograms, seconds, newtons, pascals.
namespace cubespring {

/// Closed surfaces with outward, counter-clockwise triangles, one part each: shapes for tests,
/// benchmarks and quick scenes.

/// A sphere [m] from an octahedron whose faces are split in 4, `subdivisions` times
/// (8 * 4^subdivisions triangles); symmetric under the 48 symmetries of the axes about its centre.
TriangleMesh sphere_mesh(double radius, int subdivisions, const Eigen::Vector3d& centre = Eigen::Vector3d::Zero());

/// A torus about the z axis [m]: major radius R (centre of the tube), minor radius r (the tube),
/// 2 * around * tube triangles.
TriangleMesh torus_mesh(double major_radius, double minor_radius, int around, int tube,
                        const Eigen::Vector3d& centre = Eigen::Vector3d::Zero());

/// The box [lower, upper] [m], 12 triangles.
TriangleMesh box_mesh(const Eigen::Vector3d& lower, const Eigen::Vector3d& upper);

/// The triangles of `inner` turned inside-out and appended to `outer` in the same part: the
/// hollow solid between two nested closed surfaces.
TriangleMesh hollow_mesh(const TriangleMesh& outer, const TriangleMesh& inner);

/// The parts of `b` appended after those of `a` (one file with several meshes).
TriangleMesh combine_meshes(const TriangleMesh& a, const TriangleMesh& b);

}  // namespace cubespring
