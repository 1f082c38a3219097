// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#pragma once

#include <vector>

#include <Eigen/Core>

#include "cubespring/constraints.h"
#include "cubespring/model.h"
#include "cubespring/result.h"
#include "cubespring/state.h"

/// Units are SI throughout the API: metres, kilograms, seconds, newtons, pascals.
namespace cubespring {

/// A body after some of its cells were taken out at run time (cutting: a cautery tool burns them
/// away, docs/cutting.md). The model is rebuilt from its description without those cells
/// (lattice_desc(), build_model()), so every array, the masses and the springs shared with the
/// removed cells included, is what a body of the remaining cells has from the start; a node no
/// remaining cell uses leaves. Steppers and force engines rebuild themselves from the new
/// model's revision.
struct CellRemoval {
  Model model;
  /// The state carried over: each remaining node keeps its position and velocity, the time is
  /// kept.
  State state;
  /// The constraints carried over (a fixed or driven node stays so while it remains).
  Constraints constraints;
  /// Old node n is node new_node[n] of the new model, or -1: it left with the cells. (Where the
  /// removed cells alone held a node together across split faces, face_split.h, it is one of
  /// the node's copies now: source_node tells them all.)
  std::vector<int> new_node;
  /// New node n was old node source_node[n]. (Where the removed cells alone held a node's
  /// copies apart, the copies are one node again, at their mean weighted by the mass each keeps:
  /// the first of them.)
  std::vector<int> source_node;
  /// Old cell c is cell new_cell[c] of the new model, or -1: removed.
  std::vector<int> new_cell;
  int removed_cells = 0;
  double removed_mass = 0.0;  ///< [kg]: the removed cells' mass, density times volume
  /// The momentum that left with the removed cells [kg m/s]: each took its lumped mass (an
  /// eighth at each corner) at its corners' velocities, so the body's momentum falls by exactly
  /// this, as its mass by removed_mass.
  Eigen::Vector3d removed_momentum{0.0, 0.0, 0.0};
  /// Pieces the remaining cells make, cells sharing a node counted as joined (they move
  /// together): more than 1 when the removal cut the body through. The body keeps its pieces,
  /// each moving on its own.
  int pieces = 0;
};

/// Takes `cells` (indices into model's cells, any order, repeats allowed) out of the body in
/// `state` under `constraints`. The model's added inertia (Model::inertial_mass, selective mass
/// scaling) is not carried: call add_mass_for_time_step() again, and find the stable step again
/// (the nodes by the cut lost mass and stiffness in other proportions than the rest).
/// Errors name a cell index out of range, a state or constraints of another size, or a removal
/// that would leave no cell (remove the body instead).
Result<CellRemoval> remove_cells(const Model& model, const State& state, const Constraints& constraints,
                                 const std::vector<int>& cells);

/// Per-node columns (nodal forces, targets: 3 x old nodes) on the body after the removal (3 x
/// its nodes); the columns of nodes that left are dropped. Empty stays empty.
Eigen::Matrix3Xd carry_node_columns(const CellRemoval& removal, const Eigen::Matrix3Xd& per_node);

}  // namespace cubespring
