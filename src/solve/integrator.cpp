// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "cubespring/integrator.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "forces/drive_nodes.h"
#include "forces/force_passes.h"
#include "forces/input_checks.h"
#include "solve/conjugate_gradient.h"
#include "solve/grid_multigrid.h"
#include "solve/thread_choice.h"
#include "thread_shares.h"

namespace cubespring {

const char* integrator_name(Integrator integrator) {
  switch (integrator) {
    case Integrator::kSymplecticEuler: return "symplectic-euler";
    case Integrator::kVelocityVerlet: return "velocity-verlet";
    case Integrator::kImplicitEuler: return "implicit-euler";
  }
  return "unknown";
}

const char* step_status_name(StepStatus status) {
  switch (status) {
    case StepStatus::kOk: return "ok";
    case StepStatus::kUnstable: return "unstable";
    case StepStatus::kSolverFailed: return "solver-failed";
    case StepStatus::kInvalidInput: return "invalid-input";
  }
  return "unknown";
}

const char* solver_preconditioner_name(SolverPreconditioner preconditioner) {
  switch (preconditioner) {
    case SolverPreconditioner::kAutomatic: return "automatic";
    case SolverPreconditioner::kMultigrid: return "multigrid";
    case SolverPreconditioner::kJacobi: return "jacobi";
  }
  return "unknown";
}

double max_wave_speed(const Model& model) {
  double speed = 0.0;
  for (const Material& material : model.materials) speed = std::max(speed, pressure_wave_speed(material));
  return speed;
}

Stepper::Stepper(const Model& model)
    : made_for_nodes_(model.num_nodes()), made_for_springs_(model.num_springs()), made_for_cells_(model.num_cells()) {
  thread_choice_ = std::make_unique<ThreadChoice>();
  workspace_.resize(model);
  forces_.setZero(3, model.num_nodes());
}

Stepper::~Stepper() = default;
Stepper::Stepper(Stepper&&) noexcept = default;
Stepper& Stepper::operator=(Stepper&&) noexcept = default;

StepReport Stepper::step(const Model& model, const Constraints& constraints, const Loads& loads,
                         const StepSettings& settings, State& state) {
  std::string invalid = state_and_loads_error(model, state, loads);
  if (invalid.empty()) invalid = constraints_error(model, constraints);
  if (invalid.empty() && (model.num_nodes() != made_for_nodes_ || model.num_springs() != made_for_springs_ ||
                          model.num_cells() != made_for_cells_)) {
    std::ostringstream message;
    message << "the stepper was made for a body of " << made_for_nodes_ << " nodes, " << made_for_springs_
            << " springs and " << made_for_cells_ << " cells; this one has " << model.num_nodes() << ", "
            << model.num_springs() << " and " << model.num_cells() << ": make a Stepper for it";
    invalid = message.str();
  }
  if (invalid.empty() && !(settings.speed_limit >= 0.0)) {  // NaN too; infinity: no limit
    std::ostringstream message;
    message << "speed_limit = " << settings.speed_limit << " m/s: must be a number >= 0 (0: the default)";
    invalid = message.str();
  }
  if (invalid.empty() && (!(settings.time_step > 0.0) || !std::isfinite(settings.time_step))) {
    std::ostringstream message;
    message << "time_step = " << settings.time_step << " s: the time step must be a finite number > 0";
    invalid = message.str();
  }
  if (invalid.empty() && settings.integrator == Integrator::kImplicitEuler &&
      (!(settings.solver_tolerance > 0.0) || !std::isfinite(settings.solver_tolerance) ||
       settings.solver_max_iterations < 1)) {
    std::ostringstream message;
    message << "solver_tolerance = " << settings.solver_tolerance
            << ", solver_max_iterations = " << settings.solver_max_iterations
            << ": the implicit step needs a finite tolerance > 0 and at least 1 iteration";
    invalid = message.str();
  }
  if (!invalid.empty()) return {StepStatus::kInvalidInput, invalid};
  StepSettings taken = settings;
  if (settings.adapt_threads) taken.threads = thread_choice_->threads(settings.threads);
  const auto start = std::chrono::steady_clock::now();
  StepReport report = settings.integrator == Integrator::kImplicitEuler
                          ? implicit_step(model, constraints, loads, taken, state)
                          : explicit_step(model, constraints, loads, taken, state);
  if (settings.adapt_threads) {
    thread_choice_->record(taken.threads,
                           std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  report.threads = std::max(1, taken.threads);
  return report;
}

namespace {

// Where a blow-up shows, for the message: the fastest node after the step, where it was at the
// step's start, and the cell most compressed then (a cell crushed far below its rest volume is far
// stiffer than at rest, so a step stable at rest need not be stable there).
std::string where_it_failed(const Model& model, const State& candidate, const State& start) {
  Eigen::Index node = 0;
  candidate.velocities.colwise().squaredNorm().maxCoeff(&node);
  std::ostringstream out;
  out << ", node " << node << " (at (" << start.positions.col(node).transpose() << ") m when the step began)";
  double least = std::numeric_limits<double>::infinity();
  int crushed = -1;
  for (int c = 0; c < model.num_cells(); ++c) {
    const double ratio = cell_signed_volume(model, start.positions, c) / model.rest_cell_volume();
    if (ratio < least) {
      least = ratio;
      crushed = c;
    }
  }
  if (crushed >= 0 && least < 0.5) {
    out << "; cell " << crushed << " is crushed to " << least
        << " of its rest volume, where the tissue is far stiffer than the step was chosen for (a tool or a"
           " contact pressing it, or a step too long)";
  }
  return out.str();
}

}  // namespace

StepReport Stepper::check(const Model& model, const StepSettings& settings, double fastest, const State& candidate,
                          const State& start, bool positions_checked) const {
  const double limit = settings.speed_limit > 0.0 ? settings.speed_limit : 10.0 * max_wave_speed(model);
  // x - x is 0 for a finite x and NaN otherwise; its sum is a vectorised allFinite()
  const bool finite =
      std::isfinite(fastest) && (positions_checked || std::isfinite((candidate.positions - candidate.positions).sum()));
  if (finite && fastest <= limit) return {};
  std::ostringstream message;
  if (!finite) {
    message << "positions or velocities became NaN or infinite";
  } else {
    message << "a node moves at " << fastest << " m/s, above the limit of " << limit << " m/s: the step is unstable";
    message << where_it_failed(model, candidate, start);
  }
  // the likely cause, not the body's limit itself: finding that assembles the stiffness (seconds
  // and gigabytes for a large body) at the moment the caller learns of the blow-up
  if (settings.integrator != Integrator::kImplicitEuler && settings.caller_chose_time_step) {
    message << " (is the explicit time step of " << settings.time_step
            << " s above the body's stable step? max_stable_time_step() finds it)";
  }
  return {StepStatus::kUnstable, message.str()};
}

StepReport Stepper::explicit_step(const Model& model, const Constraints& constraints, const Loads& loads,
                                  const StepSettings& settings, State& state) {
  const double dt = settings.time_step;
  const ForceOptions options{true, settings.threads, settings.min_grid_fill};
  if (candidate_.positions.cols() != model.num_nodes()) candidate_ = state;
  double fastest_sq = 0.0;
  if (settings.integrator == Integrator::kSymplecticEuler) {
    // v += dt M^-1 f(x, v); x += dt v. The kick drives the driven nodes itself, each thread its
    // own: a serial sweep here would move their cache lines to this thread every step
    KickDrift kick{dt, dt, &state, &candidate_};
    // (constraints of no model, Constraints(), have no flags for the kick to read)
    const bool kick_drives = constraints.num_nodes() == model.num_nodes();
    if (kick_drives) kick.driven = &constraints;
    fastest_sq = compute_forces_and_kick(model, state, loads, options, workspace_, forces_, kick);
    if (!kick_drives && !drive_nodes(constraints, dt, state, candidate_, 0, constraints.num_nodes())) {
      fastest_sq = std::numeric_limits<double>::quiet_NaN();
    }
  } else {
    // half kick and drift, then a half kick with the force at the new positions (its damping
    // taken at the half-step velocity), fused with that force pass like the first: each thread
    // kicks and drives its own nodes (both drive from the step's start over dt)
    const bool kick_drives = constraints.num_nodes() == model.num_nodes();
    const Constraints* driven = kick_drives ? &constraints : nullptr;
    (void)compute_forces_and_kick(model, state, loads, options, workspace_, forces_,
                                  KickDrift{0.5 * dt, dt, &state, &candidate_, driven});
    if (!kick_drives) (void)drive_nodes(constraints, dt, state, candidate_, 0, constraints.num_nodes());
    // into a third state: the kick reads the half-step state while it writes (x' = x + 0 v')
    if (half_step_end_.positions.cols() != model.num_nodes()) half_step_end_ = state;
    fastest_sq = compute_forces_and_kick(model, candidate_, loads, options, workspace_, forces_,
                                         KickDrift{0.5 * dt, 0.0, &candidate_, &half_step_end_, driven, &state, dt});
    if (!kick_drives && !drive_nodes(constraints, dt, state, half_step_end_, 0, constraints.num_nodes())) {
      fastest_sq = std::numeric_limits<double>::quiet_NaN();
    }
    std::swap(candidate_, half_step_end_);
  }
  candidate_.time = state.time + dt;
  // the kick checked the positions it made (driven nodes' targets are finite); a serial sweep
  // here would also pull every position into this thread's cache
  StepReport report = check(model, settings, std::sqrt(fastest_sq), candidate_, state, true);
  if (report.ok()) std::swap(state, candidate_);
  return report;
}

// The multigrid for this step's system_: its coarse levels (the costly part) are built again when
// there are none, when the driven unknowns changed, or when the last solve took more than twice
// the iterations of the first one after they were built (the matrix has moved away from the one
// they were made of); otherwise only its finest level takes the new matrix. Null (Jacobi) when a
// level cannot be factorised.
Preconditioner* Stepper::prepare_multigrid(const Model& model, const std::vector<std::uint8_t>& driven) {
  if (!multigrid_) multigrid_ = std::make_unique<GridMultigrid>(model);
  const bool stale =
      !multigrid_->ready() || driven != multigrid_fixed_ || last_solver_iterations_ > 2 * multigrid_iterations_;
  multigrid_fresh_ = false;
  if (stale) {
    multigrid_fixed_ = driven;
    if (!multigrid_->setup(system_, driven)) return nullptr;
    multigrid_fresh_ = true;
  } else if (!multigrid_->refresh(system_)) {
    return nullptr;
  }
  return multigrid_.get();
}

// Backward Euler linearised at the start of the step (docs/model-baudet2007.md section 6):
//   (M (1 + dt alpha) + dt K_beta + dt^2 K) v+ = M v + dt f(x),  x+ = x + dt v+,
// with f the undamped force, K the PSD stiffness; driven nodes' v+ is known and eliminated.
StepReport Stepper::implicit_step(const Model& model, const Constraints& constraints, const Loads& loads,
                                  const StepSettings& settings, State& state) {
  const double dt = settings.time_step;
  const int num_nodes = model.num_nodes();
  if (!assembler_) {
    try {
      assembler_ = std::make_unique<StiffnessAssembler>(model);
    } catch (const std::length_error& too_large) {
      return {StepStatus::kSolverFailed, too_large.what()};
    }
  }

  const ForceOptions without_damping{false, settings.threads, settings.min_grid_fill};
  compute_forces(model, state, loads, without_damping, workspace_, forces_);
  assembler_->assemble(model, state.positions, StiffnessKind::kPositiveSemiDefinite, dt * dt, dt, system_,
                       settings.threads);

  Eigen::VectorXd rhs(3 * num_nodes);
  Eigen::VectorXd guess(3 * num_nodes);
  std::vector<std::uint8_t> driven(3 * num_nodes, 0);
  const int* outer = system_.outerIndexPtr();
  const int* inner = system_.innerIndexPtr();
  double* values = system_.valuePtr();
  // the threads share the nodes, then (once every driven velocity is known) their rows: each
  // entry is changed by one thread, the same way on any thread count
  run_shares(std::min(settings.threads, num_nodes / kMinNodesPerThread),
             [&](int share, int shares, const auto& barrier) {
               const auto [first, end] = equal_share(num_nodes, share, shares);
               for (int n = first; n < end; ++n) {
                 const double mass = model.inertia()[n];
                 const double mass_term = mass + dt * model.mass_damping[n];
                 for (int a = 0; a < 3; ++a) {
                   rhs[3 * n + a] = mass * state.velocities(a, n) + dt * forces_(a, n);
                   guess[3 * n + a] = state.velocities(a, n);
                 }
                 // the mass sits on the diagonal block's own entries
                 for (int a = 0; a < 3; ++a) {
                   const int row = 3 * n + a;
                   const int* hit = std::lower_bound(inner + outer[row], inner + outer[row + 1], row);
                   values[hit - inner] += mass_term;
                 }
                 if (n < constraints.num_nodes() && constraints.is_driven(n)) {
                   const Eigen::Vector3d velocity = (constraints.target(n) - state.positions.col(n)) / dt;
                   for (int a = 0; a < 3; ++a) {
                     if (((constraints.driven_axes(n) >> a) & 1) == 0) continue;
                     driven[3 * n + a] = 1;
                     guess[3 * n + a] = velocity[a];
                   }
                 }
               }
               if (constraints.num_driven() == 0) return;
               barrier();
               // eliminate driven unknowns: move their columns to the right-hand side, identity rows
               for (int row = 3 * first; row < 3 * end; ++row) {
                 for (int e = outer[row]; e < outer[row + 1]; ++e) {
                   const int col = inner[e];
                   if (driven[row]) {
                     values[e] = row == col ? 1.0 : 0.0;
                   } else if (driven[col]) {
                     rhs[row] -= values[e] * guess[col];
                     values[e] = 0.0;
                   }
                 }
                 if (driven[row]) rhs[row] = guess[row];
               }
             });

  // automatic: Jacobi until two solves in a row take more than kJacobiIterationsBeforeMultigrid
  // iterations (the first step from rest is often one) or one fails, the multigrid from then on
  // (and at once for the solve that failed)
  const bool automatic = settings.preconditioner == SolverPreconditioner::kAutomatic;
  const bool with_multigrid =
      settings.preconditioner == SolverPreconditioner::kMultigrid || (automatic && multigrid_chosen_);
  Preconditioner* preconditioner = with_multigrid ? prepare_multigrid(model, driven) : nullptr;
  Eigen::VectorXd& velocity = guess;  // solved in place
  const Eigen::VectorXd start_guess = automatic && !with_multigrid ? guess : Eigen::VectorXd();
  const auto solve = [&] {
    const ConjugateGradientResult result =
        conjugate_gradient(system_, rhs, velocity, settings.solver_tolerance, settings.solver_max_iterations,
                           settings.threads, preconditioner);
    if (preconditioner && multigrid_fresh_) multigrid_iterations_ = std::max(1, result.iterations);
    return result;
  };
  ConjugateGradientResult solved = solve();
  if (automatic && !with_multigrid) {
    long_jacobi_solves_ = solved.iterations > kJacobiIterationsBeforeMultigrid ? long_jacobi_solves_ + 1 : 0;
    multigrid_chosen_ = long_jacobi_solves_ >= 2 || !solved.converged;
    if (!solved.converged && (preconditioner = prepare_multigrid(model, driven)) != nullptr) {
      const int jacobi_iterations = solved.iterations;
      velocity = start_guess;
      solved = solve();
      solved.iterations += jacobi_iterations;  // every product this step took
    }
  }
  last_solver_iterations_ = solved.iterations;
  StepReport report;
  report.solver_iterations = solved.iterations;
  report.solver_residual = solved.relative_residual;
  if (!solved.converged || !velocity.allFinite()) {
    std::ostringstream message;
    message << "conjugate gradients stopped after " << solved.iterations << " iterations at relative residual "
            << solved.relative_residual << " (tolerance " << settings.solver_tolerance << ")";
    report.status = StepStatus::kSolverFailed;
    report.message = message.str();
    return report;
  }

  candidate_ = state;
  candidate_.velocities = Eigen::Map<const Eigen::Matrix3Xd>(velocity.data(), 3, num_nodes);
  candidate_.positions += dt * candidate_.velocities;
  // the check below sees every velocity
  (void)drive_nodes(constraints, dt, state, candidate_, 0, constraints.num_nodes());
  candidate_.time = state.time + dt;
  const double fastest = std::sqrt(candidate_.velocities.colwise().squaredNorm().maxCoeff());
  StepReport checked = check(model, settings, fastest, candidate_, state);
  if (!checked.ok()) return checked;
  std::swap(state, candidate_);
  return report;
}

}  // namespace cubespring
