// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "voxelize/axis_rays.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace cubespring::voxelize_detail {

namespace {

// Vertices snap to 1/4096 of the sample spacing so that the ray-triangle tests are exact integer
// arithmetic: the edge shared by two triangles is tested the same way for both, and a ray that
// meets it counts exactly one crossing (watertight), whatever rounding would have done.
constexpr std::int64_t kUnits = 4096;
constexpr std::int64_t kHalfUnit = kUnits / 2;

// A vertex projected on the plane of a row, in snapped units.
struct Point2 {
  std::int64_t b;
  std::int64_t c;
};

// Twice the signed area of (p0, p1, q): > 0 when q is left of p0 -> p1. Written on differences to
// q so that swapping p0 and p1 negates it exactly.
std::int64_t edge_function(const Point2& p0, const Point2& p1, const Point2& q) {
  return (p0.b - q.b) * (p1.c - q.c) - (p0.c - q.c) * (p1.b - q.b);
}

// A point on an edge belongs to the triangle whose side it would fall on if moved by a tiny
// (+d, -d^2): the same choice for both triangles of an edge and for all of a vertex's fan.
bool covers(std::int64_t edge_value, const Point2& p0, const Point2& p1) {
  if (edge_value != 0) return edge_value > 0;
  const std::int64_t dc = p1.c - p0.c;
  return dc < 0 || (dc == 0 && p1.b - p0.b < 0);
}

struct Crossing {
  std::int64_t row;
  double position;  // along the ray, in snapped units
  int sign;         // +1 entering (normal against the ray), -1 leaving
};

// std::llround's rounding, halves away from zero, without its library call (half of the ray
// casting's time went there). Unlike floor(x + 0.5) it is odd, round(-x) == -round(x), which a
// mesh symmetric about a grid node needs to give symmetric samples. Truncate, then step away
// from zero when the dropped fraction is a half or more: x - trunc(x) is exact below 2^52, and
// from there on x is a whole number. Beyond the int64 range (no grid gets there) llround
// answers, as before.
std::int64_t round_half_away_from_zero(double x) {
  if (!(std::abs(x) < 0x1p62)) return std::llround(x);
  const auto whole = static_cast<std::int64_t>(x);
  const double fraction = x - static_cast<double>(whole);
  // added as 0 or 1 rather than branched on: fractions are random, branches would mispredict
  return whole + static_cast<std::int64_t>(fraction >= 0.5) - static_cast<std::int64_t>(fraction <= -0.5);
}

std::int64_t snap(double coordinate, double spacing, std::int64_t origin_index) {
  return round_half_away_from_zero(coordinate / spacing * static_cast<double>(kUnits)) - origin_index * kUnits;
}

// A vertex snapped on all three axes.
using SnappedVertex = std::array<std::int64_t, 3>;

SnappedVertex snap_vertex(const Eigen::Matrix3Xd& vertices, Eigen::Index v, const SampleGrid& grid) {
  SnappedVertex snapped;
  for (int d = 0; d < 3; ++d) {
    snapped[static_cast<std::size_t>(d)] = snap(vertices(d, v), grid.spacing[d], grid.origin_index[d]);
  }
  return snapped;
}

// The snapped corners of the triangles. Each vertex is snapped once rather than once per corner
// (a vertex has about six triangles), into a table over the range of vertex indices the
// triangles use; when that range is wider than their corners (a solid using few of a mesh's
// many vertices) such a table would cost more than it saves, and each corner is snapped on its
// own as before. Either way a vertex gets the same value (one function of its coordinates).
class SnappedCorners {
 public:
  SnappedCorners(const Eigen::Matrix3Xd& vertices, const Eigen::Matrix3Xi& triangles, const SampleGrid& grid)
      : triangles_(triangles) {
    if (triangles.size() == 0) return;
    const int first = triangles.minCoeff();
    const int last = triangles.maxCoeff();
    by_vertex_ = static_cast<std::int64_t>(last) - first < static_cast<std::int64_t>(triangles.size());
    if (by_vertex_) {
      first_ = first;
      table_.resize(static_cast<std::size_t>(last - first + 1));
      for (int v = first; v <= last; ++v) table_[static_cast<std::size_t>(v - first)] = snap_vertex(vertices, v, grid);
    } else {
      table_.resize(static_cast<std::size_t>(triangles.size()));
      for (Eigen::Index i = 0; i < triangles.size(); ++i) {
        table_[static_cast<std::size_t>(i)] = snap_vertex(vertices, triangles.data()[i], grid);
      }
    }
  }

  const SnappedVertex& operator()(Eigen::Index t, int corner) const {
    return by_vertex_ ? table_[static_cast<std::size_t>(triangles_(corner, t) - first_)]
                      : table_[static_cast<std::size_t>(3 * t + corner)];
  }

 private:
  const Eigen::Matrix3Xi& triangles_;
  bool by_vertex_ = false;
  int first_ = 0;
  std::vector<SnappedVertex> table_;  // by vertex - first_, or by corner (3 * t + corner)
};

// First and last row centre index (centre = index * kUnits + kHalfUnit) within [low, high].
std::int64_t first_row(std::int64_t low) {
  const std::int64_t shifted = low - kHalfUnit;
  return shifted <= 0 ? -((-shifted) / kUnits) : (shifted + kUnits - 1) / kUnits;
}
std::int64_t last_row(std::int64_t high) {
  const std::int64_t shifted = high - kHalfUnit;
  return shifted >= 0 ? shifted / kUnits : -((-shifted + kUnits - 1) / kUnits);
}

// The rows whose centres lie in a triangle's bounding box, clipped to the grid.
struct RowBox {
  std::int64_t begin_b, end_b, begin_c, end_c;  // inclusive
  bool empty() const { return begin_b > end_b || begin_c > end_c; }
};

RowBox rows_under(const std::array<Point2, 3>& p, std::int64_t rows_b, std::int64_t rows_c) {
  const std::int64_t low_b = std::min({p[0].b, p[1].b, p[2].b});
  const std::int64_t high_b = std::max({p[0].b, p[1].b, p[2].b});
  const std::int64_t low_c = std::min({p[0].c, p[1].c, p[2].c});
  const std::int64_t high_c = std::max({p[0].c, p[1].c, p[2].c});
  return {std::max<std::int64_t>(first_row(low_b), 0), std::min<std::int64_t>(last_row(high_b), rows_b - 1),
          std::max<std::int64_t>(first_row(low_c), 0), std::min<std::int64_t>(last_row(high_c), rows_c - 1)};
}

void add_triangle_crossings(const std::array<Point2, 3>& projected, const std::array<std::int64_t, 3>& along,
                            const RowBox& rows, std::int64_t rows_b, std::vector<Crossing>& crossings) {
  const std::int64_t area = edge_function(projected[0], projected[1], projected[2]);
  if (area == 0) return;  // seen edge-on: its neighbours' crossings cover the ray
  // a counter-clockwise projection has its outward normal along +axis: the ray leaves there
  const int sign = area > 0 ? -1 : 1;
  std::array<Point2, 3> p = projected;
  std::array<std::int64_t, 3> a = along;
  if (area < 0) {
    std::swap(p[1], p[2]);
    std::swap(a[1], a[2]);
  }
  for (std::int64_t jc = rows.begin_c; jc <= rows.end_c; ++jc) {
    for (std::int64_t jb = rows.begin_b; jb <= rows.end_b; ++jb) {
      const Point2 q{jb * kUnits + kHalfUnit, jc * kUnits + kHalfUnit};
      const std::int64_t w0 = edge_function(p[1], p[2], q);
      const std::int64_t w1 = edge_function(p[2], p[0], q);
      const std::int64_t w2 = edge_function(p[0], p[1], q);
      if (!covers(w0, p[1], p[2]) || !covers(w1, p[2], p[0]) || !covers(w2, p[0], p[1])) continue;
      const double position =
          (static_cast<double>(w0) * static_cast<double>(a[0]) + static_cast<double>(w1) * static_cast<double>(a[1]) +
           static_cast<double>(w2) * static_cast<double>(a[2])) /
          static_cast<double>(w0 + w1 + w2);
      crossings.push_back({jb + rows_b * jc, position, sign});
    }
  }
}

}  // namespace

void cast_axis_rays(const Eigen::Matrix3Xd& vertices, const Eigen::Matrix3Xi& triangles, const SampleGrid& grid,
                    int axis, AxisVotes& votes) {
  // rows run along `axis`; (b, c) follow it cyclically so that the projected orientation is
  // the sign of the normal's component along the axis
  const int axis_b = (axis + 1) % 3;
  const int axis_c = (axis + 2) % 3;
  const std::int64_t rows_b = grid.size[axis_b];
  const std::int64_t rows_c = grid.size[axis_c];
  const std::int64_t samples_along = grid.size[axis];

  const SnappedCorners snapped(vertices, triangles, grid);
  std::vector<Crossing> crossings;
  for (Eigen::Index t = 0; t < triangles.cols(); ++t) {
    std::array<Point2, 3> projected;
    std::array<std::int64_t, 3> along;
    for (int corner = 0; corner < 3; ++corner) {
      const SnappedVertex& vertex = snapped(t, corner);
      projected[static_cast<std::size_t>(corner)] = {vertex[static_cast<std::size_t>(axis_b)],
                                                     vertex[static_cast<std::size_t>(axis_c)]};
      along[static_cast<std::size_t>(corner)] = vertex[static_cast<std::size_t>(axis)];
    }
    // most triangles of a fine mesh lie between row centres: no crossing to look for
    const RowBox rows = rows_under(projected, rows_b, rows_c);
    if (rows.empty()) continue;
    add_triangle_crossings(projected, along, rows, rows_b, crossings);
  }
  std::sort(crossings.begin(), crossings.end(), [](const Crossing& x, const Crossing& y) {
    return x.row != y.row ? x.row < y.row : x.position < y.position;
  });

  std::array<std::int64_t, 3> index{0, 0, 0};
  for (std::size_t begin = 0; begin < crossings.size();) {
    std::size_t end = begin;
    int total = 0;
    while (end < crossings.size() && crossings[end].row == crossings[begin].row) total += crossings[end++].sign;
    const std::int64_t row = crossings[begin].row;
    index[static_cast<std::size_t>(axis_b)] = row % rows_b;
    index[static_cast<std::size_t>(axis_c)] = row / rows_b;
    const auto sample = [&](std::int64_t i) {
      index[static_cast<std::size_t>(axis)] = i;
      return static_cast<std::size_t>(grid.index(index[0], index[1], index[2]));
    };
    if (total != 0) {
      // the ray enters more often than it leaves: it went through a hole, so it has no say
      for (std::int64_t i = 0; i < samples_along; ++i) ++votes.abstain[sample(i)];
    } else {
      int winding = 0;
      std::size_t next = begin;
      for (std::int64_t i = 0; i < samples_along && next < end; ++i) {
        const double centre = static_cast<double>(i * kUnits + kHalfUnit);
        while (next < end && crossings[next].position < centre) winding += crossings[next++].sign;
        if (winding != 0) ++votes.inside[sample(i)];
      }
    }
    begin = end;
  }
}

}  // namespace cubespring::voxelize_detail
