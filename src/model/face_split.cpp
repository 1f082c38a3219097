// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "cubespring/face_split.h"

#include <array>
#include <set>
#include <string>
#include <utility>

#include "model/topology_change.h"

namespace cubespring {
Result<FaceSplit> split_faces(const Model& model, const State& state, const Constraints& constraints,
                              const std::vector<CellFace>& faces) {
  if (Status sizes = check_body_sizes(model, state, constraints); !sizes) return sizes;
  // the body's faces and the new ones, each once (build_model() checks that both cells exist)
  LatticeDesc desc = lattice_desc(model);
  std::set<std::pair<std::array<int, 3>, int>> listed;
  for (const CellFace& face : desc.split_faces)
    listed.insert({{face.cell.x(), face.cell.y(), face.cell.z()}, face.axis});
  FaceSplit split;
  for (const CellFace& face : faces) {
    if (listed.insert({{face.cell.x(), face.cell.y(), face.cell.z()}, face.axis}).second) {
      desc.split_faces.push_back(face);
      ++split.faces_split;
    }
  }
  Result<Model> rebuilt = build_model(desc);
  if (!rebuilt) return Status::error("splitting faces: " + rebuilt.message());
  split.model = std::move(rebuilt).value();
  const Model& after = split.model;

  // the same cells in the same order (the same grid keys): a copy is its cell's corner
  split.source_node.assign(static_cast<std::size_t>(after.num_nodes()), -1);
  for (int c = 0; c < after.num_cells(); ++c) {
    for (std::size_t k = 0; k < kCornersPerCell; ++k) {
      split.source_node[static_cast<std::size_t>(after.cell_nodes[static_cast<std::size_t>(c)][k])] =
          model.cell_nodes[static_cast<std::size_t>(c)][k];
    }
  }
  split.state.positions.resize(3, after.num_nodes());
  split.state.velocities.resize(3, after.num_nodes());
  split.state.time = state.time;
  for (int n = 0; n < after.num_nodes(); ++n) {
    const int from = split.source_node[static_cast<std::size_t>(n)];
    split.state.positions.col(n) = state.positions.col(from);
    split.state.velocities.col(n) = state.velocities.col(from);
  }
  Result<Constraints> carried = constraints.gathered(split.source_node);
  if (!carried) return carried.status();
  split.constraints = std::move(carried).value();
  split.nodes_added = after.num_nodes() - model.num_nodes();
  split.pieces = count_pieces(after);
  return split;
}

Eigen::Matrix3Xd carry_node_forces(const FaceSplit& split, const Eigen::Matrix3Xd& forces) {
  if (forces.cols() == 0) return forces;
  const Model& after = split.model;
  // each source's mass, summed over its copies
  Eigen::VectorXd source_mass = Eigen::VectorXd::Zero(forces.cols());
  for (int n = 0; n < after.num_nodes(); ++n) {
    const int from = split.source_node[static_cast<std::size_t>(n)];
    if (from < forces.cols()) source_mass[from] += after.mass[n];
  }
  Eigen::Matrix3Xd carried = Eigen::Matrix3Xd::Zero(3, after.num_nodes());
  for (int n = 0; n < after.num_nodes(); ++n) {
    const int from = split.source_node[static_cast<std::size_t>(n)];
    if (from < forces.cols() && source_mass[from] > 0.0)
      carried.col(n) = after.mass[n] / source_mass[from] * forces.col(from);
  }
  return carried;
}

}  // namespace cubespring
