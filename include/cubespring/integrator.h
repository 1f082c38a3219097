// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "cubespring/constraints.h"
#include "cubespring/forces.h"
#include "cubespring/model.h"
#include "cubespring/stable_time_step.h"
#include "cubespring/state.h"
#include "cubespring/stiffness.h"

/// Units are SI throughout the API: metres, kilograms, seconds, newtons, pascals.
namespace cubespring {

class GridMultigrid;   // src/solve/grid_multigrid.h
class Preconditioner;  // src/solve/conjugate_gradient.h
class ThreadChoice;    // src/solve/thread_choice.h

enum class Integrator {
  kSymplecticEuler,  ///< v += dt a(x, v); x += dt v. Explicit, conditionally stable.
  kVelocityVerlet,   ///< half kick, drift, half kick. Explicit, conditionally stable.
  kImplicitEuler,    ///< backward Euler linearised once per step, solved by conjugate gradients.
};
const char* integrator_name(Integrator integrator);

/// How the implicit step's conjugate gradients are preconditioned.
enum class SolverPreconditioner {
  /// Jacobi until two solves in a row take more than kJacobiIterationsBeforeMultigrid iterations
  /// or one fails (that step is then solved again with the multigrid), the multigrid from then
  /// on: each where it is the faster, by iteration counts only, so the same steps choose the
  /// same way on every run and thread count. The default since 2026-12-06.
  kAutomatic,
  /// A geometric multigrid V-cycle on the lattice's node grid (src/solve/grid_multigrid.h): the
  /// iterations barely depend on the body's size and are 6-10 times fewer than Jacobi's, at about
  /// 5 times the cost each (its cycle runs on one thread); its coarse levels are built on the
  /// first step and again when the driven nodes change or the iterations double. On a clamped
  /// beam of E = 1 MPa (32x8x8 cells): 6 iterations against 37 at dt = 1 ms and nu = 0.3 (about
  /// the same time), 24 against 233 at 4 ms and nu = 0.45 (2.2 times faster), 70 against 735 at
  /// 16 ms and nu = 0.49 (2.7 times faster); docs/model-baudet2007.md, section 6.
  kMultigrid,
  /// The matrix's diagonal (Jacobi): the cheapest iteration, shared by the threads; their number
  /// grows with the time step, the stiffness and nu. The only preconditioner until 2026-12-06.
  kJacobi,
};
/// Above this many iterations of a Jacobi-preconditioned solve, the multigrid's fewer and dearer
/// iterations take less time (SolverPreconditioner::kAutomatic). A cycle costs 5-7 of Jacobi's
/// iterations (more on larger bodies, and on two threads, which share Jacobi's iterations but not
/// the cycle), and takes 6-10 times fewer: on one thread Jacobi was the faster at up to 42
/// iterations on the bench's bodies (`cubespring bench`), the slower at 69 on a 32x8x8 beam and
/// from 88 on every body measured; the threshold stays on the safe side of that.
inline constexpr int kJacobiIterationsBeforeMultigrid = 80;
const char* solver_preconditioner_name(SolverPreconditioner preconditioner);

struct StepSettings {
  Integrator integrator = Integrator::kSymplecticEuler;
  double time_step = 1e-4;  ///< dt [s], > 0
  int threads = 1;          ///< threads of the force passes and the implicit step's
                            ///< conjugate gradients; results do not depend on it
  /// Take one thread instead of `threads` while one is measured faster: a small body, or a core
  /// busy with another process (a renderer, a device loop), whose barriers then wait for the
  /// scheduler (a 32x8x8 step took 200x as long on 2 threads as on 1 beside one busy process).
  /// The steps are timed and the other count is tried again now and then (src/solve/thread_choice.h).
  /// Results do not depend on it; StepReport::threads says what a step took.
  bool adapt_threads = true;
  double solver_tolerance = 1e-6;    ///< implicit: CG relative residual, finite and > 0
  int solver_max_iterations = 2000;  ///< implicit: CG iteration cap, >= 1 (a residual that turns
                                     ///< NaN stops CG before it: solver-failed)
  /// implicit: CG's preconditioner (a multigrid whose level cannot be factorised falls back to
  /// Jacobi for that step)
  SolverPreconditioner preconditioner = SolverPreconditioner::kAutomatic;
  /// A node faster than this is taken as a blow-up [m/s], >= 0 (infinity: none); 0 means 10 times
  /// the fastest pressure wave speed of the body's materials.
  double speed_limit = 0.0;
  /// Whether the caller chose time_step: an explicit step that goes unstable then asks whether it
  /// is above the body's stable step (max_stable_time_step() finds it). A caller that derived the
  /// step from that limit itself (the Bullet plugin) sets false and names the cause in its terms.
  bool caller_chose_time_step = true;
  /// The fill of its bounding box from which the body steps on the grid passes
  /// (ForceOptions::min_grid_fill: 0 whenever the lattice allows, NaN never).
  double min_grid_fill = kDefaultMinGridFill;
};

enum class StepStatus {
  kOk,            ///< the state advanced by one step
  kUnstable,      ///< positions or velocities are no longer finite, or a node exceeded the speed
                  ///< limit; the state is left as it was before the step
  kSolverFailed,  ///< implicit: CG did not reach the tolerance; the state is left unchanged
  kInvalidInput,  ///< the state, loads or constraints do not fit the body (their node counts), the
                  ///< gravity is not finite, speed_limit not >= 0, time_step not a finite number
                  ///< > 0, the implicit solver's tolerance or iterations out of range, or the body
                  ///< is not the one the stepper was made for: nothing was read or changed (a bad
                  ///< time step read as kUnstable, bad solver settings as kSolverFailed, until
                  ///< 2026-12-05)
};
const char* step_status_name(StepStatus status);

struct StepReport {
  StepStatus status = StepStatus::kOk;
  std::string message;         ///< what went wrong, with figures; empty when ok
  int solver_iterations = 0;   ///< implicit: CG iterations (products with the matrix)
  double solver_residual = 0;  ///< implicit: CG relative residual reached (of its updated residual)
  int threads = 1;             ///< threads the step took (StepSettings::adapt_threads)
  bool ok() const { return status == StepStatus::kOk; }
};

/// Advances a body's state by one time step. Keeps the scratch arrays of its integrator between
/// steps, so an explicit step allocates nothing after the first one (an implicit step assembles
/// into a kept sparsity pattern but allocates its CG vectors). One stepper per body: a body of
/// other counts is refused (invalid-input). A body's spring stiffnesses and cell corrections
/// may change between steps: each step reads them (after a change, model.mark_changed(), as
/// model.h says).
class Stepper {
 public:
  explicit Stepper(const Model& model);
  ~Stepper();
  Stepper(Stepper&&) noexcept;
  Stepper& operator=(Stepper&&) noexcept;

  StepReport step(const Model& model, const Constraints& constraints, const Loads& loads, const StepSettings& settings,
                  State& state);

  /// The nodal forces [N] (3 x num_nodes) the last step computed last: for symplectic Euler and
  /// implicit Euler those at the step's start state, which its kick used (springs, correction,
  /// damping, gravity, loads); for velocity Verlet those at its end. What held a driven node
  /// over a symplectic step is its momentum change less dt times its force here.
  const Eigen::Matrix3Xd& last_forces() const { return forces_; }

 private:
  StepReport explicit_step(const Model& model, const Constraints& constraints, const Loads& loads,
                           const StepSettings& settings, State& state);
  StepReport implicit_step(const Model& model, const Constraints& constraints, const Loads& loads,
                           const StepSettings& settings, State& state);
  Preconditioner* prepare_multigrid(const Model& model, const std::vector<std::uint8_t>& driven);
  /// `fastest` [m/s] is NaN or infinite when a velocity, or (positions_checked) a position, is not
  /// finite; a failure's message says where it shows in the step's `start` state.
  StepReport check(const Model& model, const StepSettings& settings, double fastest, const State& candidate,
                   const State& start, bool positions_checked = false) const;

  ForceWorkspace workspace_;
  Eigen::Matrix3Xd forces_;
  State candidate_;
  State half_step_end_;  // velocity Verlet's second half kick writes here (it reads candidate_)
  std::unique_ptr<StiffnessAssembler> assembler_;  // built on the first implicit step
  std::unique_ptr<GridMultigrid> multigrid_;       // on the first multigrid-preconditioned one
  std::unique_ptr<ThreadChoice> thread_choice_;    // StepSettings::adapt_threads
  std::vector<std::uint8_t> multigrid_fixed_;      // the driven unknowns its coarse levels were built for
  int multigrid_iterations_ = 0;                   // CG's iterations on the first step after they were
  bool multigrid_fresh_ = false;                   // this step built them
  int last_solver_iterations_ = 0;                 // the last implicit step's CG iterations
  bool multigrid_chosen_ = false;                  // kAutomatic: Jacobi's solves took too many
  int long_jacobi_solves_ = 0;                     // kAutomatic: in a row, over the threshold
  SparseMatrix system_;
  // the body's counts when the stepper was made: its arrays and assembler hold them
  int made_for_nodes_ = 0, made_for_springs_ = 0, made_for_cells_ = 0;
};

/// Fastest pressure wave speed among the body's materials [m/s].
double max_wave_speed(const Model& model);

}  // namespace cubespring
