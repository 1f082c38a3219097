// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "cubespring/mass_scaling.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

#include "cubespring/stiffness_row_sums.h"
#include "solve/gershgorin.h"

namespace cubespring {
namespace {

// The lowest bound lambda [1/s^2] whose inertia, sum over nodes of max(0, r_n / lambda - m_n),
// is at most `budget` [kg]. With the nodes in falling order of r_n / m_n, a lambda between the
// k-th and the next node's bound needs (sum of the first k r) / lambda - (sum of their m): the
// first interval where the budget's lambda falls in is the answer.
double lowest_affordable_bound(const Eigen::VectorXd& row_sums, const Eigen::VectorXd& mass, double budget) {
  std::vector<int> order(static_cast<std::size_t>(mass.size()));
  std::iota(order.begin(), order.end(), 0);
  const Eigen::VectorXd bounds = row_sums.cwiseQuotient(mass);  // divided once, not in each comparison
  const auto bound = [&](int n) { return bounds[n]; };
  std::sort(order.begin(), order.end(), [&](int a, int b) { return bound(a) > bound(b); });
  double sum_r = 0.0, sum_m = 0.0;
  for (std::size_t k = 0; k < order.size(); ++k) {
    sum_r += row_sums[order[k]];
    sum_m += mass[order[k]];
    const double lambda = sum_r / (budget + sum_m);  // where the first k+1 nodes spend the budget
    const double next = k + 1 < order.size() ? bound(order[k + 1]) : 0.0;
    if (lambda >= next) return lambda;
  }
  return 0.0;  // unreachable for a positive budget: the last interval reaches 0
}

}  // namespace

MassScaling add_mass_for_time_step(Model& model, double max_added_fraction) {
  return add_mass_for_time_step(model, max_added_fraction, stiffness_row_sums(model));
}

MassScaling add_mass_for_time_step(Model& model, double max_added_fraction, const Eigen::VectorXd& row_sums) {
  if (!(max_added_fraction >= 0.0 && max_added_fraction <= 1.0)) {
    throw std::invalid_argument("add_mass_for_time_step: the added mass fraction " +
                                std::to_string(max_added_fraction) + " must be in [0, 1]");
  }
  if (row_sums.size() != model.num_nodes()) {
    throw std::invalid_argument("add_mass_for_time_step: " + std::to_string(row_sums.size()) +
                                " row sums for a body of " + std::to_string(model.num_nodes()) + " nodes");
  }
  model.inertial_mass.resize(0);
  // one set of row sums gives the bound before, the target and the bound after
  // (max_stable_time_step()'s Gershgorin bound)
  const auto stable_step = [&](const Eigen::VectorXd& inertia) {
    return stable_step_for_frequency(model, std::sqrt(gershgorin_bound(row_sums, inertia)));
  };
  MassScaling scaling;
  scaling.time_step_before = stable_step(model.mass);
  scaling.time_step_after = scaling.time_step_before;
  if (max_added_fraction == 0.0 || model.num_nodes() == 0) return scaling;

  const double lambda = lowest_affordable_bound(row_sums, model.mass, max_added_fraction * model.total_mass());
  Eigen::VectorXd inertia = model.mass;
  for (int n = 0; n < model.num_nodes(); ++n) {
    const double needed = row_sums[n] / lambda;
    if (needed > model.mass[n]) {
      inertia[n] = needed;
      scaling.added_mass += needed - model.mass[n];
      ++scaling.nodes;
    }
  }
  if (scaling.nodes == 0) return scaling;
  model.inertial_mass = std::move(inertia);
  scaling.added_fraction = scaling.added_mass / model.total_mass();
  scaling.time_step_after = stable_step(model.inertial_mass);
  return scaling;
}

}  // namespace cubespring
