// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The contact surface's refinement (surface_refinement.h) against what a refinement must keep: the
// surface itself (area, enclosed volume, each triangle's side), a closed mesh closed, the input's
// vertices first, and no edge longer than asked.
#include <map>
#include <utility>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "cubespring/shapes.h"
#include "surface_refinement.h"

namespace cubespring::bullet {
namespace {

Eigen::Vector3d corner(const TriangleMesh& mesh, int t, int k) { return mesh.vertices.col(mesh.triangles(k, t)); }

Eigen::Vector3d area_vector(const TriangleMesh& mesh, int t) {
  return 0.5 * (corner(mesh, t, 1) - corner(mesh, t, 0)).cross(corner(mesh, t, 2) - corner(mesh, t, 0));
}

double longest_edge(const TriangleMesh& mesh) {
  double longest = 0.0;
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    for (int k = 0; k < 3; ++k) longest = std::max(longest, (corner(mesh, t, k) - corner(mesh, t, (k + 1) % 3)).norm());
  }
  return longest;
}

double enclosed_volume(const TriangleMesh& mesh) {
  double volume = 0.0;
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    volume += corner(mesh, t, 0).dot(corner(mesh, t, 1).cross(corner(mesh, t, 2))) / 6;
  }
  return volume;
}

// Every directed edge once, and its reverse once: closed, consistently wound, no T-junction.
bool closed_and_conforming(const TriangleMesh& mesh) {
  std::map<std::pair<int, int>, int> directed;
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    for (int k = 0; k < 3; ++k) ++directed[{mesh.triangles(k, t), mesh.triangles((k + 1) % 3, t)}];
  }
  for (const auto& [edge, count] : directed) {
    const auto reverse = directed.find({edge.second, edge.first});
    if (count != 1 || reverse == directed.end() || reverse->second != 1) return false;
  }
  return true;
}

TEST(SurfaceRefinement, ALongThinTriangleIsCutUntilNoEdgeIsLongerThanAsked) {
  TriangleMesh sliver;
  sliver.vertices.resize(3, 3);
  sliver.vertices << 0, 0.1, 0.03,  //
      0, 0, 0.004,                  //
      0, 0, 0.001;
  sliver.triangles.resize(3, 1);
  sliver.triangles << 0, 1, 2;
  const TriangleMesh refined = split_long_edges(sliver, 0.008);
  EXPECT_LE(longest_edge(refined), 0.008);
  EXPECT_EQ(refined.vertices.leftCols(3), sliver.vertices) << "the input's vertices first, in their order";
  const Eigen::Vector3d whole = area_vector(sliver, 0);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int t = 0; t < refined.num_triangles(); ++t) {
    const Eigen::Vector3d piece = area_vector(refined, t);
    EXPECT_GT(piece.dot(whole), 0.0) << "triangle " << t << " keeps the winding";
    EXPECT_NEAR(piece.normalized().dot(whole.normalized()), 1.0, 1e-12) << "triangle " << t << " lies in the plane";
    sum += piece;
  }
  EXPECT_LT((sum - whole).norm(), 1e-15) << "the pieces cover the triangle once";
}

TEST(SurfaceRefinement, AClosedMeshStaysClosedAndKeepsItsVolume) {
  const TriangleMesh octahedron = sphere_mesh(0.05, 0);  // edges of 7.1 cm
  ASSERT_TRUE(closed_and_conforming(octahedron));
  for (const double max_edge : {0.06, 0.02, 0.0051}) {
    const TriangleMesh refined = split_long_edges(octahedron, max_edge);
    EXPECT_LE(longest_edge(refined), max_edge);
    EXPECT_TRUE(closed_and_conforming(refined)) << "max edge " << max_edge;
    EXPECT_NEAR(enclosed_volume(refined), enclosed_volume(octahedron), 1e-15) << "max edge " << max_edge;
    EXPECT_EQ(refined.num_vertices() - refined.num_triangles() / 2, 2) << "Euler: V - E + F = V - F / 2 = 2";
  }
}

TEST(SurfaceRefinement, AMeshFinerThanAskedComesBackAsItWas) {
  const TriangleMesh sphere = sphere_mesh(0.05, 3);
  const TriangleMesh refined = split_long_edges(sphere, 2 * longest_edge(sphere));
  EXPECT_EQ(refined.vertices, sphere.vertices);
  EXPECT_EQ(refined.triangles, sphere.triangles);
}

}  // namespace
}  // namespace cubespring::bullet
