// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "surface_distance.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <Eigen/Geometry>

namespace cubespring::bullet {
namespace {

// The nearest points of segments p0-p1 and q0-q1 as their parameters (Ericson 5.1.9).
std::pair<double, double> closest_segment_segment(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                                  const Eigen::Vector3d& q0, const Eigen::Vector3d& q1) {
  const Eigen::Vector3d d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  if (a == 0.0 && e == 0.0) return {0.0, 0.0};
  if (a == 0.0) return {0.0, std::clamp(f / e, 0.0, 1.0)};
  const double c = d1.dot(r);
  if (e == 0.0) return {std::clamp(-c / a, 0.0, 1.0), 0.0};
  const double b = d1.dot(d2);
  const double denominator = a * e - b * b;
  double s = denominator > 0.0 ? std::clamp((b * f - c * e) / denominator, 0.0, 1.0) : 0.0;
  double t = (b * s + f) / e;
  if (t < 0.0) {
    t = 0.0;
    s = std::clamp(-c / a, 0.0, 1.0);
  } else if (t > 1.0) {
    t = 1.0;
    s = std::clamp((b - c) / a, 0.0, 1.0);
  }
  return {s, t};
}

Eigen::Vector3d unit_normal(const Eigen::Matrix3Xd& positions, const Eigen::Matrix3Xi& triangles, int t) {
  const Eigen::Vector3d a = positions.col(triangles(0, t));
  const Eigen::Vector3d n = (positions.col(triangles(1, t)) - a).cross(positions.col(triangles(2, t)) - a);
  const double length = n.norm();
  return length > 0.0 ? Eigen::Vector3d(n / length) : Eigen::Vector3d::Zero();
}

}  // namespace

Eigen::Vector3d closest_barycentric(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                    const Eigen::Vector3d& c) {
  // the Voronoi regions of the corners, the edges and the face
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {1, 0, 0};
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return {0, 1, 0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return {1 - v, v, 0};
  }
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return {0, 0, 1};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return {1 - w, 0, w};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0, 1 - w, w};
  }
  const double denominator = va + vb + vc;
  if (!(denominator > 0.0)) return {1, 0, 0};  // a degenerate triangle: its first corner
  const double v = vb / denominator, w = vc / denominator;
  return {1 - v - w, v, w};
}

SegmentTriangleClosest closest_segment_triangle(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                                const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                                const Eigen::Vector3d& c) {
  SegmentTriangleClosest best;
  // the segment through the triangle (Moeller-Trumbore, the segment's parameter in [0, 1])
  const Eigen::Vector3d direction = p1 - p0, e1 = b - a, e2 = c - a;
  const Eigen::Vector3d p = direction.cross(e2);
  const double determinant = e1.dot(p);
  if (determinant != 0.0) {
    const Eigen::Vector3d s = p0 - a;
    const double u = s.dot(p) / determinant;
    const Eigen::Vector3d q = s.cross(e1);
    const double v = direction.dot(q) / determinant;
    const double along = e2.dot(q) / determinant;
    if (u >= 0.0 && v >= 0.0 && u + v <= 1.0 && along >= 0.0 && along <= 1.0) {
      best.along = along;
      best.barycentric = {1 - u - v, u, v};
      best.distance = 0.0;
      return best;
    }
  }
  // otherwise the nearest points lie on the segment's ends or the triangle's edges
  best.distance = std::numeric_limits<double>::infinity();
  const auto consider = [&best](double along, const Eigen::Vector3d& barycentric, double distance) {
    if (distance < best.distance) best = {along, barycentric, distance};
  };
  const Eigen::Vector3d corners[3] = {a, b, c};
  for (const double end : {0.0, 1.0}) {
    const Eigen::Vector3d x = p0 + end * direction;
    const Eigen::Vector3d w = closest_barycentric(x, a, b, c);
    consider(end, w, (w[0] * a + w[1] * b + w[2] * c - x).norm());
  }
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d& q0 = corners[k];
    const Eigen::Vector3d& q1 = corners[(k + 1) % 3];
    const auto [s, t] = closest_segment_segment(p0, p1, q0, q1);
    Eigen::Vector3d w = Eigen::Vector3d::Zero();
    w[k] = 1.0 - t;
    w[(k + 1) % 3] = t;
    consider(s, w, (p0 + s * direction - (q0 + t * (q1 - q0))).norm());
  }
  return best;
}

Eigen::Vector3d pseudonormal(const Eigen::Matrix3Xd& positions, const Eigen::Matrix3Xi& triangles,
                             const SurfaceTopology& topology, const SurfacePoint& at) {
  const int t = at.triangle;
  const Eigen::Vector3d& w = at.barycentric;
  const int zeros = (w[0] == 0.0) + (w[1] == 0.0) + (w[2] == 0.0);
  Eigen::Vector3d sum = unit_normal(positions, triangles, t);
  if (zeros == 1) {
    // on the edge from corner k to k+1: the one whose opposite corner k+2 has weight 0
    const int k = w[0] == 0.0 ? 1 : w[1] == 0.0 ? 2 : 0;
    const int other = topology.neighbour(k, t);
    if (other >= 0) sum += unit_normal(positions, triangles, other);
  } else if (zeros == 2) {
    const int corner = w[0] != 0.0 ? 0 : w[1] != 0.0 ? 1 : 2;
    const int vertex = triangles(corner, t);
    sum.setZero();
    for (int i = topology.vertex_offset[static_cast<std::size_t>(vertex)];
         i < topology.vertex_offset[static_cast<std::size_t>(vertex) + 1]; ++i) {
      const int u = topology.vertex_triangle[static_cast<std::size_t>(i)];
      int k = 0;
      while (triangles(k, u) != vertex) ++k;
      const Eigen::Vector3d x = positions.col(vertex);
      const Eigen::Vector3d e1 = positions.col(triangles((k + 1) % 3, u)) - x;
      const Eigen::Vector3d e2 = positions.col(triangles((k + 2) % 3, u)) - x;
      const double angle = std::atan2(e1.cross(e2).norm(), e1.dot(e2));
      sum += angle * unit_normal(positions, triangles, u);
    }
  }
  const double length = sum.norm();
  return length > 0.0 ? Eigen::Vector3d(sum / length) : Eigen::Vector3d::Zero();
}

}  // namespace cubespring::bullet
