// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#pragma once

#include <string>

#include "cubespring/result.h"
#include "cubespring/triangle_mesh.h"

/// Units are SI throughout the API: metres, kilograms, seconds, newtons, pascals.
namespace cubespring {

/// How to read a surface mesh file.
struct LoadOptions {
  double scale = 1.0;  ///< multiplies every coordinate: 0.001 for a file in millimetres, 0.01 for
                       ///< centimetres [m per file unit], > 0 and finite.
  /// The time the COLLADA and glTF readers may take, each in a process of its own [s]; 0: 10 s
  /// plus 2 s a megabyte of file.
  double reader_seconds = 0.0;
};

/// Reads a surface mesh file through assimp into one TriangleMesh in metres. The formats are a
/// closed list: OBJ (.obj), STL (.stl), PLY (.ply), OFF (.off), glTF (.gltf, .glb) and COLLADA
/// (.dae), by extension, or by content when the extension is none assimp knows (docs/voxelize.md
/// section 1); any other file is refused before assimp reads it, with the list in the error.
///
/// - Polygons are triangulated; points and lines are ignored. A file without any triangle (a
///   point cloud, a polyline) is an error.
/// - Every (node, mesh) reference of the scene graph becomes one MeshPart, in depth-first order:
///   its vertices are transformed by the node's accumulated transform, then multiplied by
///   options.scale. The part's name is the mesh's name, or the node's when the mesh has none;
///   its material_name is the material's name ("" for assimp's own "DefaultMaterial", which
///   stands for no material in the file). A transform that mirrors (negative determinant) has
///   its triangles reversed, so surfaces stay counter-clockwise seen from outside.
/// - Vertices with identical coordinates are joined across the whole mesh
///   (join_identical_vertices).
/// - Coordinates are kept as the file gives them, except that COLLADA files are converted to
///   metres by assimp when they declare a <unit>: load those with scale 1. A COLLADA <up_axis>
///   is ignored (no rotation is added). assimp (as packaged) reads coordinates and transforms as
///   32-bit floats: about 7 significant digits survive.
/// - COLLADA and glTF files are read in a child process (fork) with a time and memory limit, so
///   that a malformed one that crashes or hangs assimp's reader is an error, not the end of the
///   caller (docs/voxelize.md section 1).
///
/// Errors name the file: it cannot be opened, its format is off the list, assimp cannot read its format or reports a
/// parse error, it has no triangles, a coordinate is not finite, a face refers to a missing vertex, the COLLADA or glTF
/// reader crashed, overran its time or its memory; or options.scale is not a finite number > 0, or
/// options.reader_seconds is negative or not finite.
Result<TriangleMesh> load_mesh(const std::string& path, const LoadOptions& options = {});

}  // namespace cubespring
