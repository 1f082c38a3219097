// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "cubespring/triangle_mesh.h"

#include <array>
#include <cmath>
#include <map>
#include <sstream>

namespace cubespring {

namespace {

std::string prefixed(const std::string& source, const std::string& message) {
  return source.empty() ? message : source + ": " + message;
}

}  // namespace

Status validate(const TriangleMesh& mesh, const std::string& source) {
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    if (!mesh.vertices.col(v).allFinite()) {
      std::ostringstream out;
      out << "vertex " << v << " has a coordinate that is not a finite number ("
          << mesh.vertices(0, v) << ", " << mesh.vertices(1, v) << ", " << mesh.vertices(2, v) << ")";
      return Status::error(prefixed(source, out.str()));
    }
  }
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    for (int corner = 0; corner < 3; ++corner) {
      const int v = mesh.triangles(corner, t);
      if (v < 0 || v >= mesh.num_vertices()) {
        std::ostringstream out;
        out << "triangle " << t << " refers to vertex " << v << ", but the mesh has "
            << mesh.num_vertices() << " vertices (expected 0.." << mesh.num_vertices() - 1 << ")";
        return Status::error(prefixed(source, out.str()));
      }
    }
  }
  int next_triangle = 0;
  for (std::size_t p = 0; p < mesh.parts.size(); ++p) {
    const MeshPart& part = mesh.parts[p];
    if (part.first_triangle != next_triangle || part.triangle_count < 0) {
      std::ostringstream out;
      out << "part " << p << " ('" << part.name << "') covers triangles " << part.first_triangle
          << " + " << part.triangle_count << "; expected to start at " << next_triangle;
      return Status::error(prefixed(source, out.str()));
    }
    next_triangle += part.triangle_count;
  }
  if (!mesh.parts.empty() && next_triangle != mesh.num_triangles()) {
    std::ostringstream out;
    out << "parts cover " << next_triangle << " triangles of " << mesh.num_triangles();
    return Status::error(prefixed(source, out.str()));
  }
  return {};
}

std::vector<MeshPart> parts_of(const TriangleMesh& mesh) {
  if (!mesh.parts.empty()) return mesh.parts;
  return {MeshPart{"", "", 0, mesh.num_triangles()}};
}

TriangleMesh join_identical_vertices(const TriangleMesh& mesh) {
  // a map on exact coordinates: joining nearly equal vertices would be a tolerance choice,
  // and the voxelizer does not need it (its inside test is exact on shared edges).
  std::map<std::array<double, 3>, int> index_of;
  std::vector<int> new_index(static_cast<std::size_t>(mesh.num_vertices()));
  TriangleMesh joined;
  joined.parts = mesh.parts;
  std::vector<Eigen::Vector3d> kept;
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    const std::array<double, 3> key{mesh.vertices(0, v), mesh.vertices(1, v), mesh.vertices(2, v)};
    const auto [it, inserted] = index_of.emplace(key, static_cast<int>(kept.size()));
    if (inserted) kept.push_back(mesh.vertices.col(v));
    new_index[static_cast<std::size_t>(v)] = it->second;
  }
  joined.vertices.resize(3, static_cast<Eigen::Index>(kept.size()));
  for (std::size_t v = 0; v < kept.size(); ++v) joined.vertices.col(static_cast<Eigen::Index>(v)) = kept[v];
  joined.triangles.resize(3, mesh.num_triangles());
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    for (int corner = 0; corner < 3; ++corner) {
      const int v = mesh.triangles(corner, t);
      joined.triangles(corner, t) =
          (v >= 0 && v < mesh.num_vertices()) ? new_index[static_cast<std::size_t>(v)] : v;
    }
  }
  return joined;
}

TriangleMesh part_mesh(const TriangleMesh& mesh, int part) {
  const std::vector<MeshPart> parts = parts_of(mesh);
  const MeshPart& chosen = parts.at(static_cast<std::size_t>(part));
  TriangleMesh result;
  result.vertices = mesh.vertices;
  result.triangles = mesh.triangles.middleCols(chosen.first_triangle, chosen.triangle_count);
  result.parts = {MeshPart{chosen.name, chosen.material_name, 0, chosen.triangle_count}};
  return result;
}

}  // namespace cubespring
