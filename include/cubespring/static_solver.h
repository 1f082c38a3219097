// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#pragma once

#include <string>

#include "cubespring/constraints.h"
#include "cubespring/forces.h"
#include "cubespring/model.h"
#include "cubespring/state.h"

/// Units are SI throughout the API: metres, kilograms, seconds, newtons, pascals.
namespace cubespring {

struct StaticSettings {
  int initial_load_steps = 1;       ///< the load is applied in this many equal increments at first
  int max_load_steps = 256;         ///< increments are halved on failure down to 1 / max_load_steps
  int max_newton_iterations = 40;   ///< per increment
  double tolerance = 1e-9;          ///< residual force relative to the applied load (L2 norms)
};

struct StaticReport {
  bool converged = false;
  int load_steps = 0;           ///< increments taken
  int newton_iterations = 0;    ///< in all increments
  double residual = 0.0;        ///< final residual force [N] on the free nodes
  std::string message;          ///< why it failed; empty when converged
};

/// Static equilibrium under the loads and constraints: Newton's method on the exact stiffness with
/// a sparse LDL^T solver, an energy line search, and load stepping (the loads and the driven
/// nodes' displacements ramp from zero to full). state.positions holds the result; velocities are
/// zeroed. Free bodies (no driven node) are solved in the range of the stiffness: rigid and
/// zero-energy modes are not excited by self-equilibrated loads. Loads or constraints that do not
/// fit the body, a gravity that is not finite or settings out of range are refused (the message
/// says which) and the state is left as it was.
StaticReport solve_static(const Model& model, const Constraints& constraints, const Loads& loads,
                          const StaticSettings& settings, State& state);

}  // namespace cubespring
