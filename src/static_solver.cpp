// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "cubespring/static_solver.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>

#include <Eigen/SparseCholesky>

#include "cubespring/stiffness.h"
#include "input_checks.h"

namespace cubespring {
namespace {

// A tiny diagonal shift keeps the factorisation of a free body's singular stiffness defined;
// iterative refinement then removes its effect on the solution's range component.
constexpr double kShiftFraction = 1e-9;
constexpr int kRefinementSteps = 4;
// Newton steps shorter than this fraction of a cell mean the iteration has converged to round-off.
constexpr double kStagnantStep = 1e-13;

struct Problem {
  const Model& model;
  const Constraints& constraints;
  const Loads& full_loads;
  std::vector<std::uint8_t> driven;  // per degree of freedom
};

Loads scaled_loads(const Loads& loads, double factor) {
  Loads scaled;
  scaled.gravity = factor * loads.gravity;
  if (loads.nodal_forces.size() > 0) scaled.nodal_forces = factor * loads.nodal_forces;
  return scaled;
}

// Residual force on the free degrees of freedom (zero on driven ones).
Eigen::VectorXd residual(const Problem& problem, const Loads& loads, const Eigen::Matrix3Xd& x,
                         ForceWorkspace& ws) {
  State state;
  state.positions = x;
  state.velocities.setZero(3, x.cols());
  Eigen::Matrix3Xd forces;
  compute_forces(problem.model, state, loads, ForceOptions{false, 1}, ws, forces);
  Eigen::VectorXd r = Eigen::Map<const Eigen::VectorXd>(forces.data(), forces.size());
  for (Eigen::Index i = 0; i < r.size(); ++i) {
    if (problem.driven[i]) r[i] = 0.0;
  }
  return r;
}

// Newton from x at fixed loads; returns false when it does not converge.
bool newton(const Problem& problem, const Loads& loads, double reference_force, const StaticSettings& settings,
            StiffnessAssembler& assembler, Eigen::Matrix3Xd& x, StaticReport& report) {
  ForceWorkspace ws;
  SparseMatrix stiffness;
  Eigen::VectorXd r = residual(problem, loads, x, ws);
  const double tolerance = settings.tolerance * reference_force;
  for (int iteration = 0; iteration < settings.max_newton_iterations; ++iteration) {
    report.residual = r.norm();
    if (report.residual <= tolerance) return true;
    ++report.newton_iterations;

    // K dx = r on free dofs, identity rows on driven ones
    assembler.assemble(problem.model, x, StiffnessKind::kExact, 1.0, 0.0, stiffness);
    Eigen::SparseMatrix<double> k = stiffness;
    double mean_diagonal = k.diagonal().cwiseAbs().mean();
    for (int col = 0; col < k.outerSize(); ++col) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(k, col); it; ++it) {
        if (problem.driven[it.row()] || problem.driven[it.col()]) it.valueRef() = it.row() == it.col() ? 1.0 : 0.0;
      }
    }
    Eigen::SparseMatrix<double> shifted = k;
    for (int i = 0; i < shifted.rows(); ++i) shifted.coeffRef(i, i) += kShiftFraction * mean_diagonal;
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(shifted);
    if (solver.info() != Eigen::Success) return false;
    Eigen::VectorXd dx = solver.solve(r);
    for (int step = 0; step < kRefinementSteps; ++step) dx += solver.solve(r - k * dx);
    if (!dx.allFinite()) return false;

    // energy line search along dx (falls back to shorter steps when K is indefinite)
    const double energy = potential_energy(problem.model, loads, x);
    const double slope = -r.dot(dx);
    double alpha = 1.0;
    Eigen::Matrix3Xd trial;
    for (; alpha > 1e-6; alpha *= 0.5) {
      trial = x + alpha * Eigen::Map<const Eigen::Matrix3Xd>(dx.data(), 3, x.cols());
      const double trial_energy = potential_energy(problem.model, loads, trial);
      if (std::isfinite(trial_energy) && (slope >= 0.0 || trial_energy <= energy + 1e-4 * alpha * slope ||
                                          std::abs(trial_energy - energy) <= 1e-14 * std::abs(energy))) {
        break;
      }
    }
    x = trial;
    r = residual(problem, loads, x, ws);
    // a full Newton step below round-off of the positions: the residual is at its floor
    if (dx.cwiseAbs().maxCoeff() <= kStagnantStep * problem.model.cell_size.maxCoeff()) {
      report.residual = r.norm();
      return true;
    }
  }
  report.residual = r.norm();
  return report.residual <= tolerance;
}

}  // namespace

StaticReport solve_static(const Model& model, const Constraints& constraints, const Loads& loads,
                          const StaticSettings& settings, State& state) {
  StaticReport report;
  std::string invalid = node_columns_error(model, loads.nodal_forces, "loads.nodal_forces", true);
  if (invalid.empty()) invalid = constraints_error(model, constraints);
  if (invalid.empty() && !loads.gravity.allFinite()) {
    std::ostringstream message;
    message << "loads.gravity = (" << loads.gravity.transpose() << ") m/s^2 is not finite";
    invalid = message.str();
  }
  if (invalid.empty() && !(settings.tolerance > 0.0 && std::isfinite(settings.tolerance))) {
    invalid = "tolerance = " + std::to_string(settings.tolerance) + ": must be a finite number > 0";
  }
  if (invalid.empty() && (settings.initial_load_steps < 1 || settings.max_load_steps < 1 ||
                          settings.max_newton_iterations < 1)) {
    invalid = "initial_load_steps, max_load_steps and max_newton_iterations must each be >= 1 (got " +
              std::to_string(settings.initial_load_steps) + ", " + std::to_string(settings.max_load_steps) + ", " +
              std::to_string(settings.max_newton_iterations) + ")";
  }
  if (!invalid.empty()) {  // nothing read, the state unchanged
    report.message = invalid;
    return report;
  }
  const int num_nodes = model.num_nodes();
  Problem problem{model, constraints, loads, std::vector<std::uint8_t>(3 * num_nodes, 0)};
  Eigen::Matrix3Xd target = model.rest_positions;
  for (int n = 0; n < constraints.num_nodes(); ++n) {
    for (int a = 0; a < 3; ++a) {
      if (((constraints.driven_axes(n) >> a) & 1) == 0) continue;
      problem.driven[3 * n + a] = 1;
      target(a, n) = constraints.target(n)[a];
    }
  }
  // the force scale that residuals are measured against
  double reference_force = (loads.gravity.norm() * model.mass).norm();
  if (loads.nodal_forces.size() > 0) reference_force = std::max(reference_force, loads.nodal_forces.norm());
  const double driven_motion = (target - model.rest_positions).norm();
  if (driven_motion > 0.0) {
    const double stiffest = *std::max_element(model.spring_stiffness.begin(), model.spring_stiffness.end());
    reference_force = std::max(reference_force, stiffest * driven_motion);
  }
  // residuals cannot fall below the round-off of the largest spring forces
  const double stiffest = *std::max_element(model.spring_stiffness.begin(), model.spring_stiffness.end());
  const double round_off = 1e-13 * stiffest * model.cell_size.maxCoeff() * std::sqrt(num_nodes);
  reference_force = std::max(reference_force, round_off / settings.tolerance);

  std::unique_ptr<StiffnessAssembler> assembler;
  try {
    assembler = std::make_unique<StiffnessAssembler>(model);
  } catch (const std::length_error& too_large) {
    report.message = too_large.what();
    return report;
  }
  Eigen::Matrix3Xd x = model.rest_positions;
  Eigen::Matrix3Xd start_driven = model.rest_positions;
  double done = 0.0;
  double increment = 1.0 / settings.initial_load_steps;
  const double smallest = 1.0 / settings.max_load_steps;
  while (done < 1.0) {
    const double next = std::min(1.0, done + increment);
    Eigen::Matrix3Xd trial = x;
    for (int i = 0; i < 3 * num_nodes; ++i) {
      if (problem.driven[i]) trial(i) = start_driven(i) + next * (target(i) - start_driven(i));
    }
    if (newton(problem, scaled_loads(loads, next), reference_force, settings, *assembler, trial, report)) {
      x = trial;
      done = next;
      ++report.load_steps;
      increment *= 1.5;  // grow again after a success
      continue;
    }
    if (increment <= smallest * 1.000001) {
      std::ostringstream message;
      message << "static solve did not converge at load fraction " << next << " (residual " << report.residual
              << " N after " << report.newton_iterations << " Newton iterations, smallest increment "
              << increment << ")";
      report.message = message.str();
      state.positions = x;
      state.velocities.setZero(3, num_nodes);
      return report;
    }
    increment = std::max(smallest, 0.5 * increment);
  }
  report.converged = true;
  state.positions = x;
  state.velocities.setZero(3, num_nodes);
  return report;
}

}  // namespace cubespring
