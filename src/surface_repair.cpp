// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Surface repair before the inside test (docs/voxelize.md, section 2).
#include "cubespring/surface_repair.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <set>
#include <utility>
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

double signed_volume_of(const Eigen::Matrix3Xd& vertices, const std::vector<Triangle>& triangles) {
  Eigen::Matrix3Xi block(3, static_cast<Eigen::Index>(triangles.size()));
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    for (int c = 0; c < 3; ++c) block(c, static_cast<Eigen::Index>(t)) = triangles[t][static_cast<std::size_t>(c)];
  }
  return signed_volume(TriangleMesh{vertices, block, {}}, 0, static_cast<int>(triangles.size()));
}

int find_root(std::vector<int>& parent, int i) {
  while (parent[static_cast<std::size_t>(i)] != i) {
    parent[static_cast<std::size_t>(i)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
    i = parent[static_cast<std::size_t>(i)];
  }
  return i;
}

// Parts that share an edge are pieces of one surface (a file that splits a closed tool by
// material): they are one solid for orientation and the inside test. Solids are numbered in
// the order of their first part.
std::vector<int> solids_of_parts(const TriangleMesh& mesh, const std::vector<MeshPart>& parts) {
  std::vector<int> parent(parts.size());
  for (std::size_t p = 0; p < parts.size(); ++p) parent[p] = static_cast<int>(p);
  std::vector<std::pair<std::int64_t, int>> edge_part;
  for (std::size_t p = 0; p < parts.size(); ++p) {
    for (int t = parts[p].first_triangle; t < parts[p].first_triangle + parts[p].triangle_count; ++t) {
      for (int corner = 0; corner < 3; ++corner) {
        const std::int64_t a = mesh.triangles(corner, t);
        const std::int64_t b = mesh.triangles((corner + 1) % 3, t);
        if (a != b) edge_part.push_back({(std::min(a, b) << 32) | std::max(a, b), static_cast<int>(p)});
      }
    }
  }
  std::sort(edge_part.begin(), edge_part.end());
  for (std::size_t i = 1; i < edge_part.size(); ++i) {
    if (edge_part[i].first != edge_part[i - 1].first) continue;
    const int a = find_root(parent, edge_part[i].second);
    const int b = find_root(parent, edge_part[i - 1].second);
    if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
  }
  std::vector<int> solid(parts.size());
  std::vector<int> number_of_root(parts.size(), -1);
  int count = 0;
  for (std::size_t p = 0; p < parts.size(); ++p) {
    const auto root = static_cast<std::size_t>(find_root(parent, static_cast<int>(p)));
    if (number_of_root[root] < 0) number_of_root[root] = count++;
    solid[p] = number_of_root[root];
  }
  return solid;
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
  const std::vector<MeshPart> parts = parts_of(mesh);
  RepairedSurface repaired;
  repaired.mesh.vertices = mesh.vertices;
  repaired.part_solid = solids_of_parts(mesh, parts);
  const int solid_count = parts.empty() ? 0 : *std::max_element(repaired.part_solid.begin(), repaired.part_solid.end()) + 1;
  repaired.solid_parts.assign(static_cast<std::size_t>(solid_count), {});
  for (std::size_t p = 0; p < parts.size(); ++p) {
    repaired.solid_parts[static_cast<std::size_t>(repaired.part_solid[p])].push_back(static_cast<int>(p));
  }
  // each solid's triangles, in file order, after dropping degenerate and duplicated ones (a
  // duplicate with either orientation); kept_part remembers which part each goes back to
  std::vector<std::vector<Triangle>> part_triangles(parts.size());
  repaired.solid_volume.assign(static_cast<std::size_t>(solid_count), 0.0);
  int flipped = 0;
  for (int solid = 0; solid < solid_count; ++solid) {
    std::vector<Triangle> kept;
    std::vector<int> kept_part;
    std::set<Triangle> seen;
    for (const int p : repaired.solid_parts[static_cast<std::size_t>(solid)]) {
      const MeshPart& part = parts[static_cast<std::size_t>(p)];
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
        kept_part.push_back(p);
      }
    }
    const std::vector<EdgeUse> uses = edge_uses(kept);
    count_edge_problems(uses, repaired.problems);
    const PartOrientation orientation = orient_part(mesh, kept, uses);
    repaired.problems.components += orientation.components;
    int solid_flipped = 0;
    for (std::size_t t = 0; t < kept.size(); ++t) {
      if (!orientation.flip[t]) continue;
      std::swap(kept[t][1], kept[t][2]);
      ++solid_flipped;
    }
    // a solid written clockwise: turn it all
    double volume = signed_volume_of(mesh.vertices, kept);
    if (volume < 0.0) {
      volume = -volume;
      for (Triangle& tri : kept) std::swap(tri[1], tri[2]);
      solid_flipped = static_cast<int>(kept.size()) - solid_flipped;
    }
    flipped += solid_flipped;
    repaired.solid_volume[static_cast<std::size_t>(solid)] = volume;
    for (std::size_t t = 0; t < kept.size(); ++t) part_triangles[static_cast<std::size_t>(kept_part[t])].push_back(kept[t]);
  }
  repaired.problems.flipped_triangles = flipped;
  // back in file order, part by part
  int total = 0;
  for (const auto& list : part_triangles) total += static_cast<int>(list.size());
  repaired.mesh.triangles.resize(3, total);
  int next = 0;
  for (std::size_t p = 0; p < parts.size(); ++p) {
    MeshPart out_part = parts[p];
    out_part.first_triangle = next;
    out_part.triangle_count = static_cast<int>(part_triangles[p].size());
    repaired.mesh.parts.push_back(out_part);
    for (const Triangle& tri : part_triangles[p]) {
      for (int c = 0; c < 3; ++c) repaired.mesh.triangles(c, next) = tri[static_cast<std::size_t>(c)];
      ++next;
    }
  }
  return repaired;
}

}  // namespace cubespring
