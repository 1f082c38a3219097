// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "cantilever_picture.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "cubespring/embedding.h"
#include "cubespring/lattice_surface.h"
#include "cubespring/render/renderer.h"
#include "cubespring/render/wireframe.h"

namespace cubespring::app {

namespace {

constexpr double kFieldOfViewDegrees = 25;
constexpr double kUsedWidth = 0.78;  // of the image: the legend takes the right edge
constexpr double kUsedHeight = 0.9;
const Eigen::Vector3f kWireOverReference{0.9f, 0.1f, 0.1f};  // red shows on every viridis colour
const Eigen::Vector3f kWireOverLattice{0.1f, 0.1f, 0.1f};

// The lattice edges that lie on its outer surface: those whose two nodes are both on it.
Eigen::Matrix2Xi outer_edges(const Model& model, const LatticeSurface& surface) {
  Eigen::Matrix3Xd points;
  Eigen::Matrix2Xi all;
  lattice_wireframe(model, model.rest_positions, points, all);
  std::vector<bool> on_surface(static_cast<std::size_t>(model.num_nodes()), false);
  for (int node : surface.nodes) on_surface[static_cast<std::size_t>(node)] = true;
  std::vector<Eigen::Index> kept;
  for (Eigen::Index s = 0; s < all.cols(); ++s) {
    if (on_surface[static_cast<std::size_t>(all(0, s))] && on_surface[static_cast<std::size_t>(all(1, s))])
      kept.push_back(s);
  }
  Eigen::Matrix2Xi edges(2, static_cast<Eigen::Index>(kept.size()));
  for (std::size_t k = 0; k < kept.size(); ++k) edges.col(static_cast<Eigen::Index>(k)) = all.col(kept[k]);
  return edges;
}

// Draws a surface coloured by a displacement field, each triangle flat (its own three vertices):
// smooth normals would round the beam's edges into shadows that look like deformation.
Status draw_field(Renderer& renderer, const Eigen::Matrix3Xd& vertices, const Eigen::Matrix3Xi& triangles,
                  const Eigen::VectorXd& magnitudes, double high) {
  const Eigen::Index corners = 3 * triangles.cols();
  Eigen::Matrix3Xd flat_vertices(3, corners);
  Eigen::VectorXd flat_magnitudes(corners);
  Eigen::Matrix3Xi flat_triangles(3, triangles.cols());
  for (Eigen::Index t = 0; t < triangles.cols(); ++t) {
    for (Eigen::Index k = 0; k < 3; ++k) {
      flat_vertices.col(3 * t + k) = vertices.col(triangles(k, t));
      flat_magnitudes[3 * t + k] = magnitudes[triangles(k, t)];
      flat_triangles(k, t) = static_cast<int>(3 * t + k);
    }
  }
  Eigen::Matrix3Xd normals;
  vertex_normals(flat_vertices, flat_triangles, normals);
  return renderer.draw_mesh_coloured(flat_vertices, normals, flat_triangles,
                                     ColourMap::viridis().colours(flat_magnitudes, 0.0, high));
}

}  // namespace

Camera cantilever_camera(const Eigen::AlignedBox3d& box, int width, int height) {
  Camera camera;
  camera.vertical_fov_degrees = kFieldOfViewDegrees;
  camera.target = box.center();
  const Eigen::Vector3d back = Eigen::Vector3d(0.35, -1.0, 0.55).normalized();  // from the target to the eye
  const Eigen::Vector3d right = camera.up.cross(back).normalized();
  const Eigen::Vector3d up = back.cross(right);
  const double tan_vertical = std::tan(0.5 * kFieldOfViewDegrees * M_PI / 180.0);
  const double tan_horizontal = tan_vertical * width / height;
  // the eye distance at which every corner of the box falls inside the used part of the image
  double distance = 0;
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3d corner = box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(k)) - camera.target;
    const double depth = corner.dot(back);  // towards the eye
    distance = std::max(distance, depth + std::abs(corner.dot(right)) / (kUsedWidth * tan_horizontal));
    distance = std::max(distance, depth + std::abs(corner.dot(up)) / (kUsedHeight * tan_vertical));
  }
  distance = std::max(distance, 1e-6);
  camera.position = camera.target + distance * back;
  camera.near = 0.01 * distance;
  camera.far = 10 * distance;
  return camera;
}

Result<CantileverPicture> draw_cantilever(const ExperimentResult& cantilever, const FemSolution* reference,
                                          const CantileverPictureOptions& options) {
  if (!(options.magnify > 0 && std::isfinite(options.magnify))) {
    return Status::error("magnify is " + std::to_string(options.magnify) + ": it must be a finite number > 0");
  }
  const int width = options.width;
  const int height = options.height;
  const Model& model = cantilever.model;
  const Eigen::Matrix3Xd positions =
      model.rest_positions + options.magnify * (cantilever.state.positions - model.rest_positions);
  const LatticeSurface surface = lattice_boundary_surface(model);
  const Eigen::Matrix3Xd lattice_vertices = surface_vertices(surface, positions);
  const Eigen::VectorXd lattice_moved =
      displacement_magnitudes(surface_vertices(surface, model.rest_positions), lattice_vertices) / options.magnify;

  Eigen::AlignedBox3d box;
  for (Eigen::Index v = 0; v < lattice_vertices.cols(); ++v) box.extend(lattice_vertices.col(v));
  double high = lattice_moved.size() > 0 ? lattice_moved.maxCoeff() : 0.0;
  Eigen::Matrix3Xd reference_vertices;
  Eigen::VectorXd reference_moved;
  if (reference != nullptr) {
    reference_vertices = reference->rest_positions + options.magnify * reference->displacements;
    reference_moved = reference->displacements.colwise().norm().transpose();
    for (Eigen::Index v = 0; v < reference_vertices.cols(); ++v) box.extend(reference_vertices.col(v));
    high = std::max(high, reference_moved.maxCoeff());
  }

  RenderSettings settings;
  settings.width = width;
  settings.height = height;
  settings.floor = false;
  Result<Renderer> renderer = Renderer::create(settings);
  if (!renderer) return renderer.status();
  CantileverPicture picture;
  picture.camera = cantilever_camera(box, width, height);
  if (Status begun = renderer->begin_frame(picture.camera); !begun) return begun;
  const Eigen::Matrix2Xi edges = outer_edges(model, surface);
  Status drawn;
  if (reference != nullptr) {
    drawn = draw_field(*renderer, reference_vertices, reference->surface, reference_moved, high);
    if (drawn) drawn = renderer->draw_lines(positions, edges, kWireOverReference, 1.5f, LineVisibility::kOverlay);
    if (drawn) drawn = renderer->draw_legend(ColourMap::viridis(), 0.0, high, "FEM displacement [m]");
  } else {
    drawn = draw_field(*renderer, lattice_vertices, surface.triangles, lattice_moved, high);
    if (drawn) drawn = renderer->draw_lines(positions, edges, kWireOverLattice, 1.0f);
    if (drawn) drawn = renderer->draw_legend(ColourMap::viridis(), 0.0, high, "displacement [m]");
  }
  if (!drawn) return drawn;
  Result<Image> image = renderer->end_frame();
  if (!image) return image.status();
  picture.image = std::move(image).value();
  return picture;
}

}  // namespace cubespring::app
