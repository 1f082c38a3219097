// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "cubespring/validation/fem_comparison.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

namespace cubespring {

namespace {

constexpr double kMatchTolerance = 1e-3;  // of a cell: frd files keep 6 significant digits

// The lattice grid point a position sits on, if it sits on one.
std::optional<Eigen::Vector3i> grid_point(const Eigen::Vector3d& position, const Eigen::Vector3d& cell_size) {
  Eigen::Vector3i point;
  for (int axis = 0; axis < 3; ++axis) {
    const double g = position[axis] / cell_size[axis];
    const double nearest = std::round(g);
    if (!(std::abs(g - nearest) <= kMatchTolerance) || std::abs(nearest) > 1e9) return std::nullopt;
    point[axis] = static_cast<int>(nearest);
  }
  return point;
}

struct GridLess {
  bool operator()(const Eigen::Vector3i& a, const Eigen::Vector3i& b) const {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  }
};

}  // namespace

FemComparison compare_cantilever_with_fem(const ExperimentResult& cantilever, const FemSolution& reference) {
  const Model& model = cantilever.model;
  const Eigen::Vector3d h = cantilever.settings.cell_size;
  FemComparison comparison;
  comparison.lattice_nodes = model.num_nodes();
  if (cantilever.experiment != Experiment::kCantilever) return comparison;

  std::map<Eigen::Vector3i, int, GridLess> reference_at;
  for (Eigen::Index c = 0; c < reference.rest_positions.cols(); ++c) {
    if (auto point = grid_point(reference.rest_positions.col(c), h)) reference_at.emplace(*point, static_cast<int>(c));
  }
  const int tip_layer = cantilever.settings.cells.x();
  std::vector<int> match(static_cast<std::size_t>(model.num_nodes()), -1);
  int tip_nodes = 0;
  int tip_matched = 0;
  double tip_sum = 0;
  for (int n = 0; n < model.num_nodes(); ++n) {
    const std::optional<Eigen::Vector3i> point = grid_point(model.rest_positions.col(n), h);
    const auto found = point ? reference_at.find(*point) : reference_at.end();
    const bool on_tip = point && point->x() == tip_layer;
    tip_nodes += on_tip ? 1 : 0;
    if (found == reference_at.end()) continue;
    match[static_cast<std::size_t>(n)] = found->second;
    ++comparison.matched_nodes;
    if (on_tip) {
      ++tip_matched;
      tip_sum += reference.displacements(2, found->second);
    }
  }
  if (tip_nodes == 0 || tip_matched != tip_nodes || !cantilever.tip_deflection) return comparison;
  const double tip = tip_sum / tip_nodes;
  comparison.reference_tip_deflection = tip;
  comparison.tip_error = *cantilever.tip_deflection / tip - 1.0;
  double sum = 0;
  double largest = 0;
  for (int n = 0; n < model.num_nodes(); ++n) {
    const int r = match[static_cast<std::size_t>(n)];
    if (r < 0) continue;
    const Eigen::Vector3d u = cantilever.state.positions.col(n) - model.rest_positions.col(n);
    const double error = (u - reference.displacements.col(r)).norm() / std::abs(tip);
    sum += error;
    largest = std::max(largest, error);
  }
  comparison.mean_nodal_error = sum / comparison.matched_nodes;
  comparison.max_nodal_error = largest;
  return comparison;
}

}  // namespace cubespring
