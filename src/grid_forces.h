// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The internal forces of a body on its dense grid (grid_layout.h): the same springs, correction,
// twist and crushed-cell test as the spring-list passes of forces.cpp, with springs found by index
// arithmetic (docs/data-layout.md, "Dense bodies: the grid passes").
#pragma once

#include <vector>

#include <Eigen/Core>

#include "cubespring/state.h"
#include "grid_layout.h"

namespace cubespring {

/// Threads the grid passes use of `threads` asked: one per 4096 points at most, and one per
/// z-layer (a second thread costs more than it gives on fewer points: cubespring bench).
int grid_threads(const GridLayout& grid, int threads);

/// Spring, correction and twist forces [N] on every node into `forces` (3 x num_nodes), with the
/// springs' and correction's Rayleigh damping when with_rate. No inversion recovery, gravity,
/// loads or mass damping. Returns the number of crushed cells (signed volume below
/// kCrushedVolumeFraction of the rest volume), for the caller to add their recovery.
/// `scratch` keeps the grid's arrays between calls; clear it before using it with another layout
/// (entries the passes never write must stay as first set).
int grid_spring_forces(const GridLayout& grid, const State& state, bool with_rate, int threads,
                       std::vector<double>& scratch, Eigen::Matrix3Xd& forces);

}  // namespace cubespring
