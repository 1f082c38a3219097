// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The twist term of the exact-bending model (docs/model-exact-bending.md section 3): per axis d, the
// difference w_d between the shear of the cell's two faces normal to d, with energy
// W = 1/2 k V0 sum_d w_d^2, k = zeta G. Zero for any uniform deformation; nonzero on the
// checkerboard (zero-energy) modes of the spring lattice.
#pragma once

#include <array>
#include <utility>

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

/// Mean a- and c-edge vectors of a face.
struct FaceMeans {
  Eigen::Vector3d a, c;
};
inline FaceMeans face_means(const TwistFace& face, const std::array<Eigen::Vector3d, kEdgesPerCell>& edges) {
  return {0.5 * (edges[face.a_edges[0]] + edges[face.a_edges[1]]), 0.5 * (edges[face.c_edges[0]] + edges[face.c_edges[1]])};
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
    const double w = (upper.a.dot(upper.c) - lower.a.dot(lower.c)) / (h * h);
    energy += 0.5 * k * h * h * h * w * w;
    // dW/d(edge) = +-k h w / 2 times the other mean on that face
    for (int side = 0; side < 2; ++side) {
      const FaceMeans& means = side == 0 ? lower : upper;
      const double coefficient = (side == 0 ? -0.5 : 0.5) * k * h * w;
      for (int t = 0; t < 2; ++t) {
        add_force(faces[d][side].a_edges[t], coefficient * means.c);
        add_force(faces[d][side].c_edges[t], coefficient * means.a);
      }
    }
  }
  return energy;
}

/// The two face terms of each edge slot: faces[d][side] with the edge on that face's a (role 0)
/// or c (role 1) pair, in the order twist_energy() adds them.
struct EdgeTwistTerms {
  std::array<int, 2> face;  // d * 2 + side
  std::array<int, 2> role;
};
constexpr std::array<EdgeTwistTerms, kEdgesPerCell> make_edge_twist_terms() {
  std::array<EdgeTwistTerms, kEdgesPerCell> terms{};
  std::array<int, kEdgesPerCell> found{};
  for (int d = 0; d < 3; ++d) {
    for (int side = 0; side < 2; ++side) {
      for (int t = 0; t < 2; ++t) {
        for (int role = 0; role < 2; ++role) {
          const TwistFace& face = kTwistFaces[d][side];
          const int slot = role == 0 ? face.a_edges[t] : face.c_edges[t];
          terms[slot].face[found[slot]] = d * 2 + side;
          terms[slot].role[found[slot]] = role;
          ++found[slot];
        }
      }
    }
  }
  return terms;
}
inline constexpr std::array<EdgeTwistTerms, kEdgesPerCell> kEdgeTwistTerms = make_edge_twist_terms();

/// The forces of twist_energy() written once per edge slot: out.col(slot) = force on that edge's
/// lower corner [N]. Same terms in the same order, so the same bits, without summing in memory.
template <typename Out>
inline void twist_edge_forces(const std::array<Eigen::Vector3d, kEdgesPerCell>& edges, double h, double k, Out&& out) {
  const auto& faces = twist_faces();
  std::array<std::array<Eigen::Vector3d, 2>, 6> face_force;  // [d * 2 + side][role]
  for (int d = 0; d < 3; ++d) {
    const FaceMeans lower = face_means(faces[d][0], edges);
    const FaceMeans upper = face_means(faces[d][1], edges);
    const double w = (upper.a.dot(upper.c) - lower.a.dot(lower.c)) / (h * h);
    for (int side = 0; side < 2; ++side) {
      const FaceMeans& means = side == 0 ? lower : upper;
      const double coefficient = (side == 0 ? -0.5 : 0.5) * k * h * w;
      face_force[d * 2 + side] = {coefficient * means.c, coefficient * means.a};
    }
  }
  for (int slot = 0; slot < kEdgesPerCell; ++slot) {
    const EdgeTwistTerms& terms = kEdgeTwistTerms[slot];
    out.col(slot) = face_force[terms.face[0]][terms.role[0]] + face_force[terms.face[1]][terms.role[1]];
  }
}

}  // namespace cubespring
