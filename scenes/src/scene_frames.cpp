// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "cubespring/scene/scene_frames.h"

#include <string>
#include <utility>

#include "cubespring/embedding.h"
#include "cubespring/render/colour_map.h"
#include "cubespring/render/wireframe.h"
#include "cubespring/scene/tool_motion.h"
#include "cubespring/strain.h"

namespace cubespring::scene {
namespace {

const Eigen::Vector3f kTissue(0.55f, 0.16f, 0.13f);  // liver red, for colour_map "none"
const Eigen::Vector3f kSteel(0.62f, 0.64f, 0.67f);   // data/probe.mtl's grey
const Eigen::Vector3f kLattice(0.08f, 0.08f, 0.08f);

}  // namespace

SceneFrames::SceneFrames(Renderer renderer, const Scene& scene) : renderer_(std::move(renderer)), spec_(scene.render) {}

Result<SceneFrames> SceneFrames::create(const Scene& scene) {
  RenderSettings settings;
  settings.width = scene.render.width;
  settings.height = scene.render.height;
  settings.supersampling = scene.render.supersampling;
  settings.lights = scene.render.lights;
  settings.ambient = static_cast<float>(scene.render.ambient);
  settings.floor = scene.table.enabled;
  settings.floor_height = scene.table.height;
  settings.floor_half_size = scene.table.half_size;
  Result<Renderer> renderer = Renderer::create(settings);
  if (!renderer) return Status::error("renderer: " + renderer.message());
  return SceneFrames(std::move(renderer).value(), scene);
}

void SceneFrames::carry_rest(const std::vector<int>& vertex_source, const Eigen::Matrix3Xd& vertices) {
  Eigen::Matrix3Xd rest = vertices;
  for (Eigen::Index v = 0; v < rest.cols(); ++v) {
    const int source =
        v < static_cast<Eigen::Index>(vertex_source.size()) ? vertex_source[static_cast<std::size_t>(v)] : -1;
    if (source >= 0 && source < rest_vertices_.cols()) rest.col(v) = rest_vertices_.col(source);
  }
  rest_vertices_ = std::move(rest);
}

Eigen::Matrix3Xd SceneFrames::organ_vertices(SceneWorld& world) {
  return organ_vertices(world, world.organ().state().positions);
}

Eigen::Matrix3Xd SceneFrames::organ_vertices(SceneWorld& world, const Eigen::Matrix3Xd& organ_positions) {
  Eigen::Matrix3Xd vertices;
  const bullet::SoftBody& organ = world.organ();
  embedded_positions(organ.model(), organ.embedding(), organ_positions, vertices);
  return vertices;
}

Status SceneFrames::draw_organ(SceneWorld& world, const Eigen::Matrix3Xd& organ_positions,
                               const Eigen::Matrix3Xd& vertices) {
  const Eigen::Matrix3Xi& triangles = world.organ().embedding().triangles;  // as cut, if it was
  vertex_normals(vertices, triangles, organ_normals_scratch_);
  const ColourMap map = ColourMap::viridis();
  if (spec_.colour_map == ColourMode::kDisplacement && rest_vertices_.cols() == vertices.cols()) {
    const Eigen::VectorXd moved = displacement_magnitudes(rest_vertices_, vertices);
    if (Status s = renderer_.draw_mesh_coloured(vertices, organ_normals_scratch_, triangles,
                                                map.colours(moved, 0.0, spec_.colour_range));
        !s) {
      return s;
    }
    // millimetres read better than metres on a 5x7 font
    return renderer_.draw_legend(map, 0.0, 1000.0 * spec_.colour_range, "DISPLACEMENT [MM]");
  }
  if (spec_.colour_map == ColourMode::kStrain) {
    const bullet::SoftBody& organ = world.organ();
    const Eigen::VectorXd node_strains =
        node_means_of_cells(organ.model(), cell_equivalent_strains(organ.model(), organ_positions));
    Eigen::VectorXd vertex_strains;
    embedded_values(organ.model(), organ.embedding(), node_strains, vertex_strains);
    if (Status s = renderer_.draw_mesh_coloured(vertices, organ_normals_scratch_, triangles,
                                                map.colours(vertex_strains, 0.0, spec_.strain_range));
        !s) {
      return s;
    }
    return renderer_.draw_legend(map, 0.0, 100.0 * spec_.strain_range, "STRAIN [%]");
  }
  return renderer_.draw_mesh(vertices, organ_normals_scratch_, triangles, kTissue);
}

Result<Image> SceneFrames::render(SceneWorld& world, double t) {
  return render(world, world.organ().state().positions, t);
}

Result<Image> SceneFrames::render(SceneWorld& world, const Eigen::Matrix3Xd& organ_positions, double t) {
  if (organ_positions.cols() != world.organ().model().num_nodes()) {
    return Status::error("SceneFrames::render: organ_positions has " + std::to_string(organ_positions.cols()) +
                         " columns; the organ has " + std::to_string(world.organ().model().num_nodes()) + " nodes");
  }
  if (Status s = renderer_.begin_frame(spec_.camera); !s) return s;

  if (Status s = draw_organ(world, organ_positions, organ_vertices(world, organ_positions)); !s) return s;

  if (spec_.wireframe) {
    Eigen::Matrix3Xd points;
    Eigen::Matrix2Xi segments;
    lattice_wireframe(world.organ().model(), organ_positions, points, segments);
    if (Status s = renderer_.draw_lines(points, segments, kLattice); !s) return s;
  }

  for (const SceneTool& tool : world.tools()) {
    const Eigen::Isometry3d pose = pose_at(tool.keyframes, t);
    const Eigen::Matrix3Xd placed = pose * tool.mesh.vertices;
    Eigen::Matrix3Xd normals;
    vertex_normals(placed, tool.mesh.triangles, normals);
    if (Status s = renderer_.draw_mesh(placed, normals, tool.mesh.triangles, kSteel); !s) return s;
  }
  return renderer_.end_frame();
}

}  // namespace cubespring::scene
