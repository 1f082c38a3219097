// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#pragma once

#include <optional>

#include "cubespring/validation/calculix_result.h"
#include "cubespring/validation/experiments.h"

/// Units are SI throughout the API: metres, kilograms, seconds, newtons, pascals.
namespace cubespring {

/// A cantilever's lattice against a finite-element solution of the same beam, node by node where
/// the reference has a node at a lattice node's rest position (within a thousandth of a cell).
struct FemComparison {
  int lattice_nodes = 0;
  int matched_nodes = 0;  ///< lattice nodes that have a reference node
  /// The reference's mean z displacement over the lattice's nodes of face x = L [m], the same
  /// nodes as ExperimentResult::tip_deflection; empty unless all of them matched.
  std::optional<double> reference_tip_deflection;
  std::optional<double> tip_error;  ///< lattice tip / reference tip - 1
  /// Over the matched nodes, |u - u_reference| relative to |reference tip deflection|: the
  /// figures of the README's validation table. Empty without a reference tip.
  std::optional<double> mean_nodal_error;
  std::optional<double> max_nodal_error;
};

/// Compares a cantilever experiment's equilibrium with `reference`. Other experiments and
/// references that share no node with the lattice give matched_nodes = 0 and no figures.
FemComparison compare_cantilever_with_fem(const ExperimentResult& cantilever, const FemSolution& reference);

}  // namespace cubespring
