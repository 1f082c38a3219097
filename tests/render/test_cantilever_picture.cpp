// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The cantilever picture of `cubespring measure cantilever --png`: what it shows where, checked
// against the lattice projected with the picture's own camera (no OpenGL in the reference).
#include <cmath>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "cantilever_picture.h"
#include "cubespring/lattice_surface.h"
#include "cubespring/render/renderer.h"
#include "cubespring/render/wireframe.h"

// OSMesa (Mesa 22) keeps a few hundred bytes per process that it never frees; they are not ours.
extern "C" const char* __lsan_default_suppressions() { return "leak:libOSMesa.so\n"; }

namespace cubespring {
namespace {

constexpr int kWidth = 480;
constexpr int kHeight = 270;

ExperimentResult sagging_beam() {
  ExperimentSettings settings;
  settings.cells = {8, 2, 2};
  settings.material.young_modulus = 1e5;  // sags about a cell: a bent picture
  Result<ExperimentResult> result = run_experiment(Experiment::kCantilever, settings);
  EXPECT_TRUE(result) << result.message();
  return std::move(result).value();
}

struct Pixel {
  int r, g, b;
};
Pixel pixel_at(const app::CantileverPicture& picture, const Eigen::Vector3d& point) {
  const Eigen::Vector2d p = picture.camera.project(point, kWidth, kHeight);
  const int x = std::clamp(static_cast<int>(p.x()), 0, kWidth - 1);
  const int y = std::clamp(static_cast<int>(p.y()), 0, kHeight - 1);
  const std::uint8_t* c = picture.image.pixel(x, y);
  return {c[0], c[1], c[2]};
}

bool is_background(const Pixel& p) {
  const Eigen::Vector3d background = RenderSettings().background.cast<double>() * 255.0;
  return std::abs(p.r - background.x()) < 3 && std::abs(p.g - background.y()) < 3 && std::abs(p.b - background.z()) < 3;
}

// Centres of the surface triangles that face the eye, with the displacement there [m].
struct FacingPoint {
  Eigen::Vector3d centre;
  double displacement;
};
std::vector<FacingPoint> facing_points(const Eigen::Matrix3Xd& rest, const Eigen::Matrix3Xd& moved,
                                       const Eigen::Matrix3Xi& triangles, const Camera& camera) {
  std::vector<FacingPoint> points;
  for (Eigen::Index t = 0; t < triangles.cols(); ++t) {
    const Eigen::Vector3d a = moved.col(triangles(0, t));
    const Eigen::Vector3d b = moved.col(triangles(1, t));
    const Eigen::Vector3d c = moved.col(triangles(2, t));
    const Eigen::Vector3d centre = (a + b + c) / 3;
    const Eigen::Vector3d normal = (b - a).cross(c - a).normalized();
    const Eigen::Vector3d to_eye = (camera.position - centre).normalized();
    if (normal.dot(to_eye) < 0.3) continue;
    double displacement = 0;
    for (int k = 0; k < 3; ++k) displacement += (moved.col(triangles(k, t)) - rest.col(triangles(k, t))).norm() / 3;
    points.push_back({centre, displacement});
  }
  return points;
}

TEST(CantileverPicture, TheBeamCoversItsProjectionColouredByDisplacement) {
  const ExperimentResult beam = sagging_beam();
  Result<app::CantileverPicture> picture = app::draw_cantilever(beam, nullptr, {kWidth, kHeight, 1.0});
  ASSERT_TRUE(picture) << picture.message();
  ASSERT_EQ(picture->image.width, kWidth);
  ASSERT_EQ(picture->image.height, kHeight);

  const LatticeSurface surface = lattice_boundary_surface(beam.model);
  const std::vector<FacingPoint> points =
      facing_points(surface_vertices(surface, beam.model.rest_positions),
                    surface_vertices(surface, beam.state.positions), surface.triangles, picture->camera);
  ASSERT_GT(points.size(), 20u);
  const double largest = (beam.state.positions - beam.model.rest_positions).colwise().norm().maxCoeff();
  int covered = 0;
  for (const FacingPoint& point : points) {
    const Pixel p = pixel_at(*picture, point.centre);
    covered += is_background(p) ? 0 : 1;
    // viridis runs from purple (blue over red) at rest to yellow (red over blue) at the tip
    if (point.displacement < 0.2 * largest) {
      EXPECT_GT(p.b, p.r) << point.centre.transpose();
    }
    if (point.displacement > 0.8 * largest) {
      EXPECT_GT(p.r, p.b + 40) << point.centre.transpose();
    }
  }
  EXPECT_EQ(covered, static_cast<int>(points.size()));
  // the camera frames the beam with room around it: the left corners are background
  const auto& image = picture->image;
  for (int y : {1, kHeight - 2}) {
    const std::uint8_t* c = image.pixel(1, y);
    EXPECT_TRUE(is_background({c[0], c[1], c[2]})) << "row " << y;
  }
}

TEST(CantileverPicture, TheLatticeWireShowsThroughTheReferenceSurface) {
  const ExperimentResult beam = sagging_beam();
  // a reference one cell below the lattice: half of the wire lies inside its surface
  const LatticeSurface surface = lattice_boundary_surface(beam.model);
  FemSolution reference;
  reference.rest_positions = surface_vertices(surface, beam.model.rest_positions);
  reference.displacements = surface_vertices(surface, beam.state.positions) - reference.rest_positions;
  reference.displacements.row(2).array() -= beam.settings.cell_size.z();
  reference.surface = surface.triangles;
  Result<app::CantileverPicture> picture = app::draw_cantilever(beam, &reference, {kWidth, kHeight, 1.0});
  ASSERT_TRUE(picture) << picture.message();

  // every outer lattice edge (both nodes on the surface), the hidden ones too, shows red at its
  // midpoint
  Eigen::Matrix3Xd points;
  Eigen::Matrix2Xi edges;
  lattice_wireframe(beam.model, beam.state.positions, points, edges);
  std::vector<bool> on_surface(static_cast<std::size_t>(beam.model.num_nodes()), false);
  for (int node : surface.nodes) on_surface[static_cast<std::size_t>(node)] = true;
  int edges_seen = 0;
  int red = 0;
  for (Eigen::Index e = 0; e < edges.cols(); ++e) {
    if (!on_surface[static_cast<std::size_t>(edges(0, e))] || !on_surface[static_cast<std::size_t>(edges(1, e))])
      continue;
    const Eigen::Vector3d midpoint = 0.5 * (points.col(edges(0, e)) + points.col(edges(1, e)));
    ++edges_seen;
    const Pixel p = pixel_at(*picture, midpoint);
    red += (p.r > 120 && p.r > p.g + 60 && p.r > p.b + 60) ? 1 : 0;
  }
  EXPECT_GE(red, 0.95 * edges_seen) << red << " of " << edges_seen << " edge midpoints are red";

  // the reference's own surface is drawn where it projects, in the colour map's colours
  const Eigen::Matrix3Xd moved = reference.rest_positions + reference.displacements;
  int covered = 0;
  const std::vector<FacingPoint> facing =
      facing_points(reference.rest_positions, moved, reference.surface, picture->camera);
  for (const FacingPoint& point : facing) covered += is_background(pixel_at(*picture, point.centre)) ? 0 : 1;
  EXPECT_EQ(covered, static_cast<int>(facing.size()));
}

}  // namespace
}  // namespace cubespring
