// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "cubespring/static_solver.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>

#include <Eigen/Eigenvalues>

#include "cubespring/stiffness.h"
#include "forces/input_checks.h"
#include "solve/grid_ldlt.h"

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
  bool held = false;                 // the driven dofs hold every rigid motion (holds_the_body)
  double load_done = 0.0;            // the load fraction the increments done have reached
};

Loads scaled_loads(const Loads& loads, double factor) {
  Loads scaled;
  scaled.gravity = factor * loads.gravity;
  if (loads.nodal_forces.size() > 0) scaled.nodal_forces = factor * loads.nodal_forces;
  return scaled;
}

// Residual force on the free degrees of freedom (zero on driven ones).
Eigen::VectorXd residual(const Problem& problem, const Loads& loads, const Eigen::Matrix3Xd& x, ForceWorkspace& ws) {
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

// An equilibrium is unstable when the stiffness has an eigenvalue below -kNegativeCurvature times
// its mean diagonal: then, and only then (Sylvester's law of inertia), K + kNegativeCurvature
// mean I has a negative LDL^T pivot. Smaller negative curvatures are taken as neutral: near-zero-
// energy modes of the lattice showed up to about 1e-4 of the mean diagonal under small loads (a
// block of the paper's cells on a frictionless floor, nu = 0).
constexpr double kNegativeCurvature = 1e-3;

// The exact stiffness at x with identity rows and columns on the driven degrees of freedom.
Eigen::SparseMatrix<double> free_stiffness(const Problem& problem, StiffnessAssembler& assembler,
                                           const Eigen::Matrix3Xd& x) {
  SparseMatrix stiffness;
  assembler.assemble(problem.model, x, StiffnessKind::kExact, 1.0, 0.0, stiffness);
  Eigen::SparseMatrix<double> k = stiffness;
  for (int col = 0; col < k.outerSize(); ++col) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(k, col); it; ++it) {
      if (problem.driven[it.row()] || problem.driven[it.col()]) it.valueRef() = it.row() == it.col() ? 1.0 : 0.0;
    }
  }
  return k;
}

double mean_diagonal(const Eigen::SparseMatrix<double>& k) { return k.diagonal().cwiseAbs().mean(); }

// Newton from x at fixed loads; returns false when it does not converge. The line search takes
// no step that raises the energy: where the Newton step is not downhill (an indefinite
// stiffness), it searches along the force instead. `descend`: where K has a direction of negative
// curvature, the step solves K + shift I with the least shift (within a factor of 2) that makes it
// positive definite, a downhill step that heads for a minimum rather than the saddle nearby (after
// leaving an unstable equilibrium).
bool newton(const Problem& problem, const Loads& loads, double reference_force, const StaticSettings& settings,
            StiffnessAssembler& assembler, Eigen::Matrix3Xd& x, StaticReport& report, bool descend) {
  ForceWorkspace ws;
  GridLDLT solver(problem.model);
  Eigen::VectorXd r = residual(problem, loads, x, ws);
  const double tolerance = settings.tolerance * reference_force;
  const double cell = problem.model.cell_size.minCoeff();
  for (int iteration = 0; iteration < settings.max_newton_iterations; ++iteration) {
    report.residual = r.norm();
    if (report.residual <= tolerance) return true;
    ++report.newton_iterations;
    if (settings.progress) settings.progress({problem.load_done, report.newton_iterations, report.residual});

    // K dx = r on free dofs, identity rows on driven ones. The shift of kShiftFraction keeps a
    // free body's singular stiffness factorisable, and refinement removes its effect.
    const Eigen::SparseMatrix<double> k = free_stiffness(problem, assembler, x);
    const double mean = mean_diagonal(k);
    double shift = kShiftFraction * mean;
    if (!solver.factorise(k, shift)) return false;
    const bool indefinite = descend && solver.pivots().minCoeff() < 0.0;
    // the least shift, within a factor of 2, that makes it positive definite: a larger one would
    // shorten the step along the direction that leads downhill
    if (indefinite) shift = 1e-3 * kNegativeCurvature * mean;
    for (int tries = 0; indefinite && tries < 60; ++tries) {
      if (!solver.factorise(k, shift)) return false;
      if (solver.pivots().minCoeff() > 0.0) break;
      shift *= 2.0;
    }
    Eigen::VectorXd dx = solver.solve(r);
    if (!indefinite) {
      for (int step = 0; step < kRefinementSteps; ++step) dx += solver.solve(r - k * dx);
    }
    if (!dx.allFinite()) return false;

    // energy line search along dx; an energy change below the round-off of the energy's terms (a
    // load's work is about the reference force times a cell) cannot be told from none
    const double energy = potential_energy(problem.model, loads, x);
    const double round_off = 1e-12 * std::max(std::abs(energy), reference_force * cell);
    double slope = -r.dot(dx);  // dE/dalpha at alpha = 0
    if (!(slope < 0.0)) {       // not downhill: along the force, a tenth of a cell at most at first
      dx = r * (0.1 * cell / r.cwiseAbs().maxCoeff());
      slope = -r.dot(dx);
    }
    bool accepted = false;
    Eigen::Matrix3Xd trial;
    for (double alpha = 1.0; alpha > 1e-6; alpha *= 0.5) {
      trial = x + alpha * Eigen::Map<const Eigen::Matrix3Xd>(dx.data(), 3, x.cols());
      const double trial_energy = potential_energy(problem.model, loads, trial);
      if (std::isfinite(trial_energy) && trial_energy <= energy + 1e-4 * alpha * slope + round_off) {
        accepted = true;
        break;
      }
    }
    if (!accepted) return false;
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

// A direction of negative curvature of the exact stiffness K at x on the free dofs (scaled to move
// no node more than a tenth of a cell), or an empty vector when there is none: the equilibrium is
// stable. From the most negative pivot d_i of P (K + s I) P^T = L D L^T (GridLDLT), s = kNegativeCurvature
// times the mean diagonal: v = P^T L^-T e_i has v^T (K + s I) v = d_i < 0.
Eigen::VectorXd negative_curvature(const Problem& problem, StiffnessAssembler& assembler, const Eigen::Matrix3Xd& x) {
  const Eigen::SparseMatrix<double> k = free_stiffness(problem, assembler, x);
  const double mean = mean_diagonal(k);
  GridLDLT solver(problem.model);
  if (!solver.factorise(k, kNegativeCurvature * mean)) return {};
  const Eigen::VectorXd pivots = solver.pivots();
  Eigen::Index most_negative = 0;
  if (!(pivots.minCoeff(&most_negative) < 0.0)) return {};
  Eigen::VectorXd direction = solver.pivot_direction(most_negative);
  for (Eigen::Index i = 0; i < direction.size(); ++i) {
    if (problem.driven[i]) direction[i] = 0.0;
  }
  const double largest = direction.cwiseAbs().maxCoeff();
  if (!(largest > 0.0) || !std::isfinite(largest) || !(direction.dot(k * direction) < 0.0)) return {};
  return direction * (0.1 * problem.model.cell_size.minCoeff() / largest);
}

// Moves x downhill along +-direction (the side and length, up to 4 times it, of lowest energy).
// False when neither side lowers the energy.
bool leave_downhill(const Problem& problem, const Loads& loads, const Eigen::VectorXd& direction, Eigen::Matrix3Xd& x) {
  const Eigen::Map<const Eigen::Matrix3Xd> step(direction.data(), 3, x.cols());
  double best = potential_energy(problem.model, loads, x);
  Eigen::Matrix3Xd best_x = x;
  for (const double length : {0.25, 0.5, 1.0, 2.0, 4.0}) {
    for (const double side : {1.0, -1.0}) {
      const Eigen::Matrix3Xd trial = x + (side * length) * step;
      const double energy = potential_energy(problem.model, loads, trial);
      if (std::isfinite(energy) && energy < best) {
        best = energy;
        best_x = trial;
      }
    }
  }
  if (best_x == x) return false;
  x = best_x;
  return true;
}

// Newton, then, for a held body, away from each unstable equilibrium it finds and towards a
// minimum, within the settings' escapes. False when it does not converge or ends unstable
// (report.message says).
bool stable_equilibrium(const Problem& problem, const Loads& loads, double reference_force,
                        const StaticSettings& settings, StiffnessAssembler& assembler, Eigen::Matrix3Xd& x,
                        StaticReport& report) {
  if (!newton(problem, loads, reference_force, settings, assembler, x, report, false)) return false;
  if (!problem.held) return true;
  for (;;) {
    const Eigen::VectorXd direction = negative_curvature(problem, assembler, x);
    if (direction.size() == 0) return true;
    ++report.unstable_equilibria;
    if (report.unstable_equilibria > settings.max_instability_escapes) {
      report.message =
          "the equilibrium found is unstable (its stiffness has a direction of negative curvature) "
          "and max_instability_escapes = " +
          std::to_string(settings.max_instability_escapes) + " escapes are spent";
      return false;
    }
    if (!leave_downhill(problem, loads, direction, x)) return false;
    if (!newton(problem, loads, reference_force, settings, assembler, x, report, true)) return false;
  }
}

// The tangent predictor of an increment: the free dofs' response, on the stiffness at x, to the
// driven dofs' move from x to `trial` and to the loads' increment (trial's free dofs are x's).
// Without it the increment's whole move first lands on the cells next to the driven nodes, which
// can crush them into a state where the stiffness is indefinite and Newton crawls. Kept only
// where the stiffness is positive definite and it lowers the energy.
void predict(const Problem& problem, const Loads& loads, StiffnessAssembler& assembler, const Eigen::Matrix3Xd& x,
             Eigen::Matrix3Xd& trial) {
  SparseMatrix assembled;
  assembler.assemble(problem.model, x, StiffnessKind::kExact, 1.0, 0.0, assembled);
  const Eigen::SparseMatrix<double> k = assembled;
  const Eigen::Matrix3Xd move = trial - x;  // nonzero on the driven dofs only
  ForceWorkspace ws;
  Eigen::VectorXd rhs =
      residual(problem, loads, x, ws) - k * Eigen::Map<const Eigen::VectorXd>(move.data(), move.size());
  for (Eigen::Index i = 0; i < rhs.size(); ++i) {
    if (problem.driven[i]) rhs[i] = 0.0;
  }
  const Eigen::SparseMatrix<double> k_free = free_stiffness(problem, assembler, x);
  GridLDLT solver(problem.model);
  if (!solver.factorise(k_free, kShiftFraction * mean_diagonal(k_free)) || !(solver.pivots().minCoeff() > 0.0)) return;
  const Eigen::VectorXd dx = solver.solve(rhs);
  if (!dx.allFinite()) return;
  const Eigen::Matrix3Xd predicted = trial + Eigen::Map<const Eigen::Matrix3Xd>(dx.data(), 3, x.cols());
  const double energy = potential_energy(problem.model, loads, predicted);
  if (std::isfinite(energy) && energy < potential_energy(problem.model, loads, trial)) trial = predicted;
}

// Whether the driven degrees of freedom hold the body: no rigid motion (3 translations, 3
// rotations about the centroid) leaves all of them in place. Only then is an equilibrium's
// stability judged: a free body's rotations under dead loads have a curvature of their own.
bool holds_the_body(const Model& model, const std::vector<std::uint8_t>& driven) {
  const Eigen::Vector3d centroid = model.rest_positions.rowwise().mean();
  const double length = std::max(model.cell_size.maxCoeff(), 1e-300);
  Eigen::Matrix<double, 6, 6> gram = Eigen::Matrix<double, 6, 6>::Zero();  // R_d^T R_d
  for (int n = 0; n < model.num_nodes(); ++n) {
    const Eigen::Vector3d arm = (model.rest_positions.col(n) - centroid) / length;
    for (int a = 0; a < 3; ++a) {
      if (!driven[3 * n + a]) continue;
      Eigen::Matrix<double, 6, 1> row = Eigen::Matrix<double, 6, 1>::Zero();  // motion of dof (n, a)
      row[a] = 1.0;
      for (int w = 0; w < 3; ++w) row[3 + w] = Eigen::Vector3d::Unit(w).cross(arm)[a];
      gram += row * row.transpose();
    }
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> eigen(gram);
  return eigen.eigenvalues()[0] > 1e-9 * std::max(eigen.eigenvalues()[5], 1e-300);
}

// The stiffness [N/m] of the stiffest spring or cell: a nearly incompressible material's cells
// (their bulk modulus B over a cell, B h, with the neo-Hookean law) can be far stiffer than its
// springs, and the residual's round-off floor grows with them.
double stiffness_scale(const Model& model) {
  double stiffest = *std::max_element(model.spring_stiffness.begin(), model.spring_stiffness.end());
  if (model.cell_law == CellLaw::kNeoHookean) {
    for (const Material& material : model.materials) {
      const double axial_modulus = bulk_modulus(material) + 4.0 / 3.0 * shear_modulus(material);
      stiffest = std::max(stiffest, axial_modulus * model.cell_size.maxCoeff());
    }
  }
  return stiffest;
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
  if (invalid.empty() && settings.max_instability_escapes < 0) {
    invalid = "max_instability_escapes = " + std::to_string(settings.max_instability_escapes) + ": must be >= 0";
  }
  if (invalid.empty() &&
      (settings.initial_load_steps < 1 || settings.max_load_steps < 1 || settings.max_newton_iterations < 1)) {
    invalid = "initial_load_steps, max_load_steps and max_newton_iterations must each be >= 1 (got " +
              std::to_string(settings.initial_load_steps) + ", " + std::to_string(settings.max_load_steps) + ", " +
              std::to_string(settings.max_newton_iterations) + ")";
  }
  if (invalid.empty() && settings.start_from_state) {
    if (!(settings.start_load_fraction >= 0.0 && settings.start_load_fraction <= 1.0)) {
      invalid = "start_load_fraction = " + std::to_string(settings.start_load_fraction) + ": must be in [0, 1]";
    } else {
      invalid = node_columns_error(model, state.positions, "state.positions (start_from_state)", false);
      if (invalid.empty() && !state.positions.allFinite()) {
        invalid = "state.positions (start_from_state) holds a number that is not finite";
      }
    }
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
  problem.held = holds_the_body(model, problem.driven);
  // the force scale that residuals are measured against
  double reference_force = (loads.gravity.norm() * model.mass).norm();
  if (loads.nodal_forces.size() > 0) reference_force = std::max(reference_force, loads.nodal_forces.norm());
  const double driven_motion = (target - model.rest_positions).norm();
  const double stiffest = stiffness_scale(model);
  if (driven_motion > 0.0) reference_force = std::max(reference_force, stiffest * driven_motion);
  // residuals cannot fall below the round-off of the largest elastic forces
  const double round_off = 1e-13 * stiffest * model.cell_size.maxCoeff() * std::sqrt(num_nodes);
  reference_force = std::max(reference_force, round_off / settings.tolerance);

  std::unique_ptr<StiffnessAssembler> assembler;
  try {
    assembler = std::make_unique<StiffnessAssembler>(model);
  } catch (const std::length_error& too_large) {
    report.message = too_large.what();
    return report;
  }
  Eigen::Matrix3Xd x = settings.start_from_state ? state.positions : model.rest_positions;
  const Eigen::Matrix3Xd start_driven = x;
  // the load fraction at the ramp's parameter t in [0, 1]
  const double first_fraction = settings.start_from_state ? settings.start_load_fraction : 0.0;
  const auto load_fraction = [first_fraction](double t) { return first_fraction + t * (1.0 - first_fraction); };
  problem.load_done = first_fraction;
  double done = 0.0;
  double increment = 1.0 / settings.initial_load_steps;
  const double smallest = 1.0 / settings.max_load_steps;
  while (done < 1.0) {
    const double next = std::min(1.0, done + increment);
    Eigen::Matrix3Xd trial = x;
    for (int i = 0; i < 3 * num_nodes; ++i) {
      if (problem.driven[i]) trial(i) = start_driven(i) + next * (target(i) - start_driven(i));
    }
    report.message.clear();
    if (settings.progress) settings.progress({problem.load_done, report.newton_iterations, report.residual});
    predict(problem, scaled_loads(loads, load_fraction(next)), *assembler, x, trial);
    if (stable_equilibrium(problem, scaled_loads(loads, load_fraction(next)), reference_force, settings, *assembler,
                           trial, report)) {
      x = trial;
      done = next;
      problem.load_done = load_fraction(done);
      ++report.load_steps;
      increment *= 1.5;  // grow again after a success
      continue;
    }
    if (increment <= smallest * 1.000001) {
      std::ostringstream message;
      message << "static solve did not converge at load fraction " << load_fraction(next) << " (residual "
              << report.residual << " N after " << report.newton_iterations << " Newton iterations, smallest increment "
              << increment << ")";
      if (!report.message.empty()) message << ": " << report.message;
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
