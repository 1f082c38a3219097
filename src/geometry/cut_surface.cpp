// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The surface of a solid after some of its lattice's cells were taken out (docs/cutting.md): the
// triangles across a removed cell are split along the grid's planes and the pieces inside it
// dropped; each face between a removed cell and one that is not gets a cap, the part of the face
// inside the solid (the solid's section by the face's plane, clipped to the face). Every point the
// cut makes is named by what makes it (an input edge crossing a plane, a grid line crossing a
// triangle, a grid corner), so that the pieces, their neighbours and the caps share it exactly and
// the surface stays closed.
#include "cubespring/cut_surface.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <utility>

#include <Eigen/Geometry>

namespace cubespring {
namespace {

// The cut's planes sit this far [cells] from the grid's, unequally along the axes: a mesh built on
// the grid's planes (a box on the lattice's faces) is then cut in general position, and no grid
// line runs along a diagonal of such a mesh's squares.
const Eigen::Vector3d kPlaneShift(1.0e-6, 1.3e-6, 1.7e-6);

// What a point is. kind 0: input vertex a; 1: input edge (a, b), a < b, crossing plane c; 2: grid
// line of planes b < c crossing triangle a; 3: grid corner (a, b, c); 4: made in a degenerate
// case, shared with nothing.
using Key = std::array<long long, 4>;
struct Point {
  Eigen::Vector3d x;
  Key key;
};

// A grid plane as one number: its index along its axis, times 4, plus the axis.
long long plane_id(int axis, long long index) { return index * 4 + axis; }
int plane_axis(long long id) { return static_cast<int>(((id % 4) + 4) % 4); }

// A segment of a plane's section: the solid's inside lies on its left seen from the plane's +axis.
struct SectionSegment {
  Point from, to;
  int triangle = 0;
};

class Cutter {
 public:
  Cutter(const TriangleMesh& surface, const Eigen::Vector3d& origin, const Eigen::Vector3d& cell_size,
         const std::vector<Eigen::Vector3i>& removed)
      : surface_(surface),
        origin_(origin),
        cell_size_(cell_size),
        input_used_(static_cast<std::size_t>(surface.num_vertices()), 0),
        on_cut_edge_(static_cast<std::size_t>(surface.num_vertices()), 0) {
    for (const Eigen::Vector3i& cell : removed) removed_.insert({cell.x(), cell.y(), cell.z()});
    // a box of flags over the removed cells: most triangles ask about cells far from any cut
    if (removed.empty()) return;
    removed_lower_ = removed.front();
    Eigen::Vector3i upper = removed_lower_;
    for (const Eigen::Vector3i& cell : removed) {
      removed_lower_ = removed_lower_.cwiseMin(cell);
      upper = upper.cwiseMax(cell);
    }
    removed_extent_ = (upper - removed_lower_).array() + 1;
    removed_flags_.assign(static_cast<std::size_t>(removed_extent_.cast<long long>().prod()), 0);
    for (const Eigen::Vector3i& cell : removed) removed_flags_[flag_of(cell.cast<long long>())] = 1;
  }

  CutSurface run() {
    std::vector<int> unclipped;
    for (int t = 0; t < surface_.num_triangles(); ++t) {
      if (!clip_triangle(t)) unclipped.push_back(t);
    }
    for (const int t : unclipped) emit_unclipped(t);
    const std::size_t before_caps = triangles_.size();
    // each part is capped on its own: a tumour's surface inside a liver's closes its own cut
    const std::vector<MeshPart> parts = parts_of(surface_);
    for (std::size_t part = 0; part < parts.size(); ++part) {
      for (const auto& cell : removed_) {
        for (int axis = 0; axis < 3; ++axis) {
          for (const int side : {-1, 1}) {
            std::array<int, 3> neighbour = cell;
            neighbour[static_cast<std::size_t>(axis)] += side;
            if (removed_.count(neighbour) == 0) cap_face(cell, axis, side, parts[part]);
          }
        }
      }
    }
    return assemble(static_cast<int>(triangles_.size() - before_caps));
  }

 private:
  double plane(int axis, long long index) const {
    return origin_[axis] + (static_cast<double>(index) + kPlaneShift[axis]) * cell_size_[axis];
  }
  double plane_at(long long id) const { return plane(plane_axis(id), (id - plane_axis(id)) / 4); }
  long long cell_along(int axis, double x) const {
    return static_cast<long long>(std::floor((x - origin_[axis]) / cell_size_[axis] - kPlaneShift[axis]));
  }
  std::size_t flag_of(const Eigen::Matrix<long long, 3, 1>& cell) const {
    const Eigen::Matrix<long long, 3, 1> at = cell - removed_lower_.cast<long long>();
    return static_cast<std::size_t>((at.z() * removed_extent_.y() + at.y()) * removed_extent_.x() + at.x());
  }
  bool is_removed(long long i, long long j, long long k) const {
    const Eigen::Matrix<long long, 3, 1> cell(i, j, k);
    const Eigen::Matrix<long long, 3, 1> at = cell - removed_lower_.cast<long long>();
    if ((at.array() < 0).any() || (at.array() >= removed_extent_.cast<long long>().array()).any()) return false;
    return removed_flags_[flag_of(cell)] != 0;
  }
  Eigen::Vector3d vertex(int v) const { return surface_.vertices.col(v); }
  Point input_vertex(int v) const { return {vertex(v), {0, v, 0, 0}}; }

  // Where input edge (u, w) crosses a plane, computed from the edge's ends in one order.
  Point edge_point(int u, int w, long long id) const {
    const int a = std::min(u, w), b = std::max(u, w);
    const int axis = plane_axis(id);
    const double c = plane_at(id);
    const Eigen::Vector3d pa = vertex(a), pb = vertex(b);
    if (pa[axis] == c) return input_vertex(a);
    if (pb[axis] == c) return input_vertex(b);
    Eigen::Vector3d x = pa + (c - pa[axis]) / (pb[axis] - pa[axis]) * (pb - pa);
    x[axis] = c;
    return {x, {1, a, b, id}};
  }
  // Where segment p q crosses a plane, with the key `key`: computed from the ends in key order.
  Point segment_point(const Point& p, const Point& q, long long id, const Key& key) const {
    const Point& a = p.key < q.key ? p : q;
    const Point& b = p.key < q.key ? q : p;
    const int axis = plane_axis(id);
    const double c = plane_at(id);
    Eigen::Vector3d x = a.x + (c - a.x[axis]) / (b.x[axis] - a.x[axis]) * (b.x - a.x);
    x[axis] = c;
    return {x, key};
  }
  // The input edge of triangle t both points lie on, as (u, w); {-1, -1} if none.
  std::array<int, 2> common_edge(int t, const Point& p, const Point& q) const {
    for (int k = 0; k < 3; ++k) {
      const int u = surface_.triangles(k, t), w = surface_.triangles((k + 1) % 3, t);
      const auto on = [&](const Point& x) {
        if (x.key[0] == 0) return x.key[1] == u || x.key[1] == w;
        return x.key[0] == 1 && x.key[1] == std::min(u, w) && x.key[2] == std::max(u, w);
      };
      if (on(p) && on(q)) return {u, w};
    }
    return {-1, -1};
  }
  // The grid planes a point lies on (by its key).
  static std::vector<long long> planes_of(const Point& x) {
    if (x.key[0] == 1) return {x.key[3]};
    if (x.key[0] == 2) return {x.key[2], x.key[3]};
    return {};
  }
  // Where the side p q of a piece of triangle t crosses plane `id`.
  Point crossing(int t, const Point& p, const Point& q, long long id) {
    const std::array<int, 2> edge = common_edge(t, p, q);
    if (edge[0] >= 0) {
      const Point x = edge_point(edge[0], edge[1], id);
      if (x.key[0] == 1) {
        edge_points_[{std::min(edge[0], edge[1]), std::max(edge[0], edge[1])}].insert(x.key);
        on_cut_edge_[static_cast<std::size_t>(edge[0])] = on_cut_edge_[static_cast<std::size_t>(edge[1])] = 1;
      }
      return x;
    }
    for (const long long a : planes_of(p)) {
      for (const long long b : planes_of(q)) {
        if (a == b) return segment_point(p, q, id, {2, t, std::min(a, id), std::max(a, id)});
      }
    }
    return segment_point(p, q, id, {4, t, id, degenerate_++});
  }

  // Splits a piece of triangle t by a plane into the parts below and at-or-above it.
  void split(int t, const std::vector<Point>& piece, long long id, std::vector<Point>& below,
             std::vector<Point>& above) {
    const int axis = plane_axis(id);
    const double c = plane_at(id);
    const auto add = [](std::vector<Point>& side, const Point& x) {
      if (side.empty() || side.back().key != x.key) side.push_back(x);
    };
    for (std::size_t i = 0; i < piece.size(); ++i) {
      const Point& p = piece[i];
      const Point& q = piece[(i + 1) % piece.size()];
      const bool p_above = p.x[axis] >= c, q_above = q.x[axis] >= c;
      add(p_above ? above : below, p);
      if (p_above != q_above) {
        const Point x = crossing(t, p, q, id);
        add(below, x);
        add(above, x);
      }
    }
    for (std::vector<Point>* side : {&below, &above}) {
      if (side->size() > 1 && side->front().key == side->back().key) side->pop_back();
    }
  }

  // Triangle t split along every grid plane across it when it reaches a removed cell, its pieces
  // outside removed cells kept; false (nothing done) when it reaches none.
  bool clip_triangle(int t) {
    Eigen::Vector3d lower = vertex(surface_.triangles(0, t)), upper = lower;
    for (int k = 1; k < 3; ++k) {
      lower = lower.cwiseMin(vertex(surface_.triangles(k, t)));
      upper = upper.cwiseMax(vertex(surface_.triangles(k, t)));
    }
    std::array<long long, 3> first{}, last{};
    for (int axis = 0; axis < 3; ++axis) {
      first[static_cast<std::size_t>(axis)] = cell_along(axis, lower[axis]);
      last[static_cast<std::size_t>(axis)] = cell_along(axis, upper[axis]);
    }
    bool reaches = false;
    for (long long i = first[0]; i <= last[0] && !reaches; ++i) {
      for (long long j = first[1]; j <= last[1] && !reaches; ++j) {
        for (long long k = first[2]; k <= last[2] && !reaches; ++k) reaches = is_removed(i, j, k);
      }
    }
    if (!reaches) return false;
    // each piece knows its cell from the sides of the planes it was split on (a centre on a
    // plane, as a cap of an earlier cut lies, would round to either cell)
    struct Piece {
      std::vector<Point> points;
      std::array<long long, 3> cell;
    };
    std::vector<Piece> pieces{{{input_vertex(surface_.triangles(0, t)), input_vertex(surface_.triangles(1, t)),
                                input_vertex(surface_.triangles(2, t))},
                               first}};
    for (int axis = 0; axis < 3; ++axis) {
      const std::size_t a = static_cast<std::size_t>(axis);
      for (long long index = first[a] + 1; index <= last[a]; ++index) {
        std::vector<Piece> next;
        for (const Piece& piece : pieces) {
          if (piece.cell[a] != index - 1) {  // beyond this plane already
            next.push_back(piece);
            continue;
          }
          Piece below{{}, piece.cell}, above{{}, piece.cell};
          above.cell[a] = index;
          split(t, piece.points, plane_id(axis, index), below.points, above.points);
          if (below.points.size() >= 3) next.push_back(std::move(below));
          if (above.points.size() >= 3) next.push_back(std::move(above));
        }
        pieces = std::move(next);
      }
    }
    const Eigen::Vector3d normal = triangle_normal(t);
    for (const Piece& piece : pieces) {
      if (!is_removed(piece.cell[0], piece.cell[1], piece.cell[2])) emit_polygon(piece.points, normal);
    }
    return true;
  }

  Eigen::Vector3d triangle_normal(int t) const {
    const Eigen::Vector3d a = vertex(surface_.triangles(0, t));
    return (vertex(surface_.triangles(1, t)) - a).cross(vertex(surface_.triangles(2, t)) - a);
  }

  // A triangle no removed cell reaches, with the points its clipped neighbours made on its edges
  // (else they would meet it at a T-junction and crack as the tissue deforms).
  void emit_unclipped(int t) {
    const auto on_cut_edge = [&](int k) {
      return on_cut_edge_[static_cast<std::size_t>(surface_.triangles(k, t))] &&
             on_cut_edge_[static_cast<std::size_t>(surface_.triangles((k + 1) % 3, t))];
    };
    if (!on_cut_edge(0) && !on_cut_edge(1) && !on_cut_edge(2)) {  // most triangles: as they were
      std::array<Key, 3> triangle;
      for (int k = 0; k < 3; ++k) {
        const Point x = input_vertex(surface_.triangles(k, t));
        remember(x);
        triangle[static_cast<std::size_t>(k)] = x.key;
      }
      triangles_.push_back(triangle);
      return;
    }
    std::vector<Point> polygon;
    bool extra = false;
    for (int k = 0; k < 3; ++k) {
      const int u = surface_.triangles(k, t), w = surface_.triangles((k + 1) % 3, t);
      polygon.push_back(input_vertex(u));
      if (!on_cut_edge_[static_cast<std::size_t>(u)] || !on_cut_edge_[static_cast<std::size_t>(w)]) continue;
      const auto found = edge_points_.find({std::min(u, w), std::max(u, w)});
      if (found == edge_points_.end()) continue;
      std::vector<Point> along;
      for (const Key& key : found->second) {
        const Point x = edge_point(u, w, key[3]);
        along.push_back(x);
      }
      const Eigen::Vector3d from = vertex(u), direction = vertex(w) - vertex(u);
      std::sort(along.begin(), along.end(), [&](const Point& a, const Point& b) {
        return (a.x - from).dot(direction) < (b.x - from).dot(direction);
      });
      polygon.insert(polygon.end(), along.begin(), along.end());
      extra = true;
    }
    if (!extra) {
      triangles_.push_back({polygon[0].key, polygon[1].key, polygon[2].key});
      for (const Point& x : polygon) remember(x);
      return;
    }
    emit_polygon(polygon, triangle_normal(t));
  }

  // A point the output uses: an input vertex is flagged, any other kept with its position.
  void remember(const Point& x) {
    if (x.key[0] == 0) {
      input_used_[static_cast<std::size_t>(x.key[1])] = 1;
    } else {
      positions_.emplace(x.key, x.x);
    }
  }

  // A planar polygon (no self-crossing) as triangles by ear clipping, each turning as the polygon.
  void emit_polygon(std::vector<Point> polygon, const Eigen::Vector3d& normal) {
    for (const Point& x : polygon) remember(x);
    int drop = 0;
    normal.cwiseAbs().maxCoeff(&drop);
    const int u = (drop + 1) % 3, v = (drop + 2) % 3;
    const auto cross = [&](const Point& a, const Point& b, const Point& c) {
      return (b.x[u] - a.x[u]) * (c.x[v] - a.x[v]) - (b.x[v] - a.x[v]) * (c.x[u] - a.x[u]);
    };
    double area = 0.0;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
      area += cross(polygon[0], polygon[i], polygon[(i + 1) % polygon.size()]);
    }
    const double sign = area >= 0.0 ? 1.0 : -1.0;
    while (polygon.size() > 3) {
      const std::size_t n = polygon.size();
      std::size_t ear = n;
      for (std::size_t i = 0; i < n && ear == n; ++i) {
        const Point& a = polygon[(i + n - 1) % n];
        const Point& b = polygon[i];
        const Point& c = polygon[(i + 1) % n];
        if (sign * cross(a, b, c) <= 0.0) continue;  // reflex, or on a line
        bool empty = true;
        for (std::size_t j = 0; j < n && empty; ++j) {
          if (j == i || j == (i + 1) % n || j == (i + n - 1) % n) continue;
          const Point& p = polygon[j];
          empty = !(sign * cross(a, b, p) > 0.0 && sign * cross(b, c, p) > 0.0 && sign * cross(c, a, p) > 0.0);
        }
        if (empty) ear = i;
      }
      if (ear == n) break;  // rounding left no clean ear: a fan closes the rest
      triangles_.push_back({polygon[(ear + n - 1) % n].key, polygon[ear].key, polygon[(ear + 1) % n].key});
      polygon.erase(polygon.begin() + static_cast<std::ptrdiff_t>(ear));
    }
    for (std::size_t i = 1; i + 1 < polygon.size(); ++i) {
      triangles_.push_back({polygon[0].key, polygon[i].key, polygon[i + 1].key});
    }
  }

  // The section of the solid by a plane: a segment for each triangle across it.
  const std::vector<SectionSegment>& section(long long id, const MeshPart& part) {
    const std::pair<long long, int> key{id, part.first_triangle};
    const auto found = sections_.find(key);
    if (found != sections_.end()) return found->second;
    std::vector<SectionSegment>& segments = sections_[key];
    const int axis = plane_axis(id);
    const double c = plane_at(id);
    Eigen::Vector3d along_axis = Eigen::Vector3d::Zero();
    along_axis[axis] = 1.0;
    for (int t = part.first_triangle; t < part.first_triangle + part.triangle_count; ++t) {
      const std::array<int, 3> corners{surface_.triangles(0, t), surface_.triangles(1, t), surface_.triangles(2, t)};
      int above = 0;
      for (const int v : corners) above += surface_.vertices(axis, v) >= c;
      if (above == 0 || above == 3) continue;  // most triangles: all on one side
      std::array<Point, 2> ends;
      int crossings = 0;
      for (int k = 0; k < 3; ++k) {
        const int p = corners[static_cast<std::size_t>(k)], q = corners[static_cast<std::size_t>((k + 1) % 3)];
        if ((vertex(p)[axis] >= c) != (vertex(q)[axis] >= c) && crossings < 2)
          ends[static_cast<std::size_t>(crossings++)] = edge_point(p, q, id);
      }
      if (crossings != 2 || ends[0].key == ends[1].key) continue;
      // the inside lies to the left of axis x normal
      if ((ends[1].x - ends[0].x).dot(along_axis.cross(triangle_normal(t))) < 0.0) std::swap(ends[0], ends[1]);
      segments.push_back({ends[0], ends[1], t});
    }
    return segments;
  }

  // The cap on the face of removed cell `cell` toward `side` along `axis`: the part of the face
  // inside the solid, facing into the cell.
  void cap_face(const std::array<int, 3>& cell, int axis, int side, const MeshPart& part) {
    const long long index = cell[static_cast<std::size_t>(axis)] + (side > 0 ? 1 : 0);
    const long long id = plane_id(axis, index);
    const std::vector<SectionSegment>& segments = section(id, part);
    const int b = (axis + 1) % 3, d = (axis + 2) % 3;
    const long long b0 = cell[static_cast<std::size_t>(b)], d0 = cell[static_cast<std::size_t>(d)];
    // the square's sides, counter-clockwise seen from +axis: d = d0, b = b0 + 1, d = d0 + 1, b = b0
    const std::array<long long, 4> side_plane{plane_id(d, d0), plane_id(b, b0 + 1), plane_id(d, d0 + 1),
                                              plane_id(b, b0)};
    const double lo_b = plane(b, b0), hi_b = plane(b, b0 + 1), lo_d = plane(d, d0), hi_d = plane(d, d0 + 1);
    const auto perimeter = [&](const Eigen::Vector3d& x, int on_side) {
      switch (on_side) {
        case 0: return (x[b] - lo_b) / (hi_b - lo_b);
        case 1: return 1.0 + (x[d] - lo_d) / (hi_d - lo_d);
        case 2: return 2.0 + (hi_b - x[b]) / (hi_b - lo_b);
        default: return 3.0 + (hi_d - x[d]) / (hi_d - lo_d);
      }
    };
    const auto corner = [&](int k) {  // corner k starts side k
      Eigen::Vector3i g;
      g[axis] = static_cast<int>(index);
      g[b] = static_cast<int>(b0 + (k == 1 || k == 2 ? 1 : 0));
      g[d] = static_cast<int>(d0 + (k >= 2 ? 1 : 0));
      Eigen::Vector3d x;
      x[axis] = plane(axis, index);
      x[b] = plane(b, g[b]);
      x[d] = plane(d, g[d]);
      return Point{x, {3, g.x(), g.y(), g.z()}};
    };

    // the section's segments clipped to the square (Liang and Barsky), with where they enter and leave
    struct Piece {
      Point from, to;
      double enters = -1.0, leaves = -1.0;  // perimeter position, or -1 inside
    };
    std::vector<Piece> pieces;
    for (const SectionSegment& segment : segments) {
      const Eigen::Vector3d p = segment.from.x, delta = segment.to.x - segment.from.x;
      double t_in = 0.0, t_out = 1.0;
      int in_side = -1, out_side = -1;
      const std::array<double, 4> bound{lo_d, hi_b, hi_d, lo_b};
      const std::array<int, 4> coordinate{d, b, d, b};
      const std::array<double, 4> outward{-1.0, 1.0, 1.0, -1.0};
      bool outside = false;
      for (int k = 0; k < 4 && !outside; ++k) {
        const int cc = coordinate[static_cast<std::size_t>(k)];
        const double dir = outward[static_cast<std::size_t>(k)] * delta[cc];
        const double gap = outward[static_cast<std::size_t>(k)] * (bound[static_cast<std::size_t>(k)] - p[cc]);
        if (dir == 0.0) {
          outside = gap < 0.0;
          continue;
        }
        const double t = gap / dir;
        if (dir < 0.0) {  // entering across side k
          if (t > t_in) t_in = t, in_side = k;
        } else if (t < t_out) {
          t_out = t, out_side = k;
        }
        outside = t_in > t_out;
      }
      if (outside || t_in >= t_out) continue;
      const auto at_side = [&](int k) {
        const long long line = side_plane[static_cast<std::size_t>(k)];
        return segment_point(segment.from, segment.to, line,
                             {2, segment.triangle, std::min(line, id), std::max(line, id)});
      };
      Piece piece{segment.from, segment.to};
      if (in_side >= 0) {
        piece.from = at_side(in_side);
        piece.enters = perimeter(piece.from.x, in_side);
      }
      if (out_side >= 0) {
        piece.to = at_side(out_side);
        piece.leaves = perimeter(piece.to.x, out_side);
      }
      pieces.push_back(piece);
    }

    std::map<Key, std::size_t> starting_at;
    std::vector<std::size_t> entering;
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      if (pieces[i].enters >= 0.0) {
        entering.push_back(i);
      } else {
        starting_at[pieces[i].from.key] = i;
      }
    }
    std::vector<char> used(pieces.size(), 0);
    Eigen::Vector3d facing = Eigen::Vector3d::Zero();
    facing[axis] = 1.0;  // the polygons below turn counter-clockwise about +axis
    const auto emit = [&](std::vector<Point> polygon) {
      if (side > 0) {  // the cell lies on the -axis side: the cap faces -axis
        std::reverse(polygon.begin(), polygon.end());
        emit_polygon(polygon, -facing);
      } else {
        emit_polygon(polygon, facing);
      }
    };
    // regions whose outline runs along the square: from each entry, the section to where it
    // leaves, then along the square's sides (counter-clockwise, turning its corners) to the next
    // entry, until the outline closes
    for (const std::size_t start : entering) {
      if (used[start]) continue;
      std::vector<Point> polygon;
      std::size_t current = start;
      bool closed = false;
      for (std::size_t guard = 0; guard <= pieces.size() && !closed; ++guard) {
        while (true) {  // along the section
          used[current] = 1;
          polygon.push_back(pieces[current].from);
          if (pieces[current].leaves >= 0.0) break;
          const auto next = starting_at.find(pieces[current].to.key);
          if (next == starting_at.end() || used[next->second]) return;  // an open surface: no cap
          current = next->second;
        }
        polygon.push_back(pieces[current].to);
        const double leaves = pieces[current].leaves;
        std::size_t next_entry = pieces.size();
        double nearest = 5.0;
        for (const std::size_t e : entering) {
          double ahead = pieces[e].enters - leaves;
          if (ahead <= 0.0) ahead += 4.0;
          if (ahead < nearest) nearest = ahead, next_entry = e;
        }
        if (next_entry == pieces.size()) return;
        for (int k = static_cast<int>(std::floor(leaves)) + 1; k <= static_cast<int>(std::floor(leaves + nearest));
             ++k) {
          polygon.push_back(corner(k % 4));
        }
        closed = next_entry == start;
        current = next_entry;
      }
      if (closed) emit(polygon);
    }
    // regions the section outlines inside the square, counter-clockwise (a clockwise one would
    // be a cavity's wall: left uncapped)
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      if (used[i]) continue;
      std::vector<Point> loop;
      std::size_t current = i;
      while (!used[current]) {
        used[current] = 1;
        loop.push_back(pieces[current].from);
        const auto next = starting_at.find(pieces[current].to.key);
        if (next == starting_at.end()) break;
        current = next->second;
      }
      double area = 0.0;
      for (std::size_t k = 0; k < loop.size(); ++k) {
        const Eigen::Vector3d& p = loop[k].x;
        const Eigen::Vector3d& q = loop[(k + 1) % loop.size()].x;
        area += p[b] * q[d] - q[b] * p[d];
      }
      if (area > 0.0 && loop.size() >= 3) emit(loop);
    }
    // no outline crosses the square: it is all inside or all outside; ask at a corner
    if (entering.empty() && winding_at(segments, lo_b, lo_d, b, d) != 0) {
      emit({corner(0), corner(1), corner(2), corner(3)});
    }
  }

  // The section's winding number about the point (pb, pd) of its plane.
  static int winding_at(const std::vector<SectionSegment>& segments, double pb, double pd, int b, int d) {
    int winding = 0;
    for (const SectionSegment& s : segments) {
      const Eigen::Vector3d& p = s.from.x;
      const Eigen::Vector3d& q = s.to.x;
      if ((p[d] <= pd) == (q[d] <= pd)) continue;
      const double crossing_b = p[b] + (pd - p[d]) / (q[d] - p[d]) * (q[b] - p[b]);
      if (crossing_b > pb) winding += q[d] > p[d] ? 1 : -1;
    }
    return winding;
  }

  CutSurface assemble(int cap_triangles) {
    CutSurface cut;
    cut.cap_triangles = cap_triangles;
    // the input vertices used, in their order, then the cut's points in the order of their keys
    std::vector<int> input_index(input_used_.size(), -1);
    std::set<Key> used;
    for (const auto& triangle : triangles_) {
      for (const Key& key : triangle) {
        if (key[0] != 0) used.insert(key);
      }
    }
    const auto count = static_cast<Eigen::Index>(std::count(input_used_.begin(), input_used_.end(), char{1}));
    cut.mesh.vertices.resize(3, count + static_cast<Eigen::Index>(used.size()));
    int next = 0;
    const auto add = [&](const Key& key, const Eigen::Vector3d& x) {
      cut.mesh.vertices.col(next) = x;
      cut.vertex_source.push_back(key[0] == 0 ? static_cast<int>(key[1]) : -1);
      cut.vertex_keys.push_back(key);
      return next++;
    };
    for (std::size_t v = 0; v < input_used_.size(); ++v) {
      if (input_used_[v]) input_index[v] = add({0, static_cast<long long>(v), 0, 0}, vertex(static_cast<int>(v)));
    }
    std::map<Key, int> index;
    for (const Key& key : used) index[key] = add(key, positions_.at(key));
    cut.mesh.triangles.resize(3, static_cast<Eigen::Index>(triangles_.size()));
    for (std::size_t t = 0; t < triangles_.size(); ++t) {
      for (int k = 0; k < 3; ++k) {
        const Key& key = triangles_[t][static_cast<std::size_t>(k)];
        cut.mesh.triangles(k, static_cast<Eigen::Index>(t)) =
            key[0] == 0 ? input_index[static_cast<std::size_t>(key[1])] : index.at(key);
      }
    }
    return cut;
  }

  const TriangleMesh& surface_;
  Eigen::Vector3d origin_, cell_size_;
  std::set<std::array<int, 3>> removed_;  // in order, for the caps
  Eigen::Vector3i removed_lower_{0, 0, 0}, removed_extent_{0, 0, 0};
  std::vector<char> removed_flags_;                          // over the removed cells' box, x fastest
  std::vector<char> input_used_;                             // input vertices the output uses
  std::vector<char> on_cut_edge_;                            // input vertices at an end of an edge the cut split
  std::map<std::array<int, 2>, std::set<Key>> edge_points_;  // the cut's points on each input edge
  std::map<std::pair<long long, int>, std::vector<SectionSegment>> sections_;  // by plane and part
  std::map<Key, Eigen::Vector3d> positions_;  // each point the cut made: its position, as first computed
  std::vector<std::array<Key, 3>> triangles_;
  long long degenerate_ = 0;
};

}  // namespace

CutSurface cut_surface(const TriangleMesh& surface, const Eigen::Vector3d& origin, const Eigen::Vector3d& cell_size,
                       const std::vector<Eigen::Vector3i>& removed) {
  return Cutter(surface, origin, cell_size, removed).run();
}

}  // namespace cubespring
