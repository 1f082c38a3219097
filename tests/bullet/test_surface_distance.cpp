// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The geometry round tools' contact stands on (plugins/bullet/src/surface_distance.h,
// surface_topology.h, round_tool_contact.h), against brute force and closed forms.
#include <cmath>
#include <random>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "round_tool_contact.h"
#include "surface_distance.h"
#include "surface_topology.h"

namespace cubespring::bullet {
namespace {

// The octahedron |x| + |y| + |z| <= size around `centre`, its faces counter-clockwise from
// outside; vertices numbered from `first`.
void add_octahedron(double size, const Eigen::Vector3d& centre, Eigen::Matrix3Xd& positions,
                    Eigen::Matrix3Xi& triangles) {
  const int first = static_cast<int>(positions.cols());
  positions.conservativeResize(3, first + 6);
  for (int axis = 0; axis < 3; ++axis) {
    positions.col(first + 2 * axis) = centre + size * Eigen::Vector3d::Unit(axis);
    positions.col(first + 2 * axis + 1) = centre - size * Eigen::Vector3d::Unit(axis);
  }
  const Eigen::Index faces = triangles.cols();
  triangles.conservativeResize(3, faces + 8);
  int f = 0;
  for (int sx = 0; sx < 2; ++sx) {
    for (int sy = 0; sy < 2; ++sy) {
      for (int sz = 0; sz < 2; ++sz) {
        Eigen::Vector3i t(first + sx, first + 2 + sy, first + 4 + sz);
        if ((sx + sy + sz) % 2 == 1) std::swap(t[1], t[2]);  // outward winding
        triangles.col(faces + f++) = t;
      }
    }
  }
}

Eigen::Vector3d point_of(const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xi& tri, int t, const Eigen::Vector3d& w) {
  return w[0] * x.col(tri(0, t)) + w[1] * x.col(tri(1, t)) + w[2] * x.col(tri(2, t));
}

TEST(SurfaceDistance, OctahedronIsOutward) {
  Eigen::Matrix3Xd x(3, 0);
  Eigen::Matrix3Xi tri(3, 0);
  add_octahedron(1.0, Eigen::Vector3d::Zero(), x, tri);
  double volume = 0.0;
  for (int t = 0; t < tri.cols(); ++t) volume += x.col(tri(0, t)).dot(x.col(tri(1, t)).cross(x.col(tri(2, t)))) / 6.0;
  EXPECT_NEAR(volume, 4.0 / 3.0, 1e-12);
}

TEST(SurfaceDistance, NearestPointsAgreeWithBruteForce) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const auto any = [&] { return Eigen::Vector3d(uniform(random), uniform(random), uniform(random)); };
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Vector3d a = any(), b = any(), c = any(), p0 = any(), p1 = any();
    const SegmentTriangleClosest found = closest_segment_triangle(p0, p1, a, b, c);
    EXPECT_GE(found.along, 0.0);
    EXPECT_LE(found.along, 1.0);
    EXPECT_NEAR(found.barycentric.sum(), 1.0, 1e-12);
    EXPECT_GE(found.barycentric.minCoeff(), -1e-12);
    const Eigen::Vector3d on_triangle = found.barycentric[0] * a + found.barycentric[1] * b + found.barycentric[2] * c;
    EXPECT_NEAR((p0 + found.along * (p1 - p0) - on_triangle).norm(), found.distance, 1e-12);
    // no sampled pair of points is nearer; a fine sampling comes within its spacing
    double sampled = 1e300;
    constexpr int kSteps = 60;
    for (int i = 0; i <= kSteps; ++i) {
      const Eigen::Vector3d s = p0 + (static_cast<double>(i) / kSteps) * (p1 - p0);
      const Eigen::Vector3d w = closest_barycentric(s, a, b, c);
      const double d = (w[0] * a + w[1] * b + w[2] * c - s).norm();
      sampled = std::min(sampled, d);
      for (int j = 0; j <= kSteps; ++j) {
        for (int k = 0; i == 0 && j + k <= kSteps; ++k) {
          const Eigen::Vector3d q =
              a + (static_cast<double>(j) / kSteps) * (b - a) + (static_cast<double>(k) / kSteps) * (c - a);
          EXPECT_GE((q - s).norm(), (w[0] * a + w[1] * b + w[2] * c - s).norm() - 1e-12) << "closest_barycentric";
        }
      }
    }
    EXPECT_LE(found.distance, sampled + 1e-12);
    EXPECT_GE(found.distance, sampled - (p1 - p0).norm() / kSteps);
  }
}

TEST(SurfaceDistance, PseudonormalTellsInsideFromOutsideAtFacesEdgesAndCorners) {
  Eigen::Matrix3Xd x(3, 0);
  Eigen::Matrix3Xi tri(3, 0);
  add_octahedron(1.0, Eigen::Vector3d::Zero(), x, tri);
  const SurfaceTopology topology = surface_topology(x, tri);
  for (int t = 0; t < tri.cols(); ++t) {
    for (int k = 0; k < 3; ++k) EXPECT_GE(topology.neighbour(k, t), 0) << "a closed surface";
  }
  std::mt19937 random(3);
  std::uniform_real_distribution<double> uniform(-1.6, 1.6);
  int inside = 0, corners_or_edges = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Eigen::Vector3d p(uniform(random), uniform(random), uniform(random));
    const double level = p.cwiseAbs().sum();
    if (std::abs(level - 1.0) < 1e-6) continue;
    SurfacePoint nearest;
    double distance = 1e300;
    for (int t = 0; t < tri.cols(); ++t) {
      const Eigen::Vector3d w = closest_barycentric(p, x.col(tri(0, t)), x.col(tri(1, t)), x.col(tri(2, t)));
      const double d = (point_of(x, tri, t, w) - p).norm();
      if (d < distance) {
        distance = d;
        nearest = {t, w};
      }
    }
    corners_or_edges += (nearest.barycentric.array() == 0.0).any();
    const bool outside =
        (p - point_of(x, tri, nearest.triangle, nearest.barycentric)).dot(pseudonormal(x, tri, topology, nearest)) >
        0.0;
    EXPECT_EQ(outside, level > 1.0) << p.transpose();
    inside += level < 1.0;
  }
  EXPECT_GT(inside, 50);  // the octahedron is 4% of the box the points are drawn from
  EXPECT_GT(corners_or_edges, 500) << "outside points mostly meet the octahedron at its edges and corners";
}

TEST(SurfaceTopology, ASurfaceInsideAnotherIsNotOuter) {
  Eigen::Matrix3Xd x(3, 0);
  Eigen::Matrix3Xi tri(3, 0);
  add_octahedron(1.0, Eigen::Vector3d::Zero(), x, tri);
  add_octahedron(0.3, Eigen::Vector3d(0.1, 0.2, 0.05), x, tri);  // an inclusion
  add_octahedron(0.5, Eigen::Vector3d(3, 0, 0), x, tri);         // a second body beside it
  const SurfaceTopology topology = surface_topology(x, tri);
  for (int t = 0; t < 24; ++t) EXPECT_EQ(topology.outer[static_cast<std::size_t>(t)], (t < 8 || t >= 16) ? 1 : 0) << t;
  for (int v = 0; v < x.cols(); ++v) {
    EXPECT_EQ(
        topology.vertex_offset[static_cast<std::size_t>(v) + 1] - topology.vertex_offset[static_cast<std::size_t>(v)],
        4);
  }
}

TEST(RoundToolContact, ACoreInsideOrOutsideIsAtItsSignedDistance) {
  Eigen::Matrix3Xd x(3, 0);
  Eigen::Matrix3Xi tri(3, 0);
  add_octahedron(1.0, Eigen::Vector3d::Zero(), x, tri);
  const SurfaceTopology topology = surface_topology(x, tri);
  std::vector<int> all(8);
  for (int t = 0; t < 8; ++t) all[static_cast<std::size_t>(t)] = t;
  const Eigen::Vector3d face_normal = Eigen::Vector3d::Ones().normalized();
  // a sphere's centre over the middle of the (+,+,+) face, outside and inside
  for (const double level : {1.3, 0.8}) {
    const Eigen::Vector3d centre = Eigen::Vector3d::Constant(level / 3.0);
    const std::vector<CoreContact> contacts = core_contacts({centre, centre, 0.1}, x, tri, topology, all, 0.1);
    ASSERT_FALSE(contacts.empty());
    EXPECT_NEAR(contacts[0].signed_distance, (level - 1.0) / std::sqrt(3.0), 1e-12);
    EXPECT_NEAR((contacts[0].normal - face_normal).norm(), 0.0, 1e-12) << "the tissue's outward normal";
  }
  // a capsule lying along the (+,+,+) face's edge from (1,0,0) to (0,1,0), a little outside it:
  // its nearest points are on both faces that share the edge, and the corners beyond
  const Eigen::Vector3d lift = 0.05 * Eigen::Vector3d(1, 1, 0).normalized();
  const RoundCore capsule{Eigen::Vector3d(0.9, 0.1, 0) + lift, Eigen::Vector3d(0.1, 0.9, 0) + lift, 0.1};
  const std::vector<CoreContact> along_edge = core_contacts(capsule, x, tri, topology, all, 0.1);
  ASSERT_FALSE(along_edge.empty());
  EXPECT_NEAR(along_edge[0].signed_distance, 0.05, 1e-12);
  for (const CoreContact& contact : along_edge) EXPECT_GT(contact.signed_distance, 0.0);
}

// Where the surface folds around a thin tool its walls cross, and the nearest point's
// pseudonormal can put the core inside the tissue when it is not. A core that was outside a
// moment ago cannot be far inside now: core_contacts takes an inside verdict deeper than the
// depth it is told to believe as a fold's. The core stays outside, and every surface point within
// reach, the fold's seen from behind too, leaves the tool away from the core.
TEST(RoundToolContact, AnInsideVerdictDeeperThanBelievedIsAFoldWhoseSurfaceLeavesTheToolAwayFromTheCore) {
  Eigen::Matrix3Xd x(3, 0);
  Eigen::Matrix3Xi tri(3, 0);
  add_octahedron(1.0, Eigen::Vector3d::Zero(), x, tri);  // its (+,+,+) face is x + y + z = 1
  // a second part whose (-,-,-) face, x + y + z = 3 s - 1, faces the first from 0.08 beyond the core
  const double beyond = 0.08;
  const double s = (1.9 + beyond * std::sqrt(3.0)) / 3.0;
  add_octahedron(1.0, Eigen::Vector3d::Constant(s), x, tri);
  const SurfaceTopology topology = surface_topology(x, tri);
  std::vector<int> all(16);
  for (int t = 0; t < 16; ++t) all[static_cast<std::size_t>(t)] = t;
  // the core on the first face's normal, 0.1 / sqrt(3) behind it: the nearest surface point
  const Eigen::Vector3d centre = Eigen::Vector3d::Constant(0.3);
  const double behind = 0.1 / std::sqrt(3.0);
  const RoundCore sphere{centre, centre, 0.1};
  const Eigen::Vector3d toward_second = Eigen::Vector3d::Ones().normalized();

  const std::vector<CoreContact> believed = core_contacts(sphere, x, tri, topology, all, 0.1);
  ASSERT_EQ(believed.size(), 1u);
  EXPECT_NEAR(believed[0].signed_distance, -behind, 1e-12) << "believed: the core is inside";
  EXPECT_EQ(core_contacts(sphere, x, tri, topology, all, 0.1, 1.01 * behind).size(), 1u);

  const std::vector<CoreContact> fold = core_contacts(sphere, x, tri, topology, all, 0.1, 0.5 * behind);
  ASSERT_EQ(fold.size(), 2u) << "the fold's point and the second part's face";
  // both lie beyond the core along (1, 1, 1): each is pushed that way, out of the tool (a
  // contact's normal points from the surface toward the core, its push against it)
  EXPECT_LT(fold[0].surface.triangle, 8) << "the fold's point, seen from behind";
  EXPECT_NEAR(fold[0].signed_distance, behind, 1e-12);
  EXPECT_GE(fold[1].surface.triangle, 8);
  EXPECT_NEAR(fold[1].signed_distance, beyond, 1e-12);
  for (const CoreContact& contact : fold) {
    EXPECT_NEAR((contact.normal + toward_second).norm(), 0.0, 1e-12);
  }
}

}  // namespace
}  // namespace cubespring::bullet
