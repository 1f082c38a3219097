// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Selective mass scaling: a longer explicit step for a body whose stiffest part is small. The
// explicit step of a whole organ is set by its fastest node (a stiff tumour, a 40 kPa inclusion in
// 8 kPa tissue, takes the step of the 8 kPa tissue down by 1.6x). Giving those nodes inertia that
// does not weigh slows their fastest modes to the rest's: equilibria, gravity and damping are as
// before, and what changes (the dynamics of the nodes that took mass) is bounded by how much mass
// was added (docs/bullet-plugin.md, section 1.3, measures it on the demo).
#pragma once

#include "cubespring/model.h"

/// Units are SI throughout the API: metres, kilograms, seconds, newtons, pascals.
namespace cubespring {

/// What add_mass_for_time_step() did.
struct MassScaling {
  double added_mass = 0.0;        ///< inertia added in all [kg]
  double added_fraction = 0.0;    ///< added_mass over the body's mass
  int nodes = 0;                  ///< nodes that took some
  double time_step_before = 0.0;  ///< max_stable_time_step() before [s] (Gershgorin's bound)
  double time_step_after = 0.0;   ///< and after [s]
};

/// Sets model.inertial_mass so that the body's explicit stable step (Gershgorin's bound, as
/// max_stable_time_step() finds it) is the longest that adding at most `max_added_fraction` of the
/// body's mass as inertia can buy: each node whose own bound, (1/m) sum_j |K_ij| over its rows,
/// is above the target takes just the inertia that brings it down to the target, and the target is
/// the lowest whose inertia fits the budget (found exactly, nodes taken from the fastest). Nodes
/// below the target keep their mass: the body's bulk moves as before. 0 leaves the model as it is;
/// a fraction that buys nothing (one node fast among many alike) adds nothing. Throws
/// std::invalid_argument for a fraction outside [0, 1], and as max_frequency() does for a body too
/// large for a sparse matrix. Whatever inertia the model had is replaced.
MassScaling add_mass_for_time_step(Model& model, double max_added_fraction);
/// The same from the body's stiffness row sums at rest (stiffness_row_sums(), or for a cut body
/// stiffness_row_sums_after()), which the call above assembles the stiffness for. Throws
/// std::invalid_argument as well when `row_sums` has not one entry per node.
MassScaling add_mass_for_time_step(Model& model, double max_added_fraction, const Eigen::VectorXd& row_sums);

}  // namespace cubespring
