// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Cells taken out of a soft body between world steps (docs/cutting.md): the body made again of
// its remaining cells, its visual surface cut from the one it started with.
#include <array>
#include <map>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include "cubespring/bullet/soft_body.h"
#include "cubespring/cell_removal.h"
#include "cubespring/cut_surface.h"

namespace cubespring::bullet {
namespace {

// The grid cells whose part of the visual surface the cuts take away: every removed cell, and the
// empty ones around them, where the surface hangs from the lattice beyond its cells (voxelize.h)
// and may have hung from a removed cell; left, it would hang a cell or more from the nearest one
// left (a corner of a cap a cell above the lattice's top, extrapolated twice the cell's height).
std::vector<Eigen::Vector3i> surface_cut_cells(const Model& remaining, const std::vector<Eigen::Vector3i>& removed) {
  std::set<std::array<int, 3>> kept;
  for (const Eigen::Vector3i& g : remaining.cell_grid_index) kept.insert({g.x(), g.y(), g.z()});
  std::set<std::array<int, 3>> cut;
  for (const Eigen::Vector3i& g : removed) {
    for (int i = -1; i <= 1; ++i) {
      for (int j = -1; j <= 1; ++j) {
        for (int k = -1; k <= 1; ++k) {
          const std::array<int, 3> around{g.x() + i, g.y() + j, g.z() + k};
          if (kept.count(around) == 0) cut.insert(around);
        }
      }
    }
  }
  std::vector<Eigen::Vector3i> cells;
  for (const std::array<int, 3>& g : cut) cells.emplace_back(g[0], g[1], g[2]);
  return cells;
}

}  // namespace

Result<SoftBody::Cut> SoftBody::remove_cells(const std::vector<int>& cells) {
  Result<CellRemoval> removal = cubespring::remove_cells(model_, state_, constraints_, cells);
  if (!removal) return Status::error("remove_cells: " + removal.message());
  Cut cut;
  cut.removed_cells = removal->removed_cells;
  cut.removed_mass = removal->removed_mass;
  cut.removed_momentum = removal->removed_momentum;
  cut.pieces = removal->pieces;
  cut.new_node = removal->new_node;
  cut.new_cell = removal->new_cell;
  Loads loads = loads_;
  loads.nodal_forces = carry_node_columns(*removal, loads_.nodal_forces);
  SoftBodySettings settings = settings_;
  settings.lattice = lattice_desc(removal->model);
  std::vector<Eigen::Vector3i> removed = removed_cells_;
  for (int c = 0; c < model_.num_cells(); ++c) {
    if (cut.new_cell[static_cast<std::size_t>(c)] < 0)
      removed.push_back(model_.cell_grid_index[static_cast<std::size_t>(c)]);
  }
  std::vector<std::array<long long, 4>> visual_keys;
  if (uncut_visual_mesh_) {  // the surface it started with, cut by every cell gone, and capped there
    CutSurface surface =
        cut_surface(*uncut_visual_mesh_, model_.origin, model_.cell_size, surface_cut_cells(removal->model, removed));
    // which vertex before the cut each one is: keys name the same points in every cut
    std::map<std::array<long long, 4>, int> before;
    for (int v = 0; v < embedding_.num_vertices(); ++v) {
      before[visual_keys_.empty() ? std::array<long long, 4>{0, v, 0, 0} : visual_keys_[static_cast<std::size_t>(v)]] =
          v;
    }
    for (const std::array<long long, 4>& key : surface.vertex_keys) {
      const auto found = before.find(key);
      cut.visual_vertex_source.push_back(found == before.end() ? -1 : found->second);
    }
    cut.cap_triangles = surface.cap_triangles;
    visual_keys = std::move(surface.vertex_keys);
    settings.visual_mesh = std::move(surface.mesh);
  }
  Result<std::unique_ptr<SoftBody>> rebuilt = assemble(settings, std::move(removal->model));
  if (!rebuilt) return Status::error("remove_cells: " + rebuilt.message());
  SoftBody& after = **rebuilt;
  after.state_ = std::move(removal->state);
  after.constraints_ = std::move(removal->constraints);
  after.loads_ = std::move(loads);
  after.step_settings_ = step_settings_;  // threads and the integrator as the user left them
  after.times_ = times_;
  after.last_report_ = last_report_;
  after.stop_message_ = stop_message_;
  after.uncut_visual_mesh_ = std::move(uncut_visual_mesh_);
  after.removed_cells_ = std::move(removed);
  after.visual_keys_ = std::move(visual_keys);
  for (const std::optional<Anchor>& anchor : anchors_) {
    std::optional<Anchor> carried;
    if (anchor) {
      Anchor kept{anchor->body, {}, Eigen::Matrix3Xd(3, static_cast<Eigen::Index>(anchor->nodes.size()))};
      for (std::size_t i = 0; i < anchor->nodes.size(); ++i) {
        const int node = cut.new_node[static_cast<std::size_t>(anchor->nodes[i])];
        if (node < 0) continue;
        kept.local.col(static_cast<Eigen::Index>(kept.nodes.size())) = anchor->local.col(static_cast<Eigen::Index>(i));
        kept.nodes.push_back(node);
      }
      kept.local.conservativeResize(3, static_cast<Eigen::Index>(kept.nodes.size()));
      if (!kept.nodes.empty()) carried = std::move(kept);
    }
    after.anchors_.push_back(std::move(carried));
  }
  after.update_surface();
  *this = std::move(after);
  return cut;
}

}  // namespace cubespring::bullet
