// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#pragma once

#include <functional>
#include <string>

#include "cubespring/constraints.h"
#include "cubespring/forces.h"
#include "cubespring/model.h"
#include "cubespring/state.h"

/// Units are SI throughout the API: metres, kilograms, seconds, newtons, pascals.
namespace cubespring {

/// Where a static solve is (StaticSettings::progress).
struct StaticProgress {
  double load_fraction = 0.0;  ///< of the load ramp reached by the increments done, in [0, 1]
  int newton_iterations = 0;   ///< so far, in all increments
  double residual = 0.0;       ///< the residual force before the last iteration's step [N]
};

struct StaticSettings {
  int initial_load_steps = 1;      ///< the load is applied in this many equal increments at first
  int max_load_steps = 256;        ///< increments are halved on failure down to 1 / max_load_steps
  int max_newton_iterations = 40;  ///< per increment
  double tolerance = 1e-9;         ///< residual force relative to the applied load (L2 norms)
  /// An equilibrium whose exact stiffness has a direction of negative curvature is unstable (a
  /// saddle or a maximum of the energy): the solver leaves it along that direction, downhill, and
  /// solves again, at most this many times in a solve; 0 reports it unstable at once.
  int max_instability_escapes = 16;
  /// Continuation: start from state.positions (an earlier solution) instead of the rest
  /// positions. The driven nodes move from where they are in state to their targets, and the
  /// loads ramp from start_load_fraction of their full value (the fraction that state was an
  /// equilibrium of; 0 when it carried none) to full.
  bool start_from_state = false;
  double start_load_fraction = 0.0;  ///< in [0, 1]; read with start_from_state
  /// Called as each load increment starts and at each Newton iteration, on the solving thread,
  /// for a caller that shows how a long solve goes (each factorises the stiffness:
  /// estimate_block_factorisation); empty: not called.
  std::function<void(const StaticProgress&)> progress;
};

struct StaticReport {
  /// An equilibrium was found at the full load and, when the constraints hold every rigid motion
  /// of the body, it is stable: the exact (unprojected) stiffness on the free degrees of freedom
  /// has no eigenvalue below -1e-3 of its mean diagonal (the LDL^T pivots of the stiffness plus
  /// that much are all positive). An unstable equilibrium of a held body
  /// is never reported as converged. (A free or partly held body's stability is not judged: its
  /// rigid rotations under dead loads have a curvature of their own.)
  bool converged = false;
  int unstable_equilibria = 0;  ///< unstable equilibria met on the way, and left downhill
  int load_steps = 0;           ///< increments taken
  int newton_iterations = 0;    ///< in all increments
  double residual = 0.0;        ///< final residual force [N] on the free nodes
  std::string message;          ///< why it failed; empty when converged
};

/// Static equilibrium under the loads and constraints: Newton's method on the exact stiffness with
/// a sparse LDL^T solver, an energy line search that never accepts a rise of the energy (where
/// the Newton step is not downhill, it takes the force's direction), and load stepping (the loads
/// and the driven nodes' displacements ramp from zero to full). Every equilibrium is checked for
/// stability (StaticReport::converged); an unstable one is left along a direction of negative
/// curvature and solved again (StaticSettings::max_instability_escapes). state.positions holds the result; velocities
/// are zeroed. Free bodies (no driven node) are solved in the range of the stiffness: rigid and zero-energy modes are
/// not excited by self-equilibrated loads. Loads or constraints that do not fit the body, a gravity that is not finite
/// or settings out of range are refused (the message says which) and the state is left as it was.
StaticReport solve_static(const Model& model, const Constraints& constraints, const Loads& loads,
                          const StaticSettings& settings, State& state);

/// What one factorisation of solve_static's stiffness costs on a block of cells.x() x cells.y() x
/// cells.z() cells (a full box), counted from its nested-dissection fronts without building
/// anything, so that a caller can refuse or announce a long run before it starts. It grows as the
/// block's largest cross-section squared (bytes) and cubed (operations).
struct FactorisationCost {
  double factor_bytes = 0;  ///< the factor's dense fronts, kept for the solves [bytes]
  double peak_bytes = 0;    ///< those and the largest front while it is factorised [bytes]
  double operations = 0;    ///< floating-point operations of one factorisation
};
FactorisationCost estimate_block_factorisation(const Eigen::Vector3i& cells);

}  // namespace cubespring
