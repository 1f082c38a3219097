// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Surface repair before the inside test (docs/voxelize.md, section 2).
#include "cubespring/surface_repair.h"

#include <algorithm>
#include <array>
#include <climits>
#include <cstdint>
#include <numeric>
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

// ---- A solid's triangles --------------------------------------------------------------------

// The triangles of one solid that take part in orientation, in file order.
struct SolidTriangles {
  std::vector<Triangle> triangles;
  std::vector<int> part;     // the part each comes from
  std::vector<double> area;  // |doubled area vector|: each triangle's weight in its component's vote
};

// The solid's triangles without the degenerate ones (two corners on one vertex, or no area),
// which are counted. The area found here is kept for the orientation vote.
SolidTriangles nondegenerate_triangles(const TriangleMesh& mesh, const std::vector<MeshPart>& parts,
                                       const std::vector<int>& members, SurfaceProblems& problems) {
  SolidTriangles solid;
  std::size_t count = 0;
  for (const int p : members) count += static_cast<std::size_t>(parts[static_cast<std::size_t>(p)].triangle_count);
  solid.triangles.reserve(count);
  solid.part.reserve(count);
  solid.area.reserve(count);
  for (const int p : members) {
    const MeshPart& part = parts[static_cast<std::size_t>(p)];
    for (int t = part.first_triangle; t < part.first_triangle + part.triangle_count; ++t) {
      const Triangle tri = triangle_at(mesh, t);
      if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0]) {
        ++problems.degenerate_triangles;
        continue;
      }
      const Eigen::Vector3d doubled_area = doubled_area_vector(mesh, tri);
      if (doubled_area.squaredNorm() == 0.0) {
        ++problems.degenerate_triangles;
        continue;
      }
      solid.triangles.push_back(tri);
      solid.part.push_back(p);
      solid.area.push_back(doubled_area.norm());
    }
  }
  return solid;
}

// ---- Edges ----------------------------------------------------------------------------------

// One side of an undirected edge: its higher vertex (its lower one is the row it is filed
// under), the triangle using it and whether that triangle runs it from the lower vertex to the
// higher one (two neighbours agree in orientation when their directions differ). Packed in 8
// bytes: a million-triangle solid has three million uses.
class EdgeUse {
 public:
  EdgeUse() = default;
  EdgeUse(int high, int triangle, bool ascending)
      : high_(high), triangle_and_direction_(static_cast<std::uint32_t>(triangle) << 1 | (ascending ? 1U : 0U)) {}
  int high() const { return high_; }
  int triangle() const { return static_cast<int>(triangle_and_direction_ >> 1); }
  bool ascending() const { return (triangle_and_direction_ & 1U) != 0; }

 private:
  int high_ = 0;
  std::uint32_t triangle_and_direction_ = 0;
};

// Every edge use of a list of triangles, grouped by edge: a row per lower vertex (compressed
// rows, filled by counting), each row by higher vertex, then by triangle. That order (which
// triangles share an edge, in which order a triangle meets its neighbours) decides everything
// downstream; it is the (edge, triangle) order a std::sort of all uses gave, in linear time for
// rows of bounded length.
// Vertices are numbered densely in the table: their index less the lowest one, or, when the
// triangles use few of a wide range of indices (a small solid of a big mesh), their rank among
// those they use, so that the rows never outnumber the corners. Both keep the order of indices.
class EdgeTable {
 public:
  explicit EdgeTable(const std::vector<Triangle>& triangles) {
    const std::vector<Triangle> ranked = number_vertices(triangles);
    const std::vector<Triangle>& table_triangles = used_.empty() ? triangles : ranked;
    const int offset = used_.empty() ? first_ : 0;
    // count each row's uses, then file them in triangle order
    row_start_.assign(row_count_ + 1, 0);
    for_each_use(table_triangles, offset,
                 [&](int low, int, int, bool) { ++row_start_[static_cast<std::size_t>(low) + 1]; });
    std::partial_sum(row_start_.begin(), row_start_.end(), row_start_.begin());
    uses_.resize(row_start_.back());
    std::vector<std::size_t> next(row_start_.begin(), row_start_.end() - 1);
    for_each_use(table_triangles, offset, [&](int low, int high, int t, bool ascending) {
      uses_[next[static_cast<std::size_t>(low)]++] = EdgeUse(high, t, ascending);
    });
    for (std::size_t row = 0; row < row_count_; ++row) sort_row(row);
  }

  const std::vector<EdgeUse>& uses() const { return uses_; }
  // The mesh's index of the table's vertex v.
  int vertex(int v) const { return used_.empty() ? first_ + v : used_[static_cast<std::size_t>(v)]; }

  // Calls fn(row, begin, end) for every edge: its lower vertex and the index range of its uses.
  template <typename Fn>
  void for_each_edge(Fn fn) const {
    for (std::size_t row = 0; row < row_count_; ++row) {
      const std::size_t row_end = row_start_[row + 1];
      for (std::size_t begin = row_start_[row]; begin < row_end;) {
        std::size_t end = begin + 1;
        while (end < row_end && uses_[end].high() == uses_[begin].high()) ++end;
        fn(static_cast<int>(row), begin, end);
        begin = end;
      }
    }
  }

  // Drops the uses of triangles whose new_index is negative and renumbers the others, in order.
  void keep_triangles(const std::vector<int>& new_index) {
    std::size_t kept = 0;
    for (std::size_t row = 0; row < row_count_; ++row) {
      const std::size_t begin = row_start_[row];
      const std::size_t end = row_start_[row + 1];
      row_start_[row] = kept;
      for (std::size_t u = begin; u < end; ++u) {
        const int t = new_index[static_cast<std::size_t>(uses_[u].triangle())];
        if (t >= 0) uses_[kept++] = EdgeUse(uses_[u].high(), t, uses_[u].ascending());
      }
    }
    row_start_[row_count_] = kept;
    uses_.resize(kept);
  }

 private:
  // Chooses the numbering; returns the triangles with their vertices ranked when that is it.
  std::vector<Triangle> number_vertices(const std::vector<Triangle>& triangles) {
    if (triangles.empty()) return {};
    int low = INT_MAX;
    int high = INT_MIN;
    for (const Triangle& tri : triangles) {
      low = std::min({low, tri[0], tri[1], tri[2]});
      high = std::max({high, tri[0], tri[1], tri[2]});
    }
    first_ = low;
    row_count_ = static_cast<std::size_t>(static_cast<std::int64_t>(high) - low + 1);
    if (row_count_ <= 3 * triangles.size()) return {};
    for (const Triangle& tri : triangles) used_.insert(used_.end(), tri.begin(), tri.end());
    std::sort(used_.begin(), used_.end());
    used_.erase(std::unique(used_.begin(), used_.end()), used_.end());
    row_count_ = used_.size();
    std::vector<Triangle> ranked(triangles.size());
    for (std::size_t t = 0; t < triangles.size(); ++t) {
      for (std::size_t corner = 0; corner < 3; ++corner) {
        const int v = triangles[t][corner];
        ranked[t][corner] = static_cast<int>(std::lower_bound(used_.begin(), used_.end(), v) - used_.begin());
      }
    }
    return ranked;
  }

  // fn(low, high, triangle, ascending) for each edge of each triangle, in triangle order, with
  // vertices less offset; an edge from a vertex to itself (a degenerate triangle's) is no edge
  template <typename Fn>
  static void for_each_use(const std::vector<Triangle>& triangles, int offset, Fn fn) {
    for (std::size_t t = 0; t < triangles.size(); ++t) {
      for (std::size_t corner = 0; corner < 3; ++corner) {
        const int from = triangles[t][corner] - offset;
        const int to = triangles[t][(corner + 1) % 3] - offset;
        if (from != to) fn(std::min(from, to), std::max(from, to), static_cast<int>(t), from < to);
      }
    }
  }

  // By higher vertex, keeping triangle order: a row holds a handful of uses (about a vertex's
  // valence), so an insertion sort; a long one (a fan around a vertex) a stable merge sort.
  void sort_row(std::size_t row) {
    const auto begin = uses_.begin() + static_cast<std::ptrdiff_t>(row_start_[row]);
    const auto end = uses_.begin() + static_cast<std::ptrdiff_t>(row_start_[row + 1]);
    if (end - begin > 32) {
      std::stable_sort(begin, end, [](const EdgeUse& a, const EdgeUse& b) { return a.high() < b.high(); });
      return;
    }
    for (auto i = begin + 1; i < end; ++i) {
      const EdgeUse use = *i;
      auto j = i;
      for (; j > begin && (j - 1)->high() > use.high(); --j) *j = *(j - 1);
      *j = use;
    }
  }

  int first_ = 0;
  std::vector<int> used_;  // the vertices used, when numbered by rank
  std::size_t row_count_ = 0;
  std::vector<std::size_t> row_start_;
  std::vector<EdgeUse> uses_;
};

// Which triangles repeat the vertex set of an earlier one (in either orientation). Two such
// triangles share all their edges; each triangle is looked at on one, the edge between its two
// lowest vertices, where its repeats are the triangles with the same third vertex.
std::vector<bool> repeated_triangles(const EdgeTable& edges, const std::vector<Triangle>& triangles) {
  std::vector<bool> repeated(triangles.size(), false);
  std::vector<std::pair<int, int>> on_lowest_edge;  // (third vertex, triangle)
  const std::vector<EdgeUse>& uses = edges.uses();
  edges.for_each_edge([&](int row, std::size_t begin, std::size_t end) {
    if (end - begin < 2) return;
    const std::int64_t low = edges.vertex(row);
    const std::int64_t high = edges.vertex(uses[begin].high());
    on_lowest_edge.clear();
    for (std::size_t u = begin; u < end; ++u) {
      const Triangle& tri = triangles[static_cast<std::size_t>(uses[u].triangle())];
      const std::int64_t third = std::int64_t{tri[0]} + tri[1] + tri[2] - low - high;
      if (third > high) on_lowest_edge.push_back({static_cast<int>(third), uses[u].triangle()});
    }
    if (on_lowest_edge.size() < 2) return;
    std::sort(on_lowest_edge.begin(), on_lowest_edge.end());
    for (std::size_t i = 1; i < on_lowest_edge.size(); ++i) {
      if (on_lowest_edge[i].first == on_lowest_edge[i - 1].first) {
        repeated[static_cast<std::size_t>(on_lowest_edge[i].second)] = true;
      }
    }
  });
  return repeated;
}

// Drops the triangles that repeat an earlier one, from the solid and from its edge table,
// counting them; the first of each stays.
void drop_repeats(SolidTriangles& solid, EdgeTable& edges, SurfaceProblems& problems) {
  const std::vector<bool> repeated = repeated_triangles(edges, solid.triangles);
  if (std::find(repeated.begin(), repeated.end(), true) == repeated.end()) return;  // the usual case
  std::vector<int> new_index(solid.triangles.size(), -1);
  std::size_t next = 0;
  for (std::size_t t = 0; t < solid.triangles.size(); ++t) {
    if (repeated[t]) {
      ++problems.duplicate_triangles;
      continue;
    }
    new_index[t] = static_cast<int>(next);
    solid.triangles[next] = solid.triangles[t];
    solid.part[next] = solid.part[t];
    solid.area[next] = solid.area[t];
    ++next;
  }
  solid.triangles.resize(next);
  solid.part.resize(next);
  solid.area.resize(next);
  edges.keep_triangles(new_index);
}

void count_edge_problems(const EdgeTable& edges, SurfaceProblems& problems) {
  edges.for_each_edge([&](int, std::size_t begin, std::size_t end) {
    if (end - begin == 1) ++problems.open_edges;
    if (end - begin > 2) ++problems.non_manifold_edges;
  });
}

// A neighbour across a two-triangle edge, and whether the pair needs opposite flips to agree
// (packed like EdgeUse).
class Neighbour {
 public:
  Neighbour() = default;
  Neighbour(int triangle, bool opposite)
      : triangle_and_opposite_(static_cast<std::uint32_t>(triangle) << 1 | (opposite ? 1U : 0U)) {}
  int triangle() const { return static_cast<int>(triangle_and_opposite_ >> 1); }
  bool opposite() const { return (triangle_and_opposite_ & 1U) != 0; }

 private:
  std::uint32_t triangle_and_opposite_ = 0;
};

// Each triangle's neighbours across its two-triangle edges. A triangle has three edges, so at
// most three neighbours: fixed slots in one flat array rather than a list (an allocation) per
// triangle. They fill in edge order, the order the orientation search visits them in.
struct NeighbourTable {
  std::vector<std::array<Neighbour, 3>> slots;
  std::vector<std::uint8_t> count;
};

NeighbourTable manifold_neighbours(const EdgeTable& edges, std::size_t triangle_count) {
  NeighbourTable table;
  table.slots.resize(triangle_count);
  table.count.assign(triangle_count, 0);
  const auto add = [&](int t, Neighbour n) {
    const auto i = static_cast<std::size_t>(t);
    table.slots[i][table.count[i]++] = n;
  };
  const std::vector<EdgeUse>& uses = edges.uses();
  edges.for_each_edge([&](int, std::size_t begin, std::size_t end) {
    if (end - begin != 2) return;
    const EdgeUse& a = uses[begin];
    const EdgeUse& b = uses[begin + 1];
    const bool opposite = a.ascending() == b.ascending();
    add(a.triangle(), Neighbour(b.triangle(), opposite));
    add(b.triangle(), Neighbour(a.triangle(), opposite));
  });
  return table;
}

// ---- Orientation ----------------------------------------------------------------------------

// Orientation of one solid: each triangle's flip relative to its component's first triangle,
// then each component turned to the orientation most of its area had.
struct Orientation {
  std::vector<std::uint8_t> flip;
  int components = 0;
};

Orientation orient(const NeighbourTable& neighbours, const std::vector<double>& area) {
  const std::size_t n = area.size();
  Orientation result;
  result.flip.assign(n, 0);
  std::vector<std::uint8_t> visited(n, 0);
  std::vector<int> component;
  for (std::size_t seed = 0; seed < n; ++seed) {
    if (visited[seed]) continue;
    ++result.components;
    // breadth-first over the component; a Moebius-like conflict keeps the first choice
    component.assign(1, static_cast<int>(seed));
    visited[seed] = 1;
    for (std::size_t head = 0; head < component.size(); ++head) {
      const auto t = static_cast<std::size_t>(component[head]);
      for (std::uint8_t k = 0; k < neighbours.count[t]; ++k) {
        const Neighbour next = neighbours.slots[t][k];
        const auto o = static_cast<std::size_t>(next.triangle());
        if (visited[o]) continue;
        visited[o] = 1;
        result.flip[o] = (result.flip[t] != 0) != next.opposite() ? 1 : 0;
        component.push_back(next.triangle());
      }
    }
    double kept_area = 0.0;
    double flipped_area = 0.0;
    for (const int t : component) {
      const auto i = static_cast<std::size_t>(t);
      (result.flip[i] ? flipped_area : kept_area) += area[i];
    }
    if (flipped_area > kept_area) {
      for (const int t : component) {
        std::uint8_t& flip = result.flip[static_cast<std::size_t>(t)];
        flip = flip ? 0 : 1;
      }
    }
  }
  return result;
}

// Enclosed volume of `count` triangles whose corners are vertices.col(corner_vertex(t, corner)),
// by tetrahedra from the centroid of the corners: the same sum as from the origin for a closed
// surface, and less cancellation for a body far from the origin. One function for the public
// signed_volume and the repair's own triangles, so both give the same bits.
template <typename CornerVertex>
double signed_volume_of_corners(const Eigen::Matrix3Xd& vertices, int count, CornerVertex corner_vertex) {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (int t = 0; t < count; ++t) {
    for (int corner = 0; corner < 3; ++corner) centre += vertices.col(corner_vertex(t, corner));
  }
  if (count > 0) centre /= 3.0 * count;
  double six_volume = 0.0;
  for (int t = 0; t < count; ++t) {
    const Eigen::Vector3d a = vertices.col(corner_vertex(t, 0)) - centre;
    const Eigen::Vector3d b = vertices.col(corner_vertex(t, 1)) - centre;
    const Eigen::Vector3d c = vertices.col(corner_vertex(t, 2)) - centre;
    six_volume += a.dot(b.cross(c));
  }
  return six_volume / 6.0;
}

double signed_volume_of(const Eigen::Matrix3Xd& vertices, const std::vector<Triangle>& triangles) {
  return signed_volume_of_corners(vertices, static_cast<int>(triangles.size()), [&](int t, int corner) {
    return triangles[static_cast<std::size_t>(t)][static_cast<std::size_t>(corner)];
  });
}

// ---- Solids ---------------------------------------------------------------------------------

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
  if (parts.size() == 1) return {0};  // nothing to join: spares tabling every edge
  std::vector<Triangle> triangles(static_cast<std::size_t>(mesh.num_triangles()));
  std::vector<int> part_of(triangles.size());
  for (std::size_t p = 0; p < parts.size(); ++p) {
    for (int t = parts[p].first_triangle; t < parts[p].first_triangle + parts[p].triangle_count; ++t) {
      triangles[static_cast<std::size_t>(t)] = triangle_at(mesh, t);
      part_of[static_cast<std::size_t>(t)] = static_cast<int>(p);
    }
  }
  std::vector<int> parent(parts.size());
  std::iota(parent.begin(), parent.end(), 0);
  const EdgeTable edges(triangles);
  const std::vector<EdgeUse>& uses = edges.uses();
  edges.for_each_edge([&](int, std::size_t begin, std::size_t end) {
    for (std::size_t u = begin + 1; u < end; ++u) {
      const int a = find_root(parent, part_of[static_cast<std::size_t>(uses[u].triangle())]);
      const int b = find_root(parent, part_of[static_cast<std::size_t>(uses[u - 1].triangle())]);
      if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
    }
  });
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

// Turns a solid's triangles to agree with their neighbours across two-triangle edges, then all
// of them when they enclose a negative volume (a solid written clockwise). Returns how many
// triangles end up turned and the volume enclosed, and counts the edge-connected components.
struct Outward {
  int flipped = 0;
  double volume = 0.0;
};

Outward turn_outward(const Eigen::Matrix3Xd& vertices, const EdgeTable& edges, SolidTriangles& solid,
                     SurfaceProblems& problems) {
  std::vector<Triangle>& triangles = solid.triangles;
  const Orientation orientation = orient(manifold_neighbours(edges, triangles.size()), solid.area);
  problems.components += orientation.components;
  Outward result;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    if (!orientation.flip[t]) continue;
    std::swap(triangles[t][1], triangles[t][2]);
    ++result.flipped;
  }
  result.volume = signed_volume_of(vertices, triangles);
  if (result.volume < 0.0) {
    result.volume = -result.volume;
    for (Triangle& tri : triangles) std::swap(tri[1], tri[2]);
    result.flipped = static_cast<int>(triangles.size()) - result.flipped;
  }
  return result;
}

// Where a part's kept triangles lie among its solid's.
struct PartSlice {
  std::size_t begin = 0;
  std::size_t count = 0;
};

// The slice of each of the solid's parts. The parts of a solid come in file order, so each
// part's triangles are one run.
void find_part_slices(const SolidTriangles& solid, std::vector<PartSlice>& part_slice) {
  for (std::size_t t = 0; t < solid.part.size(); ++t) {
    PartSlice& slice = part_slice[static_cast<std::size_t>(solid.part[t])];
    if (slice.count++ == 0) slice.begin = t;
  }
}

}  // namespace

double signed_volume(const TriangleMesh& mesh, int first, int count) {
  return signed_volume_of_corners(mesh.vertices, count,
                                  [&](int t, int corner) { return mesh.triangles(corner, first + t); });
}

RepairedSurface repair_surface(const TriangleMesh& mesh) {
  const std::vector<MeshPart> parts = parts_of(mesh);
  RepairedSurface repaired;
  repaired.mesh.vertices = mesh.vertices;
  repaired.part_solid = solids_of_parts(mesh, parts);
  const int solid_count =
      parts.empty() ? 0 : *std::max_element(repaired.part_solid.begin(), repaired.part_solid.end()) + 1;
  repaired.solid_parts.assign(static_cast<std::size_t>(solid_count), {});
  for (std::size_t p = 0; p < parts.size(); ++p) {
    repaired.solid_parts[static_cast<std::size_t>(repaired.part_solid[p])].push_back(static_cast<int>(p));
  }
  // each solid's triangles, in file order, after dropping degenerate and duplicated ones (a
  // duplicate with either orientation), oriented; then given back to their parts
  std::vector<std::vector<Triangle>> solid_triangles(static_cast<std::size_t>(solid_count));
  std::vector<PartSlice> part_slice(parts.size());
  repaired.solid_volume.assign(static_cast<std::size_t>(solid_count), 0.0);
  int flipped = 0;
  for (int solid = 0; solid < solid_count; ++solid) {
    SolidTriangles kept =
        nondegenerate_triangles(mesh, parts, repaired.solid_parts[static_cast<std::size_t>(solid)], repaired.problems);
    EdgeTable edges(kept.triangles);
    drop_repeats(kept, edges, repaired.problems);
    count_edge_problems(edges, repaired.problems);
    const Outward outward = turn_outward(mesh.vertices, edges, kept, repaired.problems);
    flipped += outward.flipped;
    repaired.solid_volume[static_cast<std::size_t>(solid)] = outward.volume;
    find_part_slices(kept, part_slice);
    solid_triangles[static_cast<std::size_t>(solid)] = std::move(kept.triangles);
  }
  repaired.problems.flipped_triangles = flipped;
  // back in file order, part by part
  std::size_t total = 0;
  for (const PartSlice& slice : part_slice) total += slice.count;
  repaired.mesh.triangles.resize(3, static_cast<Eigen::Index>(total));
  int next = 0;
  for (std::size_t p = 0; p < parts.size(); ++p) {
    const PartSlice& slice = part_slice[p];
    MeshPart out_part = parts[p];
    out_part.first_triangle = next;
    out_part.triangle_count = static_cast<int>(slice.count);
    repaired.mesh.parts.push_back(out_part);
    const std::vector<Triangle>& from = solid_triangles[static_cast<std::size_t>(repaired.part_solid[p])];
    for (std::size_t t = slice.begin; t < slice.begin + slice.count; ++t) {
      for (int c = 0; c < 3; ++c) repaired.mesh.triangles(c, next) = from[t][static_cast<std::size_t>(c)];
      ++next;
    }
  }
  return repaired;
}

}  // namespace cubespring
