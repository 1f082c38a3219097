// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "cubespring/stable_time_step.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Eigenvalues>

#include "cubespring/stiffness.h"
#include "cubespring/stiffness_row_sums.h"
#include "solve/gershgorin.h"

namespace cubespring {
namespace {

// Largest eigenvalue of A = M^-1/2 K M^-1/2 by Lanczos without reorthogonalisation (only the
// extreme Ritz value is wanted, and it converges first). Every 10 steps, the top Ritz value and its
// residual |beta_k s_k|: stops when the residual is below 1e-4 of the value, and returns the value
// plus its residual, the largest an eigenvalue near it can be.
double lanczos_largest_eigenvalue(const SparseMatrix& stiffness, const Eigen::VectorXd& mass) {
  const Eigen::Index n = stiffness.rows();
  Eigen::VectorXd inverse_sqrt_mass(n);
  for (Eigen::Index i = 0; i < n; ++i) inverse_sqrt_mass[i] = 1.0 / std::sqrt(mass[i / 3]);
  const auto apply = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd {
    return inverse_sqrt_mass.cwiseProduct(stiffness * inverse_sqrt_mass.cwiseProduct(v));
  };

  std::mt19937 random(20070301);  // fixed seed: the same body gets the same step every run
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Eigen::VectorXd q = Eigen::VectorXd::NullaryExpr(n, [&] { return uniform(random); });
  q.normalize();
  Eigen::VectorXd previous = Eigen::VectorXd::Zero(n);
  std::vector<double> alphas, betas;
  double beta = 0.0;
  double estimate = 0.0;
  const int max_iterations = static_cast<int>(std::min<Eigen::Index>(n, 300));
  for (int k = 0; k < max_iterations; ++k) {
    Eigen::VectorXd w = apply(q) - beta * previous;
    const double alpha = q.dot(w);
    w -= alpha * q;
    beta = w.norm();
    alphas.push_back(alpha);
    betas.push_back(beta);
    const int size = k + 1;
    const bool exhausted = beta <= 1e-14 * std::abs(alpha);  // the Krylov space is invariant
    if (size % 10 == 0 || size == max_iterations || exhausted) {
      const Eigen::VectorXd diagonal = Eigen::Map<Eigen::VectorXd>(alphas.data(), size);
      const Eigen::VectorXd off_diagonal = Eigen::Map<Eigen::VectorXd>(betas.data(), size - 1);
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> tridiagonal;
      tridiagonal.computeFromTridiagonal(diagonal, off_diagonal, Eigen::ComputeEigenvectors);
      const double ritz = tridiagonal.eigenvalues()[size - 1];
      const double residual = std::abs(beta * tridiagonal.eigenvectors()(size - 1, size - 1));
      estimate = ritz + residual;
      if (residual <= 1e-4 * ritz || exhausted) break;
    }
    previous = q;
    q = w / beta;
  }
  return estimate;
}

}  // namespace

double gershgorin_bound(const Eigen::VectorXd& row_sums, const Eigen::VectorXd& inertia) {
  double bound = 0.0;
  for (Eigen::Index n = 0; n < row_sums.size(); ++n) bound = std::max(bound, row_sums[n] / inertia[n]);
  return bound;
}

double stable_step_for_frequency(const Model& model, double omega) {
  double beta = 0.0;
  for (const Material& material : model.materials) beta = std::max(beta, material.stiffness_damping);
  // with damping ratio zeta = beta omega / 2 the limit is 2 / omega (sqrt(1 + zeta^2) - zeta)
  const double zeta = 0.5 * beta * omega;
  return 2.0 / omega * (std::sqrt(1.0 + zeta * zeta) - zeta);
}

double max_frequency(const Model& model, FrequencyBound bound) {
  const SparseMatrix stiffness = rest_stiffness(model);
  const double gershgorin = gershgorin_bound(node_row_sums(stiffness), model.inertia());
  if (bound == FrequencyBound::kGershgorin) return std::sqrt(gershgorin);
  return std::sqrt(std::min(gershgorin, lanczos_largest_eigenvalue(stiffness, model.inertia())));
}

namespace {

// Gershgorin's bound is looser in a body's middle than at its corners and edges (by up to 35% on a
// block: its slack, not the tissue's), so no cell may count on more than the least step of a cell
// of its own tissue whose step reads that tissue alone (no node it reads, those of the cells
// sharing a node with it, touches another tissue). Cells near another tissue keep their own step.
void cap_at_pure_tissue(const Model& model, Eigen::VectorXd& steps) {
  const auto& cells = model.cell_nodes;
  std::vector<int> node_material(static_cast<std::size_t>(model.num_nodes()), -1);
  std::vector<char> node_mixed(static_cast<std::size_t>(model.num_nodes()), 0);
  for (int c = 0; c < model.num_cells(); ++c) {
    const int material = model.cell_material[static_cast<std::size_t>(c)];
    for (const int node : cells[static_cast<std::size_t>(c)]) {
      int& seen = node_material[static_cast<std::size_t>(node)];
      if (seen >= 0 && seen != material) node_mixed[static_cast<std::size_t>(node)] = 1;
      seen = material;
    }
  }
  // the nodes of a cell whose own nodes touch two tissues: a step that reads them reads both
  std::vector<char> near_mixed(static_cast<std::size_t>(model.num_nodes()), 0);
  for (int c = 0; c < model.num_cells(); ++c) {
    bool touches = false;
    for (const int node : cells[static_cast<std::size_t>(c)])
      touches = touches || node_mixed[static_cast<std::size_t>(node)];
    if (!touches) continue;
    for (const int node : cells[static_cast<std::size_t>(c)]) near_mixed[static_cast<std::size_t>(node)] = 1;
  }
  std::vector<double> least(model.materials.size(), std::numeric_limits<double>::infinity());
  for (int c = 0; c < model.num_cells(); ++c) {
    bool pure = true;
    for (const int node : cells[static_cast<std::size_t>(c)])
      pure = pure && !near_mixed[static_cast<std::size_t>(node)];
    double& bound = least[static_cast<std::size_t>(model.cell_material[static_cast<std::size_t>(c)])];
    if (pure) bound = std::min(bound, steps[c]);
  }
  for (int c = 0; c < model.num_cells(); ++c)
    steps[c] = std::min(steps[c], least[static_cast<std::size_t>(model.cell_material[static_cast<std::size_t>(c)])]);
}

}  // namespace

Eigen::VectorXd cell_stable_time_steps(const Model& model) {
  return cell_stable_time_steps(model, stiffness_row_sums(model));
}

Eigen::VectorXd cell_stable_time_steps(const Model& model, const Eigen::VectorXd& row_sums) {
  if (row_sums.size() != model.num_nodes()) {
    throw std::invalid_argument("cell_stable_time_steps: " + std::to_string(row_sums.size()) +
                                " row sums for a body of " + std::to_string(model.num_nodes()) + " nodes");
  }
  const auto& cells = model.cell_nodes;
  // the largest bound of each cell's nodes, then of the nodes of each cell's cells, then of the
  // cells around each cell (those that share a node with it)
  Eigen::VectorXd own(model.num_cells());
  for (int c = 0; c < model.num_cells(); ++c) {
    own[c] = 0.0;
    for (const int node : cells[static_cast<std::size_t>(c)])
      own[c] = std::max(own[c], row_sums[node] / model.mass[node]);
  }
  Eigen::VectorXd near_node = Eigen::VectorXd::Zero(model.num_nodes());
  for (int c = 0; c < model.num_cells(); ++c) {
    for (const int node : cells[static_cast<std::size_t>(c)]) near_node[node] = std::max(near_node[node], own[c]);
  }
  Eigen::VectorXd steps(model.num_cells());
  for (int c = 0; c < model.num_cells(); ++c) {
    double bound = 0.0;
    for (const int node : cells[static_cast<std::size_t>(c)]) bound = std::max(bound, near_node[node]);
    steps[c] = stable_step_for_frequency(model, std::sqrt(bound));
  }
  cap_at_pure_tissue(model, steps);
  return steps;
}

double max_stable_time_step(const Model& model, FrequencyBound bound) {
  return stable_step_for_frequency(model, max_frequency(model, bound));
}

}  // namespace cubespring
