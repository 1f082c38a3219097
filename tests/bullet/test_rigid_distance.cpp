// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The way out of a flat-faced rigid shape (rigid_distance.h): through the face the tissue presses
// on at an edge, but never through a face more than half a cell beyond the nearest one; the
// tissue's normal worked out only where that choice needs it; a box reaching through a triangle
// only near one of its corners.
#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "rigid_distance.h"

namespace cubespring::bullet {
namespace {

constexpr double kCell = 0.008;

ContactReach projector_reach() {
  ContactReach reach;
  reach.thickness = 2 * kCell;  // what the contact projector gives without max_depth
  reach.detour = 0.5 * kCell;
  return reach;
}

void expect_near(const std::optional<Eigen::Vector3d>& push, const Eigen::Vector3d& expected) {
  ASSERT_TRUE(push.has_value());
  // Bullet may be single precision: its shapes hold floats
  EXPECT_LT((*push - expected).norm(), 1e-7) << "push " << push->transpose() << ", expected " << expected.transpose();
}

// The scene's table: a slab 50 cm square and 2 cm thick whose top is z = 0.
btBoxShape table_shape() { return btBoxShape(btVector3(0.25f, 0.25f, 0.01f)); }
btTransform table_place() { return btTransform(btQuaternion::getIdentity(), btVector3(0, 0, -0.01f)); }

TEST(RigidDistance, ASideWallGrazingATableLeavesThroughItsTop) {
  // a point of an organ's side wall, its outward normal tilted 7 degrees up, 0.05 mm into the
  // table: the ray into the tissue leaves the slab through its side 17 cm away, which threw the
  // point there (a liver on the table blew up at once); the nearest way out is up
  const btBoxShape table = table_shape();
  const Eigen::Vector3d point(-0.08, 0.05, -5e-5);
  const Eigen::Vector3d wall_normal = Eigen::Vector3d(0.763, -0.636, 0.115).normalized();
  expect_near(penetration_push(table, table_place(), point, wall_normal, projector_reach()),
              Eigen::Vector3d(0, 0, 5e-5));
}

TEST(RigidDistance, AnEdgePressedIntoTheTissueLeavesThroughThePressingFace) {
  // a 2 cm box sunk 2 mm into tissue whose surface faces up meets a vertex 0.5 mm behind its
  // leading face: the face pressing on the tissue is its bottom, 2 mm away (the nearest face, its
  // leading one, would push the vertex forward into a wall ahead of the box)
  const btBoxShape box(btVector3(0.01f, 0.01f, 0.01f));
  const btTransform place = btTransform::getIdentity();
  const Eigen::Vector3d point(0.0095, 0.0, -0.008);
  const Eigen::Vector3d up(0, 0, 1);
  expect_near(penetration_push(box, place, point, up, projector_reach()), Eigen::Vector3d(0, 0, -0.002));
  // the same face only while it lies within reach.detour of the nearest one
  ContactReach short_reach;
  short_reach.detour = 0.001;
  expect_near(penetration_push(box, place, point, up, short_reach), Eigen::Vector3d(0.0005, 0, 0));
}

TEST(RigidDistance, APointUnderAFaceWhereTheSurfaceIsFoldedLeavesThroughThatFace) {
  // a 3 cm box dropped on soft tissue has sunk into it; a node of the crumpled surface under its
  // bottom, 0.01 mm inside, 1.5 cells from its side, has a normal that a fold turned sideways and
  // a little down: the ray into the tissue leaves through the side, and with a detour of two
  // cells the node was thrown out there, 12 mm in one sub-step, turning a cell inside out
  const btBoxShape box(btVector3(0.015f, 0.015f, 0.015f));
  const btTransform place = btTransform::getIdentity();
  const Eigen::Vector3d point(-0.015 + 1.5 * kCell, -0.0025, -0.015 + 1e-5);
  const Eigen::Vector3d folded = Eigen::Vector3d(1.0, 0.0, -0.2).normalized();
  expect_near(penetration_push(box, place, point, folded, projector_reach()), Eigen::Vector3d(0, 0, -1e-5));
}

TEST(RigidDistance, ACylinderAndAHullFollowTheSameRule) {
  // the grazing side wall against a cylinder table and a hull table: up, not through the side
  const Eigen::Vector3d point(-0.08, 0.05, -5e-5);
  const Eigen::Vector3d wall_normal = Eigen::Vector3d(0.763, -0.636, 0.115).normalized();
  const btCylinderShapeZ cylinder(btVector3(0.25f, 0.25f, 0.01f));
  expect_near(penetration_push(cylinder, table_place(), point, wall_normal, projector_reach()),
              Eigen::Vector3d(0, 0, 5e-5));
  btConvexHullShape hull;
  for (int corner = 0; corner < 8; ++corner) {
    hull.addPoint(btVector3(corner & 1 ? 0.25f : -0.25f, corner & 2 ? 0.25f : -0.25f, corner & 4 ? 0.01f : -0.01f));
  }
  hull.setMargin(0);
  expect_near(penetration_push(hull, table_place(), point, wall_normal, projector_reach()),
              Eigen::Vector3d(0, 0, 5e-5));
}

// A triangle of tissue wrapped over the top front edge of a 2 cm box (the edge along x at
// y = z = h), its plane normal to the edge's diagonal d = (0, 1, 1) / sqrt(2), `beyond` [m] out
// along d from the edge (negative: the edge pokes through it into the tissue by that much), its
// corners 3 mm around the point over the edge at x = `along`; the tissue lies beyond it, so its
// outward normal is -d (counter-clockwise seen from the box).
struct AcrossTheEdge {
  Eigen::Vector3d a, b, c;
};
constexpr double kBoxHalf = 0.01;
AcrossTheEdge triangle_across_the_edge(double beyond, double along = 0.0) {
  const Eigen::Vector3d n = Eigen::Vector3d(0, 1, 1).normalized();
  const Eigen::Vector3d e1 = Eigen::Vector3d::UnitX(), e2 = Eigen::Vector3d(0, 1, -1).normalized();
  const Eigen::Vector3d centre = Eigen::Vector3d(along, kBoxHalf, kBoxHalf) + beyond * n;
  return {centre - 0.003 * e1 - 0.003 * e2, centre + 0.003 * e2, centre + 0.003 * e1 - 0.003 * e2};
}

TEST(RigidDistance, ABoxEdgeThroughATriangleBetweenItsCornersPushesItByTheEdgesDepth) {
  const btScalar half = static_cast<btScalar>(kBoxHalf);
  const btBoxShape box(btVector3(half, half, half));
  const std::vector<RigidEdge> edges = box_edges(box, btTransform::getIdentity(), 0.0);
  ASSERT_EQ(edges.size(), 12u);
  const auto deepest = [&](const AcrossTheEdge& t, double thickness) {
    std::optional<FacePenetration> found;
    for (const RigidEdge& edge : edges) {
      const std::optional<FacePenetration> through = edge_penetration(edge, t.a, t.b, t.c, thickness);
      if (through && (!found || through->depth > found->depth)) found = through;
    }
    return found;
  };
  // the edge 1 mm through the triangle: the triangle goes back 1 mm, its foot on the edge's line
  const AcrossTheEdge poked = triangle_across_the_edge(-0.001);
  const std::optional<FacePenetration> through = deepest(poked, 0.004);
  ASSERT_TRUE(through.has_value());
  EXPECT_NEAR(through->depth, 0.001, 1e-9);
  EXPECT_NEAR(through->barycentric.sum(), 1.0, 1e-12);
  EXPECT_TRUE((through->barycentric.array() >= -1e-12).all()) << through->barycentric.transpose();
  const Eigen::Vector3d foot =
      through->barycentric[0] * poked.a + through->barycentric[1] * poked.b + through->barycentric[2] * poked.c;
  const Eigen::Vector3d on_edge = foot + 0.001 * Eigen::Vector3d(0, 1, 1).normalized();
  EXPECT_NEAR(on_edge.y(), kBoxHalf, 1e-9);
  EXPECT_NEAR(on_edge.z(), kBoxHalf, 1e-9);
  // clear of it, beside it (the edge ends at x = 0.01; the triangle spans x = 0.012 .. 0.018), or
  // deeper than the thickness (a tool inside the tissue, which the vertex contacts hold): nothing
  EXPECT_FALSE(deepest(triangle_across_the_edge(0.0005), 0.004).has_value());
  EXPECT_FALSE(deepest(triangle_across_the_edge(-0.001, 0.015), 0.004).has_value());
  EXPECT_FALSE(deepest(poked, 0.0005).has_value());
  // grown by an offset, the edge reaches that much farther through
  const std::vector<RigidEdge> grown = box_edges(box, btTransform::getIdentity(), 0.0005);
  double grown_depth = 0.0;
  for (const RigidEdge& edge : grown) {
    if (const std::optional<FacePenetration> t = edge_penetration(edge, poked.a, poked.b, poked.c, 0.004)) {
      grown_depth = std::max(grown_depth, t->depth);
    }
  }
  EXPECT_NEAR(grown_depth, 0.001 + 0.0005 * std::sqrt(2.0), 1e-9);
}

// An edge across a triangle's plane: the part over the triangle is clipped by the prism's sides,
// and the deeper end of what is left is the hit (1 cm right triangle in z = 0, the tissue below).
TEST(RigidDistance, AnEdgeAcrossTheTrianglesPlaneIsClippedToItsPrism) {
  const double s = 0.01;
  const Eigen::Vector3d a(0, 0, 0), b(s, 0, 0), c(0, s, 0);  // outward normal +z
  const auto hit = [&](const Eigen::Vector3d& from, const Eigen::Vector3d& to, double thickness = 0.004) {
    return edge_penetration(RigidEdge{from * s, to * s}, a, b, c, thickness);
  };
  // down from x = -0.5 to 0.5 at y = 0.25: over the triangle from x = 0, deepest at its end
  std::optional<FacePenetration> through = hit({-0.5, 0.25, 0.05}, {0.5, 0.25, -0.05});
  ASSERT_TRUE(through.has_value());
  EXPECT_NEAR(through->depth, 0.05 * s, 1e-12);
  EXPECT_TRUE(through->barycentric.isApprox(Eigen::Vector3d(0.25, 0.5, 0.25), 1e-9))
      << through->barycentric.transpose();
  // steeper, on past the hypotenuse x + y = 1: deepest where it leaves the prism, at x = 0.75
  through = hit({0.25, 0.25, 0.05}, {1.25, 0.25, -0.15});
  ASSERT_TRUE(through.has_value());
  EXPECT_NEAR(through->depth, 0.05 * s, 1e-12);
  EXPECT_TRUE(through->barycentric.isApprox(Eigen::Vector3d(0.0, 0.75, 0.25), 1e-9))
      << through->barycentric.transpose();
  // the same edge reversed gives the same hit
  const std::optional<FacePenetration> reversed = hit({1.25, 0.25, -0.15}, {0.25, 0.25, 0.05});
  ASSERT_TRUE(reversed.has_value());
  EXPECT_NEAR(reversed->depth, through->depth, 1e-15);
  // a point (an edge of no length) behind the triangle; a degenerate triangle; an edge beside
  // the prism; an edge in front of the plane
  through = hit({0.2, 0.2, -0.1}, {0.2, 0.2, -0.1});
  ASSERT_TRUE(through.has_value());
  EXPECT_NEAR(through->depth, 0.1 * s, 1e-12);
  EXPECT_FALSE(edge_penetration(RigidEdge{Eigen::Vector3d(0.002, 0.002, -0.001), Eigen::Vector3d(0.003, 0.002, -0.001)},
                                a, b, a, 0.004)
                   .has_value());
  EXPECT_FALSE(hit({-0.5, -0.25, -0.05}, {0.5, -0.25, -0.05}).has_value());
  EXPECT_FALSE(hit({0.1, 0.1, 0.05}, {0.5, 0.2, 0.01}).has_value());
}

TEST(RigidDistance, TheTissuesNormalIsWorkedOutOnlyWhereTwoFacesAreAboutEquallyNear) {
  const btBoxShape box(btVector3(0.01f, 0.01f, 0.01f));
  const btTransform place = btTransform::getIdentity();
  const Eigen::Vector3d up(0, 0, 1);
  int asked = 0;
  const auto normal = [&] {
    ++asked;
    return up;
  };
  // under the middle of the bottom face, 0.5 mm in: every other face is 9.5 mm or more away
  const Eigen::Vector3d middle(0.0, 0.0, -0.0095);
  const std::optional<Eigen::Vector3d> lazy =
      penetration_push(box, place, middle, SurfaceNormal::when_asked(normal), projector_reach());
  EXPECT_EQ(asked, 0);
  expect_near(lazy, Eigen::Vector3d(0, 0, -0.0005));
  // at the edge of the test above, the leading face is nearer: the normal decides, and is asked
  // for once, with the answer the known normal gives
  const Eigen::Vector3d at_edge(0.0095, 0.0, -0.008);
  const std::optional<Eigen::Vector3d> asked_for =
      penetration_push(box, place, at_edge, SurfaceNormal::when_asked(normal), projector_reach());
  EXPECT_EQ(asked, 1);
  expect_near(asked_for, *penetration_push(box, place, at_edge, up, projector_reach()));
  expect_near(asked_for, Eigen::Vector3d(0, 0, -0.002));
}

TEST(RigidDistance, ABoxReachesThroughATriangleOnlyNearOneOfItsCorners) {
  // random boxes and triangles around them: every triangle face_penetration() finds the box
  // reaching through lies within the offset and the depth of one of face_penetration_points()
  const btBoxShape box(btVector3(0.01f, 0.02f, 0.005f));
  ContactReach reach;
  reach.offset = 0.0005;
  reach.thickness = 0.004;
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int hits = 0;
  for (int trial = 0; trial < 100000; ++trial) {
    const btQuaternion turn(btVector3(static_cast<btScalar>(unit(random)), static_cast<btScalar>(unit(random)),
                                      static_cast<btScalar>(unit(random))),
                            static_cast<btScalar>(3.0 * unit(random)));
    const btTransform place(turn, btVector3(0.001f, -0.002f, 0.003f));
    const std::optional<std::vector<Eigen::Vector3d>> corners = face_penetration_points(box, place);
    ASSERT_TRUE(corners.has_value());
    ASSERT_EQ(corners->size(), 8u);
    const Eigen::Vector3d centre = 0.025 * Eigen::Vector3d(unit(random), unit(random), unit(random));
    const double size = 0.002 + 0.01 * (1.0 + unit(random));
    const Eigen::Vector3d a = centre + size * Eigen::Vector3d(unit(random), unit(random), unit(random));
    const Eigen::Vector3d b = centre + size * Eigen::Vector3d(unit(random), unit(random), unit(random));
    const Eigen::Vector3d c = centre + size * Eigen::Vector3d(unit(random), unit(random), unit(random));
    const std::optional<FacePenetration> through = face_penetration(box, place, a, b, c, reach);
    if (!through) continue;
    ++hits;
    const Eigen::AlignedBox3d triangle(a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c));
    const double within = reach.offset + reach.thickness;
    const bool near_a_corner = std::any_of(corners->begin(), corners->end(), [&](const Eigen::Vector3d& corner) {
      return Eigen::AlignedBox3d(corner.array() - within, corner.array() + within).intersects(triangle);
    });
    ASSERT_TRUE(near_a_corner) << "trial " << trial;
  }
  EXPECT_GT(hits, 200);  // the triangles met the box often enough to tell
  // the corners are the box's, in the world frame; other shapes have no such few points
  const btTransform lifted(btQuaternion::getIdentity(), btVector3(0, 0, 1));
  const std::optional<std::vector<Eigen::Vector3d>> lifted_corners = face_penetration_points(box, lifted);
  ASSERT_TRUE(lifted_corners.has_value());
  for (const Eigen::Vector3d& corner : *lifted_corners) {
    EXPECT_NEAR(std::abs(corner.x()), 0.01, 1e-6);
    EXPECT_NEAR(std::abs(corner.y()), 0.02, 1e-6);
    EXPECT_NEAR(std::abs(corner.z() - 1.0), 0.005, 1e-6);
  }
  EXPECT_FALSE(face_penetration_points(btSphereShape(0.01f), lifted).has_value());
  EXPECT_FALSE(face_penetration_points(btCapsuleShapeZ(0.005f, 0.02f), lifted).has_value());
}

TEST(RigidDistance, OnlyBoxesHaveEdges) {
  EXPECT_TRUE(box_edges(btSphereShape(0.01f), btTransform::getIdentity(), 0.0).empty());
  EXPECT_TRUE(box_edges(btCapsuleShapeZ(0.005f, 0.02f), btTransform::getIdentity(), 0.0).empty());
  btCompoundShape handle;
  btBoxShape blade(btVector3(0.01f, 0.002f, 0.03f));
  handle.addChildShape(btTransform(btQuaternion::getIdentity(), btVector3(0, 0, 0.05f)), &blade);
  const std::vector<RigidEdge> edges = box_edges(handle, btTransform::getIdentity(), 0.0);
  ASSERT_EQ(edges.size(), 12u);
  for (const RigidEdge& edge : edges) {
    EXPECT_NEAR(std::abs(edge.from.z() - 0.05), 0.03, 1e-7) << "the child's place is kept";
  }
}

}  // namespace
}  // namespace cubespring::bullet
