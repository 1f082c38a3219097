// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#pragma once

#include "cubespring/model.h"

/// Units are SI throughout the API: metres, kilograms, seconds, newtons, pascals.
namespace cubespring {

/// How the body's highest natural frequency omega_max (the square root of the largest eigenvalue
/// of M^-1 K, the linearised body at rest) is found for the explicit stability limit.
enum class FrequencyBound {
  /// Gershgorin's bound, max over rows of (1/m) sum |K_ij|: rigorous and cheap, but 1.3-1.5 times
  /// above omega_max on box lattices, so the step it allows is that much too short.
  kGershgorin,
  /// omega_max itself, by Lanczos iteration on M^-1/2 K M^-1/2 (its largest Ritz value plus that
  /// value's residual, capped by Gershgorin's bound): within 0.1% of the true value. The step it
  /// allows has no margin for a body deformed stiffer than at rest: multiply by a safety factor.
  /// It does not know what contact and anchors add: the Bullet plugin keeps Gershgorin, since at
  /// 0.9 of this step a block anchored to a light dynamic body blew up in its tests.
  kLanczos,
};

/// The body's highest natural frequency omega_max [rad/s], found as `bound` says. Both bounds
/// assemble the body's stiffness (0.3 s for 64x16x16 cells, 5 s and 1.2 GB for 64^3): find it
/// once per body. Throws std::length_error for a body too large for the matrix's int indices
/// (StiffnessAssembler; check_stiffness_size() in stiffness.h says so first, as a Status).
double max_frequency(const Model& model, FrequencyBound bound = FrequencyBound::kGershgorin);

/// The largest time step [s] at which the explicit integrators stay stable for this body at rest:
/// 2 / omega_max, reduced for stiffness-proportional damping. Fixed nodes are ignored (they only
/// lower omega_max), so the limit holds for any constraints. Throws as max_frequency() does.
double max_stable_time_step(const Model& model, FrequencyBound bound = FrequencyBound::kGershgorin);

/// The fraction of the rest step that stays stable in the state `positions` [m], in (0, 1]. A
/// cell squeezed or sheared thin carries waves across it sooner, so a step stable at rest is not
/// then: a 200 g box dropped onto 5 kPa tissue thinned cells under its edges to a quarter and blew
/// up at 0.9 of the rest step, where at 0.5 it ran. A cell's thickness across each pair of its faces
/// is its volume over the area its other two mean edges span, over its rest size along that axis;
/// cells at least kThickEnough of their rest thickness keep the rest step (the rest step's own
/// margin holds them), thinner ones shrink it in proportion, down to 0.2 of it (five times as many
/// sub-steps: an inverted or flat cell, or one whose volume is not a number, is reported by the
/// step, not followed forever). A cell
/// stretched flat is stiffer across than its thickness says, its stiffness there growing with the
/// area of its faces: a face over twice its rest area divides the thickness by the square root of
/// its area over twice the rest area (a cell 2.6 times as wide each way and a fifth as thick,
/// behind a 1 mm probe dragged through 2.7 mm cells, blew up at the 0.4 its thickness gave). 1 for the
/// springs law (CellLaw::kSprings), whose springs are linear in their length: a thin cell is no
/// stiffer (the default demo, whose probe crushes cells, ran as stable and took twice as long).
double compressed_step_factor(const Model& model, const Eigen::Matrix3Xd& positions);
inline constexpr double kThickEnough = 0.5;

/// Each cell's stable explicit step at rest [s], as the thin-cell factor needs it: the step
/// stable_step_for_frequency() gives the largest Gershgorin bound, (1/m) sum_j |K_ij| over a
/// node's rows, among the nodes of the cell and of the cells around it (those sharing a node with
/// it), with the nodes' mass. A thin cell's nodes move against their neighbours', whose margin
/// the factor counts on too: with the cell's own 8 nodes alone, a 4 mm liver blew up under a
/// probe. Inertia that selective mass scaling added is left out, as the nodes that took it keep
/// no margin beyond the target step. The least of these steps is max_stable_time_step() of the
/// body without added inertia; soft tissue two cells or more away from a stiff inclusion has a
/// longer one, so a cell that a probe squeezes thin there is not held to the inclusion's step.
/// No cell's step is longer than the least of its own tissue's cells with only that tissue
/// around them: Gershgorin's bound is up to 35% looser in a body's middle than at its corners,
/// slack that a thin cell under a probe must not plan on (a drag's force rang on it). Throws as
/// max_frequency() does.
Eigen::VectorXd cell_stable_time_steps(const Model& model);
/// The same from the body's stiffness row sums at rest (stiffness_row_sums(), or for a cut body
/// stiffness_row_sums_after()), without assembling the stiffness. Throws std::invalid_argument
/// when `row_sums` has not one entry per node.
Eigen::VectorXd cell_stable_time_steps(const Model& model, const Eigen::VectorXd& row_sums);

/// The longest step [s] that the cells thinner than kThickEnough allow in the state `positions`
/// [m]: the least over them of each one's factor (as compressed_step_factor() finds it for the
/// thinnest cell; 0.2 for a flat or inverted cell) times its entry of `cell_steps` [s]
/// (cell_stable_time_steps(), times a safety factor). Infinity when no cell is thin, and for the
/// springs law. Throws std::invalid_argument when `cell_steps` does not have one entry per cell.
double compressed_time_step(const Model& model, const Eigen::Matrix3Xd& positions, const Eigen::VectorXd& cell_steps);

}  // namespace cubespring
