// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "cubespring/model.h"
#include "cubespring/result.h"
#include "cubespring/state.h"

/// Units are SI throughout the API: metres, kilograms, seconds, newtons, pascals.
namespace cubespring {

/// External loads on a body.
struct Loads {
  Eigen::Vector3d gravity{0.0, 0.0, 0.0};  ///< [m/s^2], acts on every node's mass
  Eigen::Matrix3Xd nodal_forces;           ///< (3 x num_nodes) [N], or empty for none
};

/// What compute_forces() includes.
struct ForceOptions {
  bool damping = true;  ///< Rayleigh damping from the velocities
  int threads = 1;      ///< threads for the force passes; the result does not depend on it
  /// The body goes on the grid passes when its cells fill at least this fraction of their
  /// bounding box (0: whenever the lattice allows; above 1, or NaN: never) and on the spring
  /// lists otherwise; both give the same forces to rounding. The grid costs about 280 bytes per
  /// point of the box, however few of them the body holds; a box of more than 2^31 points gets
  /// no grid. Keep it the same between calls on one workspace: a change rebuilds the grid.
  double min_grid_fill = kDefaultMinGridFill;
};

/// Whether compute_forces() with these options puts the model on the grid passes (it builds
/// the grid to find out: for tests and benchmarks, not for a step).
bool uses_grid_passes(const Model& model, const ForceOptions& options = {});

/// How the grid passes share a body's z-layers among threads (src/forces/grid/grid_forces.cpp): threads go in
/// pairs, each pair's region of layers swept by one thread from the bottom and the other from the
/// top, each claiming a layer as it gets to it, so that they meet where their speeds on that call
/// bring them (an odd thread out sweeps a region alone). Between regions, from an even split, a
/// layer at a time moves to the region whose threads took less time. Results do not depend on
/// the split.
struct GridSplit {
  /// each thread's first z-layer of grid points, then the layer count: a pair's first thread
  /// starts its region, the second where the two met on the last call; each thread copies in the
  /// state of its own layers
  std::vector<int> first_layers;
  std::vector<double> seconds;  ///< each region's time (its later thread's) [s], summed over `calls` calls
  int calls = 0;                ///< calls timed since a region's boundary last moved
  /// each pair meets where first_layers says and nothing moves (tests; a split that does not
  /// fit the grid is still made even)
  bool fixed = false;
};

struct ForceEngine;  // internal: src/forces/force_engine.h

/// The force engine of one body and the scratch arrays of its passes, kept between calls so that
/// a step allocates nothing. The engine (the thread blocks, the grid layout) is built from the
/// model on the first call and rebuilt when Model::revision, the model's counts or
/// ForceOptions::min_grid_fill change; one workspace may serve several bodies in turn, at the
/// cost of a rebuild at each change.
struct ForceWorkspace {
  Eigen::Matrix3Xd spring_vector;             ///< x of the second node minus x of the first [m]
  std::vector<double> spring_length;          ///< current length [m]
  std::vector<double> spring_inverse_length;  ///< 1 / length, 0 for a degenerate spring [1/m]
  std::vector<double> spring_rate;            ///< d(length)/dt [m/s]
  std::vector<double> spring_own_tension;     ///< the spring's own tension and damping, no correction [N]
  std::vector<double> spring_tension;         ///< total tension (spring + correction), filled for the stiffness [N]
  Eigen::Matrix3Xd cell_tension;              ///< correction tension on each axis' edges [N]
  std::vector<std::uint8_t> cell_crushed;     ///< 1 where the inversion recovery acts
  std::vector<Eigen::Matrix3Xd> block_halo;  ///< forces of each block's springs and cells on the next block's nodes [N]
  std::vector<int> block_crushed;            ///< crushed cells found by each block
  std::vector<double> block_fastest;         ///< largest squared speed each block gave a node [m^2/s^2]
  std::vector<double> grid_arrays;           ///< arrays of the grid passes (src/forces/grid/grid_forces.h)
  std::vector<int> crushed_corners;          ///< nodes of the crushed cells, when the grid passes kicked
  std::shared_ptr<const void> grid_arrays_layout;  ///< the grid layout grid_arrays belong to
  GridSplit grid_split;                            ///< how the grid passes share the layers among threads
  std::shared_ptr<const ForceEngine> engine;       ///< built from the model by the passes
  void resize(const Model& model);
};

/// Whether the state and the loads fit the model: state.positions and state.velocities with one
/// column per node, loads.nodal_forces with one or none, a finite gravity, and the constants of
/// the model's cell law (set Model::cell_law through LatticeDesc::law). The error names the array
/// and both counts, as the exceptions below do: check here to get it as a Status instead.
Status check_state_and_loads(const Model& model, const State& state, const Loads& loads = {});

/// Total force on every node [N] (3 x num_nodes): springs, correction, inversion recovery,
/// damping, gravity and nodal loads. docs/model-baudet2007.md gives the formulas. Throws
/// std::invalid_argument when state.positions, state.velocities (with damping; without, it may
/// be empty) or loads.nodal_forces (or empty) has not one column per node (a precondition the
/// caller checks with check_state_and_loads(), like std::vector::at's index: result.h).
void compute_forces(const Model& model, const State& state, const Loads& loads, const ForceOptions& options,
                    ForceWorkspace& workspace, Eigen::Matrix3Xd& forces);

/// The energies throw std::invalid_argument, as compute_forces() does, for arrays without one
/// column per node.
/// Internal elastic energy [J]: springs, correction and inversion recovery.
double elastic_energy(const Model& model, const Eigen::Matrix3Xd& positions);
/// Elastic energy minus the work of gravity and nodal loads from the rest state [J].
double potential_energy(const Model& model, const Loads& loads, const Eigen::Matrix3Xd& positions);
/// 1/2 sum m v^2 [J].
double kinetic_energy(const Model& model, const State& state);

/// Signed volume [m^3] of the parallelepiped spanned by a cell's mean edge vectors; the rest
/// volume for an undeformed cell, negative for a cell turned inside out.
double cell_signed_volume(const Model& model, const Eigen::Matrix3Xd& positions, int cell);

/// A cell counts as crushed, and its inversion recovery acts, when its signed volume falls below
/// this fraction of its rest volume (docs/model-baudet2007.md section 5).
inline constexpr double kCrushedVolumeFraction = 0.2;

}  // namespace cubespring
