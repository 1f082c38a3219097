// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The internal forces of a body on its dense grid (grid_layout.h): the same springs, correction,
// twist, neo-Hookean cell term and crushed-cell test as the spring-list passes of forces.cpp, with
// springs found by index arithmetic (docs/data-layout.md, "Dense bodies: the grid passes").
#pragma once

#include <vector>

#include <Eigen/Core>

#include "cubespring/forces.h"
#include "cubespring/state.h"
#include "forces/grid/grid_kick.h"
#include "forces/grid/grid_layout.h"

namespace cubespring {

/// Threads the grid passes use of `threads` asked: one per 1024 points at most, one per z-layer
/// of cells, and 64 at most (a second thread costs more than it gives on fewer points: cubespring
/// bench).
int grid_threads(const GridLayout& grid, int threads);

/// What grid_spring_forces() did.
struct GridForces {
  int crushed = 0;          ///< cells with signed volume below kCrushedVolumeFraction of the rest volume
  double fastest_sq = 0.0;  ///< with a kick: the largest squared speed [m^2/s^2], NaN if not finite
};

/// Spring, correction, twist and neo-Hookean forces [N] on every node into `forces` (3 x
/// num_nodes), with the springs' and correction's Rayleigh damping when with_rate. No inversion
/// recovery (a neo-Hookean body has none: its crushed count is 0). When `kick`
/// is given, the forces also get the loads and mass damping and every node its kick
/// (grid_kick.h); when cells are crushed, the caller then redoes the nodes of those cells, whose
/// spring forces grid_spring_force() gives, with their recovery. `scratch` keeps the grid's
/// arrays between calls; clear it before using it with another layout (entries the passes never
/// write must stay as first set). `split` shares the layers among the threads (GridSplit: a split
/// that gives each region a layer of points and each pair's meeting point inside its region is
/// used as it is, another is made even); unless it is fixed, it records where each pair met and
/// its regions are balanced by their threads' times.
GridForces grid_spring_forces(const GridLayout& grid, const State& state, bool with_rate, int threads,
                              std::vector<double>& scratch, GridSplit& split, Eigen::Matrix3Xd& forces,
                              const GridKick* kick = nullptr);

/// The spring, correction and twist force [N] on `node` that the last grid_spring_forces() with
/// this scratch found.
Eigen::Vector3d grid_spring_force(const GridLayout& grid, const std::vector<double>& scratch, int node);

}  // namespace cubespring
