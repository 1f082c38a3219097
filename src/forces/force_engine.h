// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The force engine: what the force passes build from a Model to run on it, the blocks the
// spring-list passes hand to threads and, for a body that fills its box, its layout on the
// dense grid. A Model is data; its engine lives in the ForceWorkspace of whoever steps it (the
// Stepper, the static solver, a caller of compute_forces) and is rebuilt when the model's
// revision, its counts, or the grid fill asked for change (docs/architecture.md).
#pragma once

#include <cstdint>
#include <memory>

#include "cubespring/forces.h"
#include "forces/force_blocks.h"
#include "forces/grid/grid_layout.h"

namespace cubespring {

struct ForceEngine {
  std::uint64_t model_revision = 0;
  int num_nodes = 0, num_springs = 0, num_cells = 0;
  ForceBlocks blocks;
  /// Whether the grid was decided, and for which fill (Model::revision and counts as above).
  bool grid_decided = false;
  double min_grid_fill = kDefaultMinGridFill;
  /// The grid passes' layout; null: the spring lists.
  std::shared_ptr<const GridLayout> grid;

  bool made_for(const Model& model) const {
    return model_revision == model.revision && num_nodes == model.num_nodes() && num_springs == model.num_springs() &&
           num_cells == model.num_cells();
  }
};

/// The workspace's engine with its blocks for this model, built when it has none for it (its
/// grid then undecided).
const ForceEngine& engine_blocks(const Model& model, ForceWorkspace& ws);

/// The workspace's engine for this model with the grid decided for min_grid_fill (as
/// ForceOptions::min_grid_fill says).
const ForceEngine& engine_with_grid(const Model& model, double min_grid_fill, ForceWorkspace& ws);

}  // namespace cubespring
