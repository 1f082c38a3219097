// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Surface repair before the inside test (docs/voxelize.md, section 2).
#include "cubespring/surface_repair.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <set>
#include <vector>

#include <Eigen/Geometry>

namespace cubespring {

namespace {

using Triangle = std::array<int, 3>;

Triangle triangle_at(const TriangleMesh& mesh, int t) {
  return {mesh.triangles(0, t), mesh.triangles(1, t), mesh.triangles(2, t)};
}

Eigen::Vector3d doubled_area_vector(const TriangleMesh& mesh, const Triangle& tri) {
  const Eigen::Vector3d a = mesh.vertices.col(tri[0]);
  return (mesh.vertices.col(tri[1]) - a).cross(mesh.vertices.col(tri[2]) - a);
}

bool is_degenerate(const TriangleMesh& mesh, const Triangle& tri) {
  if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0]) return true;
  return doubled_area_vector(mesh, tri).squaredNorm() == 0.0;
}

// One side of an undirected edge: the triangle using it and whether it runs from the lower vertex
// index to the higher one (two neighbours agree in orientation when their directions differ).
struct EdgeUse {
  std::int64_t key;
  int triangle;
  bool ascending;
};

std::vector<EdgeUse> edge_uses(const std::vector<Triangle>& triangles) {
  std::vector<EdgeUse> uses;
  uses.reserve(triangles.size() * 3);
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    for (int corner = 0; corner < 3; ++corner) {
      const int from = triangles[t][static_cast<std::size_t>(corner)];
      const int to = triangles[t][static_cast<std::size_t>((corner + 1) % 3)];
      const std::int64_t low = std::min(from, to);
      const std::int64_t high = std::max(from, to);
      uses.push_back({(low << 32) | high, static_cast<int>(t), from < to});
    }
  }
  std::sort(uses.begin(), uses.end(), [](const EdgeUse& a, const EdgeUse& b) {
    return a.key != b.key ? a.key < b.key : a.triangle < b.triangle;
  });
  return uses;
}

// Orientation of one part: each triangle's flip relative to its component's first triangle, then
// each component turned to the orientation most of its area had.
struct PartOrientation {
  std::vector<bool> flip;
  int components = 0;
};

PartOrientation orient_part(const TriangleMesh& mesh, const std::vector<Triangle>& triangles,
                            const std::vector<EdgeUse>& uses) {
  const std::size_t n = triangles.size();
  // neighbours across manifold edges, with whether the pair needs opposite flips to agree
  std::vector<std::vector<std::pair<int, bool>>> neighbours(n);
  for (std::size_t begin = 0; begin < uses.size();) {
    std::size_t end = begin;
    while (end < uses.size() && uses[end].key == uses[begin].key) ++end;
    if (end - begin == 2) {
      const EdgeUse& a = uses[begin];
      const EdgeUse& b = uses[begin + 1];
      const bool agree = a.ascending != b.ascending;
      neighbours[static_cast<std::size_t>(a.triangle)].push_back({b.triangle, !agree});
      neighbours[static_cast<std::size_t>(b.triangle)].push_back({a.triangle, !agree});
    }
    begin = end;
  }
  PartOrientation result;
  result.flip.assign(n, false);
  std::vector<bool> visited(n, false);
  std::vector<int> component;
  for (std::size_t seed = 0; seed < n; ++seed) {
    if (visited[seed]) continue;
    ++result.components;
    // breadth-first over the component; a Moebius-like conflict keeps the first choice
    component.assign(1, static_cast<int>(seed));
    visited[seed] = true;
    for (std::size_t head = 0; head < component.size(); ++head) {
      const auto t = static_cast<std::size_t>(component[head]);
      for (const auto& [other, opposite] : neighbours[t]) {
        const auto o = static_cast<std::size_t>(other);
        if (visited[o]) continue;
        visited[o] = true;
        result.flip[o] = result.flip[t] != opposite;
        component.push_back(other);
      }
    }
    double kept_area = 0.0;
    double flipped_area = 0.0;
    for (const int t : component) {
      const double area = doubled_area_vector(mesh, triangles[static_cast<std::size_t>(t)]).norm();
      (result.flip[static_cast<std::size_t>(t)] ? flipped_area : kept_area) += area;
    }
    if (flipped_area > kept_area) {
      for (const int t : component) result.flip[static_cast<std::size_t>(t)] = !result.flip[static_cast<std::size_t>(t)];
    }
  }
  return result;
}

void count_edge_problems(const std::vector<EdgeUse>& uses, SurfaceProblems& problems) {
  for (std::size_t begin = 0; begin < uses.size();) {
    std::size_t end = begin;
    while (end < uses.size() && uses[end].key == uses[begin].key) ++end;
    if (end - begin == 1) ++problems.open_edges;
    if (end - begin > 2) ++problems.non_manifold_edges;
    begin = end;
  }
}

}  // namespace

double signed_volume(const TriangleMesh& mesh, int first, int count) {
  // tetrahedra from the centroid of the part's corners: the same sum as from the origin for a
  // closed surface, and less cancellation for a body far from the origin
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (int t = first; t < first + count; ++t) {
    for (int corner = 0; corner < 3; ++corner) centre += mesh.vertices.col(mesh.triangles(corner, t));
  }
  if (count > 0) centre /= 3.0 * count;
  double six_volume = 0.0;
  for (int t = first; t < first + count; ++t) {
    const Eigen::Vector3d a = mesh.vertices.col(mesh.triangles(0, t)) - centre;
    const Eigen::Vector3d b = mesh.vertices.col(mesh.triangles(1, t)) - centre;
    const Eigen::Vector3d c = mesh.vertices.col(mesh.triangles(2, t)) - centre;
    six_volume += a.dot(b.cross(c));
  }
  return six_volume / 6.0;
}

RepairedSurface repair_surface(const TriangleMesh& mesh) {
  RepairedSurface repaired;
  repaired.mesh.vertices = mesh.vertices;
  std::vector<Triangle> output;
  output.reserve(static_cast<std::size_t>(mesh.num_triangles()));
  int flipped = 0;
  for (const MeshPart& part : parts_of(mesh)) {
    // drop degenerate and duplicated triangles (a duplicate with either orientation)
    std::vector<Triangle> kept;
    std::set<Triangle> seen;
    for (int t = part.first_triangle; t < part.first_triangle + part.triangle_count; ++t) {
      const Triangle tri = triangle_at(mesh, t);
      if (is_degenerate(mesh, tri)) {
        ++repaired.problems.degenerate_triangles;
        continue;
      }
      Triangle sorted = tri;
      std::sort(sorted.begin(), sorted.end());
      if (!seen.insert(sorted).second) {
        ++repaired.problems.duplicate_triangles;
        continue;
      }
      kept.push_back(tri);
    }
    const std::vector<EdgeUse> uses = edge_uses(kept);
    count_edge_problems(uses, repaired.problems);
    const PartOrientation orientation = orient_part(mesh, kept, uses);
    repaired.problems.components += orientation.components;
    for (std::size_t t = 0; t < kept.size(); ++t) {
      if (orientation.flip[t]) std::swap(kept[t][1], kept[t][2]);
    }
    MeshPart out_part = part;
    out_part.first_triangle = static_cast<int>(output.size());
    out_part.triangle_count = static_cast<int>(kept.size());
    repaired.mesh.parts.push_back(out_part);
    output.insert(output.end(), kept.begin(), kept.end());
    // a part written clockwise: turn it all
    Eigen::Matrix3Xi block(3, static_cast<Eigen::Index>(kept.size()));
    for (std::size_t t = 0; t < kept.size(); ++t) {
      for (int c = 0; c < 3; ++c) block(c, static_cast<Eigen::Index>(t)) = kept[t][static_cast<std::size_t>(c)];
    }
    TriangleMesh part_only{mesh.vertices, block, {}};
    double volume = signed_volume(part_only, 0, part_only.num_triangles());
    int part_flipped = 0;
    for (const bool f : orientation.flip) part_flipped += f ? 1 : 0;
    if (volume < 0.0) {
      volume = -volume;
      for (std::size_t t = out_part.first_triangle; t < output.size(); ++t) std::swap(output[t][1], output[t][2]);
      part_flipped = out_part.triangle_count - part_flipped;
    }
    flipped += part_flipped;
    repaired.part_volume.push_back(volume);
  }
  repaired.problems.flipped_triangles = flipped;
  repaired.mesh.triangles.resize(3, static_cast<Eigen::Index>(output.size()));
  for (std::size_t t = 0; t < output.size(); ++t) {
    for (int c = 0; c < 3; ++c) repaired.mesh.triangles(c, static_cast<Eigen::Index>(t)) = output[t][static_cast<std::size_t>(c)];
  }
  return repaired;
}

}  // namespace cubespring
