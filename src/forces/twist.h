// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The twist term of the exact-bending model (docs/model-exact-bending.md section 3): per axis d, the
// difference w_d between the shear of the cell's two faces normal to d, with energy
// W = 1/2 k V0 sum_d w_d^2, k = zeta G. Zero for any uniform deformation; nonzero on the
// checkerboard (zero-energy) modes of the spring lattice.
#pragma once

#include <array>

#include <Eigen/Core>

#include "cubespring/model.h"

namespace cubespring {

/// The edges of one cell face: the two along axis a and the two along axis c (a < c, the axes
/// other than the face normal d), by slot (0-11, see model.h).
struct TwistFace {
  std::array<int, 2> a_edges;
  std::array<int, 2> c_edges;
};

/// Slot of the edge along axis a whose lower corner is c.
constexpr int edge_slot(int axis, int corner) {
  return axis * kEdgesPerAxis + (((corner >> (axis + 1)) << axis) | (corner & ((1 << axis) - 1)));
}

/// faces[d][side]: the face normal to d on side 0 (lower) or 1 (upper).
constexpr std::array<std::array<TwistFace, 2>, 3> make_twist_faces() {
  std::array<std::array<TwistFace, 2>, 3> faces{};
  for (int d = 0; d < 3; ++d) {
    const int a = d == 0 ? 1 : 0;
    const int c = d == 2 ? 1 : 2;
    for (int side = 0; side < 2; ++side) {
      for (int t = 0; t < 2; ++t) {
        faces[d][side].a_edges[t] = edge_slot(a, (side << d) | (t << c));
        faces[d][side].c_edges[t] = edge_slot(c, (side << d) | (t << a));
      }
    }
  }
  return faces;
}

inline constexpr std::array<std::array<TwistFace, 2>, 3> kTwistFaces = make_twist_faces();
inline const std::array<std::array<TwistFace, 2>, 3>& twist_faces() { return kTwistFaces; }

/// w_d of a cell: the dot products of the mean a- and c-edge vectors of its lower and upper faces
/// normal to d [m^2] over h^2, for a cell of side h [m].
[[gnu::always_inline]] inline double twist_shear(double lower_dot, double upper_dot, double h) {
  return (upper_dot - lower_dot) / (h * h);
}

/// Q_d = k h w_d / 2 [N/m], the coefficient of the twist's forces (stiffness k [Pa]): each edge of
/// the upper face gets +Q_d times the face's mean of the other in-plane edges, of the lower -Q_d.
/// The grid passes (forces/grid/grid_forces.cpp) and the spring lists (below) both use these two.
[[gnu::always_inline]] inline double twist_coefficient(double w, double k, double h) { return 0.5 * k * h * w; }

/// Mean a- and c-edge vectors of a face.
struct FaceMeans {
  Eigen::Vector3d a, c;
};
inline FaceMeans face_means(const TwistFace& face, const std::array<Eigen::Vector3d, kEdgesPerCell>& edges) {
  return {0.5 * (edges[face.a_edges[0]] + edges[face.a_edges[1]]),
          0.5 * (edges[face.c_edges[0]] + edges[face.c_edges[1]])};
}

/// Twist energy [J] of a cubic cell of side h [m] and stiffness k [Pa] from its 12 edge vectors
/// (x of the upper corner minus x of the lower); add_force(slot, f) receives the force on that
/// edge's lower corner [N] (the upper corner gets the negative).
template <typename ForceFn>
inline double twist_energy(const std::array<Eigen::Vector3d, kEdgesPerCell>& edges, double h, double k,
                           const ForceFn& add_force) {
  const auto& faces = twist_faces();
  double energy = 0.0;
  for (int d = 0; d < 3; ++d) {
    const FaceMeans lower = face_means(faces[d][0], edges);
    const FaceMeans upper = face_means(faces[d][1], edges);
    const double w = twist_shear(lower.a.dot(lower.c), upper.a.dot(upper.c), h);
    energy += 0.5 * k * h * h * h * w * w;
    // dW/d(edge) = +-k h w / 2 times the other mean on that face
    for (int side = 0; side < 2; ++side) {
      const FaceMeans& means = side == 0 ? lower : upper;
      const double coefficient = side == 0 ? -twist_coefficient(w, k, h) : twist_coefficient(w, k, h);
      for (int t = 0; t < 2; ++t) {
        add_force(faces[d][side].a_edges[t], coefficient * means.c);
        add_force(faces[d][side].c_edges[t], coefficient * means.a);
      }
    }
  }
  return energy;
}

/// The twist forces of the two faces normal to axis d on their corners (see twist_corner_forces);
/// d is a template argument so that every corner index is a constant.
template <int d>
inline void add_twist_face_forces(const std::array<Eigen::Vector3d, kEdgesPerCell>& edges, double h, double k,
                                  std::array<Eigen::Vector3d, kCornersPerCell>& corner) {
  constexpr int a = d == 0 ? 1 : 0;
  constexpr int c = d == 2 ? 1 : 2;
  const FaceMeans lower = face_means(kTwistFaces[d][0], edges);
  const FaceMeans upper = face_means(kTwistFaces[d][1], edges);
  const double coefficient = twist_coefficient(twist_shear(lower.a.dot(lower.c), upper.a.dot(upper.c), h), k, h);
  // lower face (side 0): coefficient -q; upper face (side 1): +q
  const Eigen::Vector3d lower_sum = coefficient * (lower.a + lower.c);
  const Eigen::Vector3d lower_difference = coefficient * (lower.a - lower.c);
  corner[0] -= lower_sum;
  corner[(1 << a) | (1 << c)] += lower_sum;
  corner[1 << a] -= lower_difference;
  corner[1 << c] += lower_difference;
  constexpr int up = 1 << d;
  const Eigen::Vector3d upper_sum = coefficient * (upper.a + upper.c);
  const Eigen::Vector3d upper_difference = coefficient * (upper.a - upper.c);
  corner[up] += upper_sum;
  corner[up | (1 << a) | (1 << c)] -= upper_sum;
  corner[up | (1 << a)] += upper_difference;
  corner[up | (1 << c)] -= upper_difference;
}

/// The forces of twist_energy() gathered on the cell's 8 corners [N], face by face: on a face with
/// means a, c and coefficient q, the a-edges' lower corners get q c and their upper ones -q c,
/// the c-edges' q a and -q a, so its corner 0 gets q (a + c), the opposite corner -q (a + c), the
/// corner one step along a q (a - c), and the one a step along c -q (a - c).
inline std::array<Eigen::Vector3d, kCornersPerCell> twist_corner_forces(
    const std::array<Eigen::Vector3d, kEdgesPerCell>& edges, double h, double k) {
  std::array<Eigen::Vector3d, kCornersPerCell> corner;
  corner.fill(Eigen::Vector3d::Zero());
  add_twist_face_forces<0>(edges, h, k, corner);
  add_twist_face_forces<1>(edges, h, k, corner);
  add_twist_face_forces<2>(edges, h, k, corner);
  return corner;
}

}  // namespace cubespring
