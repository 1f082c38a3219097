// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// A soft body's cells taken out, or the faces between them split, between world steps
// (docs/cutting.md): the body made again of its remaining cells, its visual surface cut from the
// one it started with.
#include <array>
#include <cstdint>
#include <functional>
#include <future>
#include <map>
#include <optional>
#include <set>
#include <unordered_set>
#include <utility>
#include <vector>

#include "cubespring/bullet/soft_body.h"
#include "cubespring/cell_removal.h"
#include "cubespring/cut_surface.h"
#include "cubespring/face_split.h"
#include "cubespring/stiffness_row_sums.h"

namespace cubespring::bullet {
namespace {

using PointKey = std::array<long long, 4>;  // CutSurface::vertex_keys

// The grid cells whose part of the visual surface the cuts take away: every removed cell, and the
// empty ones around them, where the surface hangs from the lattice beyond its cells (voxelize.h)
// and may have hung from a removed cell; left, it would hang a cell or more from the nearest one
// left (a corner of a cap a cell above the lattice's top, extrapolated twice the cell's height).
// A grid index as one number (21 bits an axis, as the core's keys).
std::int64_t cell_key(int x, int y, int z) {
  constexpr std::int64_t kOffset = std::int64_t{1} << 20;
  return ((x + kOffset) << 42) | ((y + kOffset) << 21) | (z + kOffset);
}

std::vector<Eigen::Vector3i> surface_cut_cells(const std::unordered_set<std::int64_t>& kept,
                                               const std::vector<Eigen::Vector3i>& removed) {
  std::set<std::array<int, 3>> cut;
  for (const Eigen::Vector3i& g : removed) {
    for (int i = -1; i <= 1; ++i) {
      for (int j = -1; j <= 1; ++j) {
        for (int k = -1; k <= 1; ++k) {
          const std::array<int, 3> around{g.x() + i, g.y() + j, g.z() + k};
          if (kept.count(cell_key(around[0], around[1], around[2])) == 0) cut.insert(around);
        }
      }
    }
  }
  std::vector<Eigen::Vector3i> cells;
  for (const std::array<int, 3>& g : cut) cells.emplace_back(g[0], g[1], g[2]);
  return cells;
}

// The visual mesh after a cut, and which vertex before it each of its vertices is (-1: new).
struct VisualCut {
  CutSurface surface;
  std::vector<int> vertex_source;
};

// The mesh the user gave, cut by every cell gone (`removed`, grid indices) and capped there:
// cutting the surface as cut before would cut caps lying on the grid's planes again
// (cut_surface.h). `keys_before` name the vertices of the mesh as cut before (empty before the
// first cut: the user's vertices, in order, `vertices_before` of them).
VisualCut cut_visual_mesh(const TriangleMesh& uncut, const Model& model, const std::vector<char>& removing,
                          const std::vector<Eigen::Vector3i>& removed, const std::vector<PointKey>& keys_before,
                          int vertices_before) {
  std::unordered_set<std::int64_t> kept;
  kept.reserve(static_cast<std::size_t>(model.num_cells()));
  for (int c = 0; c < model.num_cells(); ++c) {
    const Eigen::Vector3i& g = model.cell_grid_index[static_cast<std::size_t>(c)];
    if (!removing[static_cast<std::size_t>(c)]) kept.insert(cell_key(g.x(), g.y(), g.z()));
  }
  VisualCut cut;
  cut.surface = cut_surface(uncut, model.origin, model.cell_size, surface_cut_cells(kept, removed));
  // keys name the same points in every cut: the user's vertices (kind 0) by their number, the
  // cuts' points by the whole key
  std::vector<int> before_input(static_cast<std::size_t>(uncut.num_vertices()), -1);
  std::map<PointKey, int> before_cut;
  for (int v = 0; v < vertices_before; ++v) {
    const PointKey key = keys_before.empty() ? PointKey{0, v, 0, 0} : keys_before[static_cast<std::size_t>(v)];
    if (key[0] == 0) {
      before_input[static_cast<std::size_t>(key[1])] = v;
    } else {
      before_cut[key] = v;
    }
  }
  for (const PointKey& key : cut.surface.vertex_keys) {
    if (key[0] == 0) {
      cut.vertex_source.push_back(before_input[static_cast<std::size_t>(key[1])]);
      continue;
    }
    const auto found = before_cut.find(key);
    cut.vertex_source.push_back(found == before_cut.end() ? -1 : found->second);
  }
  return cut;
}

}  // namespace

Result<SoftBody::Cut> SoftBody::remove_cells(const std::vector<int>& cells) {
  // the visual surface is cut on a second thread while the model is rebuilt: neither reads what
  // the other makes (cells out of range are left to the core's removal to report)
  std::vector<char> removing(static_cast<std::size_t>(model_.num_cells()), 0);
  bool in_range = true;
  for (const int c : cells) {
    in_range = in_range && c >= 0 && c < model_.num_cells();
    if (in_range) removing[static_cast<std::size_t>(c)] = 1;
  }
  std::vector<Eigen::Vector3i> removed = removed_cells_;
  for (int c = 0; in_range && c < model_.num_cells(); ++c) {
    if (removing[static_cast<std::size_t>(c)]) removed.push_back(model_.cell_grid_index[static_cast<std::size_t>(c)]);
  }
  std::future<VisualCut> visual;
  if (uncut_visual_mesh_ && in_range) {
    visual = std::async(std::launch::async, cut_visual_mesh, std::cref(*uncut_visual_mesh_), std::cref(model_),
                        std::cref(removing), std::cref(removed), std::cref(visual_keys_), embedding_.num_vertices());
  }
  Result<CellRemoval> removal = cubespring::remove_cells(model_, state_, constraints_, cells);
  if (!removal) return Status::error("remove_cells: " + removal.message());  // (the future waits)
  // the stable steps read the stiffness's row sums: those the cut changed are summed again
  std::optional<Eigen::VectorXd> row_sums;
  if (row_sums_.size() == model_.num_nodes()) row_sums = stiffness_row_sums_after(model_, row_sums_, *removal);

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
  std::vector<PointKey> visual_keys;
  if (visual.valid()) {
    VisualCut surface = visual.get();
    cut.visual_vertex_source = std::move(surface.vertex_source);
    cut.cap_triangles = surface.surface.cap_triangles;
    visual_keys = std::move(surface.surface.vertex_keys);
    settings.visual_mesh = std::move(surface.surface.mesh);
  }
  Result<std::unique_ptr<SoftBody>> rebuilt = assemble(settings, std::move(removal->model), std::move(row_sums));
  if (!rebuilt) return Status::error("remove_cells: " + rebuilt.message());
  (*rebuilt)->removed_cells_ = std::move(removed);
  (*rebuilt)->visual_keys_ = std::move(visual_keys);
  take_over(std::move(*rebuilt), std::move(removal->state), std::move(removal->constraints), std::move(loads),
            removal->source_node);
  return cut;
}

Result<SoftBody::Split> SoftBody::split_faces(const std::vector<CellFace>& faces) {
  if (uncut_visual_mesh_) {
    return Status::error(
        "split_faces: this body has a visual mesh, and a visual mesh does not follow a split yet "
        "(docs/cutting.md, \"Not yet\"); a body whose surface is its lattice's can be split");
  }
  Result<FaceSplit> split = cubespring::split_faces(model_, state_, constraints_, faces);
  if (!split) return Status::error("split_faces: " + split.message());
  Split done;
  done.faces_split = split->faces_split;
  done.nodes_added = split->nodes_added;
  done.pieces = split->pieces;
  done.source_node = split->source_node;
  Loads loads = loads_;
  loads.nodal_forces = carry_node_forces(*split, loads_.nodal_forces);
  SoftBodySettings settings = settings_;
  settings.lattice = lattice_desc(split->model);
  // the nodes given copies have new rows: the stable steps sum the stiffness again
  Result<std::unique_ptr<SoftBody>> rebuilt = assemble(settings, std::move(split->model));
  if (!rebuilt) return Status::error("split_faces: " + rebuilt.message());
  (*rebuilt)->removed_cells_ = removed_cells_;
  (*rebuilt)->visual_keys_ = visual_keys_;
  take_over(std::move(*rebuilt), std::move(split->state), std::move(split->constraints), std::move(loads),
            done.source_node);
  return done;
}

void SoftBody::take_over(std::unique_ptr<SoftBody> rebuilt, State state, Constraints constraints, Loads loads,
                         const std::vector<int>& source_node) {
  SoftBody& after = *rebuilt;
  after.state_ = std::move(state);
  after.constraints_ = std::move(constraints);
  after.loads_ = std::move(loads);
  after.step_settings_ = step_settings_;  // threads and the integrator as the user left them
  after.times_ = times_;
  after.last_report_ = last_report_;
  after.stop_message_ = stop_message_;
  after.uncut_visual_mesh_ = std::move(uncut_visual_mesh_);
  std::vector<std::vector<int>> copies(static_cast<std::size_t>(model_.num_nodes()));  // of each old node
  for (std::size_t n = 0; n < source_node.size(); ++n) {
    copies[static_cast<std::size_t>(source_node[n])].push_back(static_cast<int>(n));
  }
  for (const std::optional<Anchor>& anchor : anchors_) {
    std::optional<Anchor> carried;
    if (anchor) {
      Anchor kept{anchor->body, {}, Eigen::Matrix3Xd(3, 0)};
      std::vector<Eigen::Vector3d> local;
      for (std::size_t i = 0; i < anchor->nodes.size(); ++i) {
        for (const int node : copies[static_cast<std::size_t>(anchor->nodes[i])]) {
          kept.nodes.push_back(node);
          local.push_back(anchor->local.col(static_cast<Eigen::Index>(i)));
        }
      }
      kept.local.resize(3, static_cast<Eigen::Index>(local.size()));
      for (std::size_t i = 0; i < local.size(); ++i) kept.local.col(static_cast<Eigen::Index>(i)) = local[i];
      if (!kept.nodes.empty()) carried = std::move(kept);
    }
    after.anchors_.push_back(std::move(carried));
  }
  after.update_surface();
  *this = std::move(after);
}

}  // namespace cubespring::bullet
