// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "cubespring/triangle_mesh.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <vector>

namespace cubespring {

namespace {

std::string prefixed(const std::string& source, const std::string& message) {
  return source.empty() ? message : source + ": " + message;
}

// The bits of a coordinate as join_identical_vertices compares them: -0.0 is the same point as
// 0.0 (== says so, and so did the ordered map this replaced), any other value is its exact bit
// pattern (a NaN, which validate() rejects, then equals only the same NaN).
std::uint64_t coordinate_bits(double x) {
  if (x == 0.0) x = 0.0;
  std::uint64_t bits = 0;
  std::memcpy(&bits, &x, sizeof bits);
  return bits;
}

// The first vertex with each vertex's coordinates: a hash table on their bits, with open
// addressing (one flat array, probed linearly). An ordered map on the coordinates cost a few
// pointer hops per vertex, most of what loading a mesh spent beyond assimp.
class FirstWithCoordinates {
 public:
  explicit FirstWithCoordinates(const Eigen::Matrix3Xd& vertices) : vertices_(vertices) {
    // at most half full, so that probe runs stay short
    std::size_t capacity = 16;
    while (capacity < 2 * static_cast<std::size_t>(vertices.cols())) capacity *= 2;
    slots_.assign(capacity, Slot{});
    mask_ = capacity - 1;
  }

  // The first vertex seen with v's coordinates, or v itself (then remembered) when there is none.
  int find_or_add(int v) {
    const Key key = key_of(v);
    const std::uint64_t h = hash(key);
    const auto tag = static_cast<std::uint32_t>(h >> 32);
    for (std::size_t i = static_cast<std::size_t>(h) & mask_;; i = (i + 1) & mask_) {
      Slot& slot = slots_[i];
      if (slot.vertex == kEmpty) {
        slot = {v, tag};
        return v;
      }
      if (slot.tag == tag && key_of(slot.vertex) == key) return slot.vertex;
    }
  }

 private:
  using Key = std::array<std::uint64_t, 3>;
  static constexpr int kEmpty = -1;
  // A vertex and bits of its hash: most probes that meet another vertex are told apart by the
  // tag, without reading that vertex's coordinates from far away in memory.
  struct Slot {
    int vertex = kEmpty;
    std::uint32_t tag = 0;
  };

  Key key_of(int v) const {
    return {coordinate_bits(vertices_(0, v)), coordinate_bits(vertices_(1, v)), coordinate_bits(vertices_(2, v))};
  }
  // Mixes every bit into all others: coordinates of nearby vertices differ mostly in their low
  // mantissa bits, and the table index takes the hash's low bits, the tag its high ones.
  static std::uint64_t hash(const Key& key) {
    std::uint64_t h = 0;
    for (const std::uint64_t word : key) {
      h = (h ^ word) * 0x9e3779b97f4a7c15ULL;
      h ^= h >> 32;
    }
    return h;
  }

  const Eigen::Matrix3Xd& vertices_;
  std::vector<Slot> slots_;
  std::size_t mask_ = 0;
};

}  // namespace

Status validate(const TriangleMesh& mesh, const std::string& source) {
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    if (!mesh.vertices.col(v).allFinite()) {
      std::ostringstream out;
      out << "vertex " << v << " has a coordinate that is not a finite number (" << mesh.vertices(0, v) << ", "
          << mesh.vertices(1, v) << ", " << mesh.vertices(2, v) << ")";
      return Status::error(prefixed(source, out.str()));
    }
  }
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    for (int corner = 0; corner < 3; ++corner) {
      const int v = mesh.triangles(corner, t);
      if (v < 0 || v >= mesh.num_vertices()) {
        std::ostringstream out;
        out << "triangle " << t << " refers to vertex " << v << ", but the mesh has " << mesh.num_vertices()
            << " vertices (expected 0.." << mesh.num_vertices() - 1 << ")";
        return Status::error(prefixed(source, out.str()));
      }
    }
  }
  int next_triangle = 0;
  for (std::size_t p = 0; p < mesh.parts.size(); ++p) {
    const MeshPart& part = mesh.parts[p];
    if (part.first_triangle != next_triangle || part.triangle_count < 0) {
      std::ostringstream out;
      out << "part " << p << " ('" << part.name << "') covers triangles " << part.first_triangle << " + "
          << part.triangle_count << "; expected to start at " << next_triangle;
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
  // exact coordinates only: joining nearly equal vertices would be a tolerance choice, and the
  // voxelizer does not need it (its inside test is exact on shared edges)
  const int count = mesh.num_vertices();
  FirstWithCoordinates first_with(mesh.vertices);
  std::vector<int> new_index(static_cast<std::size_t>(count));
  std::vector<int> kept;  // the original index of each joined vertex, in order of first appearance
  for (int v = 0; v < count; ++v) {
    const int first = first_with.find_or_add(v);
    if (first == v) {
      new_index[static_cast<std::size_t>(v)] = static_cast<int>(kept.size());
      kept.push_back(v);
    } else {
      new_index[static_cast<std::size_t>(v)] = new_index[static_cast<std::size_t>(first)];
    }
  }
  TriangleMesh joined;
  joined.parts = mesh.parts;
  joined.vertices.resize(3, static_cast<Eigen::Index>(kept.size()));
  for (std::size_t v = 0; v < kept.size(); ++v) {
    joined.vertices.col(static_cast<Eigen::Index>(v)) = mesh.vertices.col(kept[v]);
  }
  joined.triangles.resize(3, mesh.num_triangles());
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    for (int corner = 0; corner < 3; ++corner) {
      const int v = mesh.triangles(corner, t);
      joined.triangles(corner, t) = (v >= 0 && v < count) ? new_index[static_cast<std::size_t>(v)] : v;
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
