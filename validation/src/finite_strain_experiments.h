// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The finite-strain experiments of run_experiment (experiments.h): uniaxial, simple shear and
// hydrostatic, each a curve of the lattice's nominal stress against the law's closed form, and
// the bonded compression (a curve with no closed form).
#pragma once

#include <vector>

#include "cubespring/constraints.h"
#include "cubespring/static_solver.h"
#include "cubespring/validation/experiments.h"

namespace cubespring {

/// Whether the experiment is one of the curves.
bool is_finite_strain_experiment(Experiment experiment);

/// The curve on the built block; `state` gets its last point's equilibrium, `solver` the sums of
/// the solves' increments, Newton iterations and unstable equilibria. Errors name a failed solve
/// and its load level.
Result<std::vector<CurvePoint>> finite_strain_curve(Experiment experiment, const Model& model,
                                                    const ExperimentSettings& settings, State& state,
                                                    StaticReport& solver);

/// The force [N] along `direction` that holds the nodes of the face at index `at` along
/// face_axis in place: minus the elastic force on them (at an equilibrium, the constraints' reaction).
double face_reaction(const Model& model, const State& state, int face_axis, int at, int direction);

/// Holds the face at coordinate 0 along `axis` against sliding and turning in its plane, as a
/// frictionless support needs: the node at its centre along the other two axes, the node at the
/// end of its row along the first other axis on the second (they take no force when nothing
/// pushes the block sideways or turns it).
Status hold_face_in_plane(const Model& model, const Eigen::Vector3i& cells, int axis, Constraints& constraints);

}  // namespace cubespring
