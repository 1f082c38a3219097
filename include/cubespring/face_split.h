// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#pragma once

#include <vector>

#include <Eigen/Core>

#include "cubespring/constraints.h"
#include "cubespring/lattice.h"
#include "cubespring/model.h"
#include "cubespring/result.h"
#include "cubespring/state.h"

/// Units are SI throughout the API: metres, kilograms, seconds, newtons, pascals.
namespace cubespring {

/// A body after faces between its cells were split at run time (cutting: a blade separates the
/// tissue it sweeps through, docs/cutting.md). Nothing leaves: every cell stays with its mass;
/// a node that the split faces part is duplicated, one copy for each side, each taking the mass
/// of the cells on its side, so that the two sides no longer share it (LatticeDesc::split_faces
/// says which nodes are shared). The model is built again from its description with the faces
/// added (build_model()), so every array is what a body of those cells and splits has from the
/// start. Steppers and force engines rebuild themselves from the new model's revision; a body
/// with split faces steps on the spring lists (the grid passes hold one node a grid point).
struct FaceSplit {
  Model model;
  /// The state carried over: each copy of a node has its position and velocity, so the body's
  /// momentum is unchanged (the copies' masses sum to the node's). The time is kept.
  State state;
  /// The constraints carried over: every copy of a driven node is driven as it was.
  Constraints constraints;
  /// New node n was old node source_node[n] (several new nodes where a node was duplicated).
  std::vector<int> source_node;
  /// The faces split by this call (faces already split, or listed twice, count once).
  int faces_split = 0;
  /// Nodes it added (copies).
  int nodes_added = 0;
  /// Pieces the body is in after the split (cells sharing a node counted as joined); more than
  /// before where the split cut it through.
  int pieces = 0;
};

/// Splits `faces` (each the face between cell `cell` and the cell after it along `axis`, both
/// cells of the body) of the body in `state` under `constraints`. The cells keep their indices:
/// the cells are the same. Errors name a face with an axis out of 0-2 or a side that is not a
/// cell of the body, or a state or constraints of another size.
Result<FaceSplit> split_faces(const Model& model, const State& state, const Constraints& constraints,
                              const std::vector<CellFace>& faces);

/// Nodal forces [N] (3 x old nodes) on the body after the split (3 x its nodes): a node's force
/// shared between its copies in proportion to their mass, so that the total, and each side's
/// share of a load spread by mass, is kept. Empty stays empty.
Eigen::Matrix3Xd carry_node_forces(const FaceSplit& split, const Eigen::Matrix3Xd& forces);

}  // namespace cubespring
