// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Internal forces of the cube lattice, in passes over flat arrays (docs/model-baudet2007.md,
// docs/data-layout.md):
//   1. springs: current vector, length, 1/length, length rate and the spring's own tension, in
//               tiles whose square roots and divisions run two springs per SIMD instruction;
//   2. cells:   mean edge strains -> correction tension per axis (section 3); signed volume from
//               the body diagonals -> crushed-cell flag (section 5); twist forces (exact bending)
//               straight onto the cell's corners;
//   3. crushed cells: inversion recovery;
//   4. springs: total tension -> force on both ends, walking the springs grouped by their first
//               node (they are sorted so): that node's sum stays in registers, the second node
//               gets one scattered write. A node whose force is then complete gets its damping
//               and loads at once, and the explicit step moves it (still in cache).
// The springs are cut into blocks of consecutive first nodes (force_blocks.h), the cells with them
// (by their corner 0). A block's springs and cells that reach into the next block write to a halo
// of their own, added once every block is done; the blocks depend on the body alone, so the sums,
// and the results, do not depend on the thread count.
#include "cubespring/forces.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

#include "forces/correction_tension.h"
#include "forces/drive_nodes.h"
#include "forces/force_engine.h"
#include "forces/force_passes.h"
#include "forces/grid/grid_forces.h"
#include "forces/input_checks.h"
#include "forces/kick_drift.h"
#include "forces/twist.h"
#include "model/cell_geometry.h"
#include "model/neo_hookean_cell.h"
#include "thread_shares.h"

namespace cubespring {
namespace {

// Pass 1 for spring s alone (the tail of a block).
template <bool kWithRate>
inline void measure_spring(const Model& model, const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v, int s,
                           ForceWorkspace& ws) {
  const int i = model.spring_nodes[s][0];
  const int j = model.spring_nodes[s][1];
  const Eigen::Vector3d d = x.col(j) - x.col(i);
  ws.spring_vector.col(s) = d;
  const double length = d.norm();
  const double rest = model.spring_rest_length[s];
  ws.spring_length[s] = length;
  const double inverse = length > kDegenerateLengthFraction * rest ? 1.0 / length : 0.0;
  ws.spring_inverse_length[s] = inverse;
  double own = model.spring_stiffness[s] * (length - rest);
  if constexpr (kWithRate) {
    const double rate = (v.col(j) - v.col(i)).dot(d) * inverse;
    ws.spring_rate[s] = rate;
    own += model.spring_damping[s] * rate;
  }
  ws.spring_own_tension[s] = own;
}

// Springs per tile of pass 1: the tile's gathers fill a small array, then its square roots and
// divisions run as whole arrays, two springs per SIMD instruction (Eigen's packets); one spring
// at a time the divider is the bottleneck.
constexpr int kTileSprings = 32;
using Tile = Eigen::Array<double, kTileSprings, 1>;
using TileMap = Eigen::Map<Tile>;
using ConstTileMap = Eigen::Map<const Tile>;

// Pass 1 over springs [begin, end): the same values as measure_spring, by tiles.
template <bool kWithRate>
void measure_springs(const Model& model, const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v, int begin, int end,
                     ForceWorkspace& ws) {
  constexpr double kDegenerateSq = kDegenerateLengthFraction * kDegenerateLengthFraction;
  int tile = begin;
  for (; tile + kTileSprings <= end; tile += kTileSprings) {
    Tile length_sq;
    bool degenerate = false;
    for (int k = 0; k < kTileSprings; ++k) {
      const int s = tile + k;
      const int i = model.spring_nodes[s][0];
      const int j = model.spring_nodes[s][1];
      const Eigen::Vector3d d = x.col(j) - x.col(i);
      ws.spring_vector.col(s) = d;
      length_sq[k] = d.squaredNorm();
      const double rest = model.spring_rest_length[s];
      degenerate |= length_sq[k] <= kDegenerateSq * rest * rest;
      if constexpr (kWithRate) ws.spring_rate[s] = (v.col(j) - v.col(i)).dot(d);  // times 1/length below
    }
    if (degenerate) {  // rare: the spring-by-spring path handles the zero lengths
      for (int s = tile; s < tile + kTileSprings; ++s) measure_spring<kWithRate>(model, x, v, s, ws);
      continue;
    }
    const Tile length = length_sq.sqrt();
    const Tile inverse = length.inverse();
    TileMap(ws.spring_length.data() + tile) = length;
    TileMap(ws.spring_inverse_length.data() + tile) = inverse;
    Tile own = ConstTileMap(model.spring_stiffness.data() + tile) *
               (length - ConstTileMap(model.spring_rest_length.data() + tile));
    if constexpr (kWithRate) {
      const Tile rate = TileMap(ws.spring_rate.data() + tile) * inverse;
      TileMap(ws.spring_rate.data() + tile) = rate;
      own += ConstTileMap(model.spring_damping.data() + tile) * rate;
    }
    TileMap(ws.spring_own_tension.data() + tile) = own;
  }
  for (int s = tile; s < end; ++s) measure_spring<kWithRate>(model, x, v, s, ws);
}

// Where the cell pass puts forces on a cell's corners (the twist of exact bending, the
// neo-Hookean term): the forces of the block whose nodes end at `block_end`, and its halo past it.
// A cell goes with the block of its corner 0. Node numbers rise along every grid axis, so corner
// 7 has the cell's highest number, and the cell's 0-7 diagonal is a spring of corner 0: every
// corner lies in the block or within its halo.
struct CornerTarget {
  Eigen::Matrix3Xd& forces;
  Eigen::Matrix3Xd& halo;
  int block_end;
};

inline void add_corner_forces(const Model& model, int c, const std::array<Eigen::Vector3d, kCornersPerCell>& f,
                              const CornerTarget& target) {
  for (int corner = 0; corner < kCornersPerCell; ++corner) {
    const int j = model.cell_nodes[c][corner];
    if (j < target.block_end) {
      target.forces.col(j) += f[corner];
    } else {
      target.halo.col(j - target.block_end) += f[corner];
    }
  }
}

// The twist forces of cell c on its corners.
inline void add_twist_forces(const Model& model, int c, const ForceWorkspace& ws, const CornerTarget& target) {
  std::array<Eigen::Vector3d, kEdgesPerCell> edge_vectors;
  for (int e = 0; e < kEdgesPerCell; ++e) edge_vectors[e] = ws.spring_vector.col(model.cell_edges[c][e]);
  add_corner_forces(model, c, twist_corner_forces(edge_vectors, model.cell_size.x(), model.cell_twist_stiffness[c]),
                    target);
}

// Diagonal k's spring runs from corner k unless corner 7 - k comes first in node order
// (Model::major_axis): then its vector is the negative of corner 7 - k minus corner k.
struct DiagonalSigns {
  double sign[4];
  explicit DiagonalSigns(const Model& model) {
    for (int k = 0; k < 4; ++k) sign[k] = (k >> model.major_axis) & 1 ? -1.0 : 1.0;
  }
};

// The mean edge vectors of cell c from its diagonals (pass 1's vectors):
// sum_k s_a(k) x_k = sum over diagonals c -> 7-c of s_a(7-c) (x_{7-c} - x_c).
inline CellFrame frame_from_diagonals(const Model& model, const ForceWorkspace& ws, const DiagonalSigns& signs, int c) {
  const std::array<int, 4>& diagonals = model.cell_diagonals[c];
  const Eigen::Vector3d d0 = signs.sign[0] * ws.spring_vector.col(diagonals[0]);
  const Eigen::Vector3d d1 = signs.sign[1] * ws.spring_vector.col(diagonals[1]);
  const Eigen::Vector3d d2 = signs.sign[2] * ws.spring_vector.col(diagonals[2]);
  const Eigen::Vector3d d3 = signs.sign[3] * ws.spring_vector.col(diagonals[3]);
  // s_a(7 - k) for k = 0..3: x: + - + -, y: + + - -, z: + + + +
  CellFrame frame;
  frame.edge[0] = 0.25 * ((d0 - d1) + (d2 - d3));
  frame.edge[1] = 0.25 * ((d0 + d1) - (d2 + d3));
  frame.edge[2] = 0.25 * ((d0 + d1) + (d2 + d3));
  return frame;
}

// The correction tensions of cell c on its edges along each axis (correction_tension.h) from the
// lengths (and, with_rate, the length rates) pass 1 measured.
void cell_correction_tensions(const Model& model, bool with_rate, int c, ForceWorkspace& ws) {
  const Eigen::Vector3d& size = model.cell_size;
  const Eigen::Array3d inverse_edge_sum = (kEdgesPerAxis * size.array()).inverse();
  const Eigen::Array3d tension_per_stress = size.prod() * inverse_edge_sum;
  const std::array<int, kEdgesPerCell>& edges = model.cell_edges[c];
  const double beta = with_rate ? model.materials[model.cell_material[c]].stiffness_damping : 0.0;
  double strain[3];
  for (int axis = 0; axis < 3; ++axis) {
    const int* e = edges.data() + axis * kEdgesPerAxis;
    const double length_sum =
        (ws.spring_length[e[0]] + ws.spring_length[e[1]]) + (ws.spring_length[e[2]] + ws.spring_length[e[3]]);
    strain[axis] = mean_edge_strain(length_sum, inverse_edge_sum[axis]);
    if (with_rate) {
      const double rate_sum =
          (ws.spring_rate[e[0]] + ws.spring_rate[e[1]]) + (ws.spring_rate[e[2]] + ws.spring_rate[e[3]]);
      strain[axis] = damped_edge_strain(strain[axis], beta, rate_sum, inverse_edge_sum[axis]);
    }
  }
  const Eigen::Matrix3d& d = model.cell_correction[c];
  for (int axis = 0; axis < 3; ++axis) {
    ws.cell_tension(axis, c) = correction_tension(tension_per_stress[axis], d(axis, 0), d(axis, 1), d(axis, 2),
                                                  strain[0], strain[1], strain[2]);
  }
}

// Pass 2 over cells [begin, end): the correction tensions, and the crushed flag from the signed
// volume of the mean edge vectors, which the diagonals give. With a corner target, also the
// twist forces (exact bending). Returns the number of crushed cells.
int cell_pass(const Model& model, bool with_rate, int begin, int end, ForceWorkspace& ws,
              const CornerTarget* twist = nullptr) {
  const double crushed_volume = kCrushedVolumeFraction * model.cell_size.prod();
  const DiagonalSigns signs(model);
  int crushed = 0;
  for (int c = begin; c < end; ++c) {
    cell_correction_tensions(model, with_rate, c, ws);

    const bool is_crushed = frame_from_diagonals(model, ws, signs, c).volume() < crushed_volume;
    ws.cell_crushed[c] = is_crushed;
    crushed += is_crushed;

    if (twist != nullptr && model.cell_twist_stiffness[c] != 0.0) add_twist_forces(model, c, ws, *twist);
  }
  return crushed;
}

// Pass 2 of a neo-Hookean body (Model::cell_law) over cells [begin, end): the correction tension
// of the edges' share of the term (neo_hookean_edge_correction; no damping: the law adds none)
// and no crushed cells (the law's barrier replaces the inversion recovery); with a target, the
// cell term's forces and the twist's go straight onto the corners. Returns 0 crushed cells.
int neo_hookean_cell_pass(const Model& model, int begin, int end, ForceWorkspace& ws, const CornerTarget* target) {
  const DiagonalSigns signs(model);
  for (int c = begin; c < end; ++c) {
    cell_correction_tensions(model, false, c, ws);
    ws.cell_crushed[c] = 0;
    if (target == nullptr) continue;
    MeanEdgeGradient gradient;
    (void)neo_hookean_cell_energy(model.law_constants[model.cell_material[c]],
                                  frame_from_diagonals(model, ws, signs, c), &gradient);
    add_corner_forces(model, c, corner_forces(gradient), *target);
    if (model.cell_twist_stiffness[c] != 0.0) add_twist_forces(model, c, ws, *target);
  }
  return 0;
}

// Pass 2 of either law.
int any_cell_pass(const Model& model, bool with_rate, int begin, int end, ForceWorkspace& ws,
                  const CornerTarget* target) {
  if (model.cell_law == CellLaw::kNeoHookean) return neo_hookean_cell_pass(model, begin, end, ws, target);
  return cell_pass(model, with_rate, begin, end, ws, target);
}

// Total tension of spring s: its own (pass 1) plus the correction of each cell it is an edge of.
inline double spring_tension(const Model& model, const ForceWorkspace& ws, int s) {
  double tension = ws.spring_own_tension[s];
  const double* cell_tension = ws.cell_tension.data();
  for (int e = model.spring_cell_offset[s]; e < model.spring_cell_offset[s + 1]; ++e) {
    tension += cell_tension[model.spring_cell_tension[e]];
  }
  return tension;
}

// Force on spring_nodes[s][0]; the other end gets its negative.
inline Eigen::Vector3d spring_force(const Model& model, const ForceWorkspace& ws, int s) {
  return (spring_tension(model, ws, s) * ws.spring_inverse_length[s]) * ws.spring_vector.col(s);
}

// The first cell whose lowest corner (corner 0) is node n or after it: cells are in grid order,
// so their corner 0 nodes rise with the cell index.
inline int first_cell_from_node(const Model& model, int n) {
  const auto after =
      std::partition_point(model.cell_nodes.begin(), model.cell_nodes.end(),
                           [n](const std::array<int, kCornersPerCell>& corners) { return corners[0] < n; });
  return static_cast<int>(after - model.cell_nodes.begin());
}

// Pass 4 over block b: scatters its springs' forces; each node past the previous block's halo is
// complete once its own springs are done, and goes to finish(n), which returns a squared speed.
template <typename Finish>
double scatter_block(const Model& model, int b, ForceWorkspace& ws, Eigen::Matrix3Xd& forces, const Finish& finish) {
  const ForceBlocks& blocks = ws.engine->blocks;
  const int begin = blocks.begin(b);
  const int end = blocks.end(b);
  const int settled = b > 0 ? blocks.reach_of(b - 1) : begin;
  Eigen::Matrix3Xd& halo = ws.block_halo[b];
  double fastest_sq = 0.0;
  for (int n = begin; n < end; ++n) {
    Eigen::Vector3d first_node_sum = Eigen::Vector3d::Zero();
    for (int s = model.node_first_spring[n]; s < model.node_first_spring[n + 1]; ++s) {
      const Eigen::Vector3d f = spring_force(model, ws, s);
      first_node_sum += f;
      const int j = model.spring_nodes[s][1];
      if (j < end) {
        forces.col(j) -= f;
      } else {
        halo.col(j - end) -= f;
      }
    }
    forces.col(n) += first_node_sum;
    if (n >= settled) fastest_sq = faster(finish(n), fastest_sq);
  }
  return fastest_sq;
}

// The nodes of block b that the previous block's springs reach: their halo, then finish(n).
template <typename Finish>
double settle_halo(int b, const ForceWorkspace& ws, Eigen::Matrix3Xd& forces, const Finish& finish) {
  const ForceBlocks& blocks = ws.engine->blocks;
  if (b == 0) return 0.0;
  const int begin = blocks.begin(b);
  const int reach = blocks.reach_of(b - 1);
  const Eigen::Matrix3Xd& halo = ws.block_halo[b - 1];
  double fastest_sq = 0.0;
  for (int n = begin; n < reach; ++n) {
    forces.col(n) += halo.col(n - begin);
    fastest_sq = faster(finish(n), fastest_sq);
  }
  return fastest_sq;
}

void apply_inversion_forces(const Model& model, const Eigen::Matrix3Xd& x, const ForceWorkspace& ws,
                            Eigen::Matrix3Xd& forces) {
  const double rest_volume = model.rest_cell_volume();
  for (int c = 0; c < model.num_cells(); ++c) {
    if (!ws.cell_crushed[c]) continue;
    const CellFrame frame = cell_frame(model, x, c);
    const double ratio = frame.volume() / rest_volume;
    const double scale = -model.cell_inversion_stiffness[c] * (ratio - kCrushedVolumeFraction);
    const auto gradient = frame.volume_gradient();
    for (int corner = 0; corner < kCornersPerCell; ++corner) {
      forces.col(model.cell_nodes[c][corner]) += scale * gradient[corner];
    }
  }
}

void prepare(const Model& model, ForceWorkspace& ws, Eigen::Matrix3Xd& forces) {
  const ForceBlocks& split = engine_blocks(model, ws).blocks;  // resize keeps this engine
  const int blocks = split.count();
  if (ws.spring_vector.cols() != model.num_springs() || ws.cell_tension.cols() != model.num_cells() ||
      static_cast<int>(ws.block_halo.size()) != blocks) {
    ws.resize(model);
  }
  for (int b = 0; b < blocks; ++b) {
    const Eigen::Index halo = std::max(0, split.reach_of(b) - split.end(b));
    if (ws.block_halo[b].cols() != halo) ws.block_halo[b].resize(3, halo);
  }
  if (forces.cols() != model.num_nodes()) forces.resize(3, model.num_nodes());
}

// The blocks [begin, end) of one thread's share of the passes; barrier() waits for every share
// (nothing when one thread runs them all). Every thread finds the same crushed count, so all or
// none wait at the inversion recovery's barrier.
template <bool kWithCornerForces, typename Finish, typename Barrier>
void run_block_passes(const Model& model, const State& state, bool with_rate, int begin_block, int end_block,
                      bool first_share, const Barrier& barrier, ForceWorkspace& ws, Eigen::Matrix3Xd& forces,
                      const Finish& finish) {
  const ForceBlocks& blocks = ws.engine->blocks;
  for (int b = begin_block; b < end_block; ++b) {
    const int begin = blocks.begin(b);
    const int end = blocks.end(b);
    forces.middleCols(begin, end - begin).setZero();
    ws.block_halo[b].setZero();
    const int first = model.node_first_spring[begin];
    const int last = model.node_first_spring[end];
    if (with_rate) {
      measure_springs<true>(model, state.positions, state.velocities, first, last, ws);
    } else {
      measure_springs<false>(model, state.positions, state.positions, first, last, ws);
    }
  }
  barrier();
  for (int b = begin_block; b < end_block; ++b) {
    // the cells whose corner 0 is in the block, so that their corner forces stay in its nodes
    const int first_cell = first_cell_from_node(model, blocks.begin(b));
    const int last_cell = first_cell_from_node(model, blocks.end(b));
    const CornerTarget target{forces, ws.block_halo[b], blocks.end(b)};
    ws.block_crushed[b] =
        any_cell_pass(model, with_rate, first_cell, last_cell, ws, kWithCornerForces ? &target : nullptr);
  }
  barrier();
  int crushed = 0;
  for (int b = 0; b < blocks.count(); ++b) crushed += ws.block_crushed[b];
  if (crushed > 0) {
    if (first_share) apply_inversion_forces(model, state.positions, ws, forces);
    barrier();
  }
  for (int b = begin_block; b < end_block; ++b) ws.block_fastest[b] = scatter_block(model, b, ws, forces, finish);
  barrier();
  for (int b = begin_block; b < end_block; ++b) {
    ws.block_fastest[b] = faster(settle_halo(b, ws, forces, finish), ws.block_fastest[b]);
  }
}

// The passes, the blocks shared among threads (each a contiguous part, as a static schedule
// would); finish(n) is called once for every node, after its force. Returns the largest value
// finish gave (NaN wins).
template <bool kWithCornerForces, typename Finish>
double run_passes(const Model& model, const State& state, const ForceOptions& options, ForceWorkspace& ws,
                  Eigen::Matrix3Xd& forces, const Finish& finish) {
  prepare(model, ws, forces);
  const int blocks = ws.engine->blocks.count();
  const bool with_rate = options.damping && model.has_stiffness_damping;
  const int threads = std::max(1, std::min(options.threads, blocks));
  run_shares(threads, [&](int share, int shares, const auto& barrier) {
    run_block_passes<kWithCornerForces>(model, state, with_rate, blocks * share / shares, blocks * (share + 1) / shares,
                                        share == 0, barrier, ws, forces, finish);
  });
  double fastest_sq = 0.0;
  for (int b = 0; b < blocks; ++b) fastest_sq = faster(ws.block_fastest[b], fastest_sq);
  return fastest_sq;
}

// Damping and loads of node n, the last terms of its force.
struct NodeLoads {
  const Model& model;
  const State& state;
  const Loads& loads;
  bool with_mass_damping, with_nodal;

  NodeLoads(const Model& m, const State& s, const Loads& l, const ForceOptions& options)
      : model(m),
        state(s),
        loads(l),
        with_mass_damping(options.damping && m.has_mass_damping),
        with_nodal(l.nodal_forces.cols() == m.num_nodes()) {}

  void add(int n, Eigen::Matrix3Xd& forces) const {
    for (int axis = 0; axis < 3; ++axis) {
      forces(axis, n) =
          with_node_loads(forces(axis, n), with_mass_damping, with_mass_damping ? model.mass_damping[n] : 0.0,
                          with_mass_damping ? state.velocities(axis, n) : 0.0, model.mass[n], loads.gravity[axis],
                          with_nodal, with_nodal ? loads.nodal_forces(axis, n) : 0.0);
    }
  }
};

// Node n's kick-drift with its complete force (kick_drift.h), into `to` unless it is null.
// Returns its squared speed [m^2/s^2], NaN if a new position is not finite.
double kick_node(const Model& model, const Eigen::Matrix3Xd& forces, const KickDrift& kick, int n, State* to) {
  const State& from = *kick.from;
  const double rate = kick.kick / model.inertia()[n];
  double speed_sq = 0.0;
  bool finite = true;
  for (int axis = 0; axis < 3; ++axis) {
    const KickedCoordinate kicked =
        kick_and_drift(from.velocities(axis, n), from.positions(axis, n), rate, kick.drift, forces(axis, n));
    if (to != nullptr) {
      to->velocities(axis, n) = kicked.velocity;
      to->positions(axis, n) = kicked.position;
    }
    speed_sq += kicked.velocity * kicked.velocity;
    finite = finite && std::isfinite(kicked.position);
  }
  return finite ? speed_sq : std::numeric_limits<double>::quiet_NaN();
}

// Which cells are crushed (ws.cell_crushed), when some are.
void find_crushed_cells(const Model& model, const State& state, ForceWorkspace& ws) {
  const double crushed_volume = kCrushedVolumeFraction * model.rest_cell_volume();
  for (int c = 0; c < model.num_cells(); ++c) {
    ws.cell_crushed[c] = cell_signed_volume(model, state.positions, c) < crushed_volume;
  }
}

// What finish(n) of compute_forces_and_kick returned for every node, from the forces its kick
// used (a driven node's kicked velocity is gone from `to`): the largest squared speed, NaN if a
// kicked position or a driven velocity is not finite.
double fastest_after_kick(const Model& model, const Eigen::Matrix3Xd& forces, const KickDrift& kick) {
  const std::uint8_t* driven = kick.driven != nullptr ? kick.driven->driven_flags() : nullptr;
  double fastest_sq = 0.0;
  for (int n = 0; n < model.num_nodes(); ++n) {
    double speed_sq = kick_node(model, forces, kick, n, nullptr);
    if (driven != nullptr && driven[n] != 0 && !kick.to->velocities.col(n).allFinite()) {
      speed_sq = std::numeric_limits<double>::quiet_NaN();
    }
    fastest_sq = faster(speed_sq, fastest_sq);
  }
  return fastest_sq;
}

// The grid passes kicked every node without the recovery of the crushed cells: the corners of
// those cells get their spring forces back, the recovery and finish(n) again; every other node's
// kick is the one finish would give (its force has no recovery term).
template <typename Finish>
double redo_crushed_corners(const Model& model, const State& state, ForceWorkspace& ws, Eigen::Matrix3Xd& forces,
                            const Finish& finish, const KickDrift& kick) {
  find_crushed_cells(model, state, ws);
  std::vector<int>& corners = ws.crushed_corners;
  corners.clear();
  for (int c = 0; c < model.num_cells(); ++c) {
    if (!ws.cell_crushed[c]) continue;
    corners.insert(corners.end(), model.cell_nodes[c].begin(), model.cell_nodes[c].end());
  }
  std::sort(corners.begin(), corners.end());
  corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
  for (int n : corners) forces.col(n) = grid_spring_force(*ws.engine->grid, ws.grid_arrays, n);
  apply_inversion_forces(model, state.positions, ws, forces);
  for (int n : corners) (void)finish(n);
  return fastest_after_kick(model, forces, kick);
}

// The forces of a body on its dense grid (grid_forces.h). With `kick` (finish's kick), the grid
// passes kick every node themselves and only the crushed cells' corners are redone; without,
// the inversion recovery and finish(n) of every node follow, the nodes cut into the force
// blocks. Returns what run_passes does.
template <typename Finish>
double grid_passes(const Model& model, const State& state, const ForceOptions& options, ForceWorkspace& ws,
                   Eigen::Matrix3Xd& forces, const Finish& finish, const GridKick* kick) {
  prepare(model, ws, forces);
  if (ws.grid_arrays_layout != ws.engine->grid) {  // another body's arrays: start afresh
    ws.grid_arrays.clear();
    ws.grid_split = GridSplit{};
    ws.grid_arrays_layout = ws.engine->grid;
  }
  const bool with_rate = options.damping && model.has_stiffness_damping;
  const GridForces grid = grid_spring_forces(*ws.engine->grid, state, with_rate, options.threads, ws.grid_arrays,
                                             ws.grid_split, forces, kick);
  if (kick != nullptr) {
    if (grid.crushed == 0) return grid.fastest_sq;
    return redo_crushed_corners(model, state, ws, forces, finish, kick->kick);
  }
  if (grid.crushed > 0) {
    find_crushed_cells(model, state, ws);
    apply_inversion_forces(model, state.positions, ws, forces);
  }
  const ForceBlocks& split = ws.engine->blocks;
  const int blocks = split.count();
  const int threads = std::min(grid_threads(*ws.engine->grid, options.threads), blocks);
  const auto finish_block = [&](int b) {
    double fastest_sq = 0.0;
    for (int n = split.begin(b); n < split.end(b); ++n) {
      fastest_sq = faster(finish(n), fastest_sq);
    }
    ws.block_fastest[b] = fastest_sq;
  };
  run_shares(threads, [&](int share, int shares, const auto&) {
    for (int b = blocks * share / shares; b < blocks * (share + 1) / shares; ++b) finish_block(b);
  });
  double fastest_sq = 0.0;
  for (int b = 0; b < blocks; ++b) fastest_sq = faster(ws.block_fastest[b], fastest_sq);
  return fastest_sq;
}

template <typename Finish>
double force_sweep(const Model& model, const State& state, const ForceOptions& options, ForceWorkspace& ws,
                   Eigen::Matrix3Xd& forces, const Finish& finish, const GridKick* kick = nullptr) {
  if (engine_with_grid(model, options.min_grid_fill, ws).grid) {
    return grid_passes(model, state, options, ws, forces, finish, kick);
  }
  const bool corner_forces = model.has_twist || model.cell_law == CellLaw::kNeoHookean;
  return corner_forces ? run_passes<true>(model, state, options, ws, forces, finish)
                       : run_passes<false>(model, state, options, ws, forces, finish);
}

}  // namespace

void measure_tensions(const Model& model, const Eigen::Matrix3Xd& x, ForceWorkspace& ws) {
  ws.resize(model);
  measure_springs<false>(model, x, x, 0, model.num_springs(), ws);
  (void)any_cell_pass(model, false, 0, model.num_cells(), ws, nullptr);
  for (int s = 0; s < model.num_springs(); ++s) ws.spring_tension[s] = spring_tension(model, ws, s);
}

void ForceWorkspace::resize(const Model& model) {
  const ForceEngine& own = engine_blocks(model, *this);
  const auto num_springs = static_cast<std::size_t>(model.num_springs());
  spring_vector.resize(3, model.num_springs());
  spring_length.resize(num_springs);
  spring_inverse_length.resize(num_springs);
  spring_rate.resize(num_springs);
  spring_own_tension.resize(num_springs);
  spring_tension.resize(num_springs);
  cell_tension.resize(3, model.num_cells());
  cell_crushed.resize(model.num_cells());
  const auto blocks = static_cast<std::size_t>(own.blocks.count());
  block_halo.resize(blocks);
  block_crushed.resize(blocks);
  block_fastest.resize(blocks);
}

void compute_forces(const Model& model, const State& state, const Loads& loads, const ForceOptions& options,
                    ForceWorkspace& ws, Eigen::Matrix3Xd& forces) {
  std::string error = node_columns_error(model, state.positions, "state.positions");
  if (error.empty()) error = node_columns_error(model, state.velocities, "state.velocities", !options.damping);
  if (error.empty()) error = node_columns_error(model, loads.nodal_forces, "loads.nodal_forces", true);
  if (error.empty()) error = gravity_error(loads);
  if (!error.empty()) throw std::invalid_argument("compute_forces: " + error);
  require_law_constants(model, "compute_forces");
  const NodeLoads node_loads(model, state, loads, options);
  (void)force_sweep(model, state, options, ws, forces, [&](int n) {
    node_loads.add(n, forces);
    return 0.0;
  });
}

double compute_forces_and_kick(const Model& model, const State& state, const Loads& loads, const ForceOptions& options,
                               ForceWorkspace& ws, Eigen::Matrix3Xd& forces, const KickDrift& kick) {
  const NodeLoads node_loads(model, state, loads, options);
  State& to = *kick.to;
  const GridKick grid_kick{model, state, loads, node_loads.with_mass_damping, kick};
  return force_sweep(
      model, state, options, ws, forces,
      [&](int n) {
        node_loads.add(n, forces);
        double speed_sq = kick_node(model, forces, kick, n, &to);
        if (kick.driven != nullptr && !drive_node(*kick.driven, kick.step_of_drive(), kick.start_of_drive(), to, n)) {
          speed_sq = std::numeric_limits<double>::quiet_NaN();
        }
        return speed_sq;
      },
      &grid_kick);
}

double cell_signed_volume(const Model& model, const Eigen::Matrix3Xd& positions, int cell) {
  return cell_frame(model, positions, cell).volume();
}

double elastic_energy(const Model& model, const Eigen::Matrix3Xd& x) {
  require_node_columns(model, x, "elastic_energy: positions");
  require_law_constants(model, "elastic_energy");
  double energy = 0.0;
  std::vector<double> length(model.num_springs());
  for (int s = 0; s < model.num_springs(); ++s) {
    length[s] = (x.col(model.spring_nodes[s][1]) - x.col(model.spring_nodes[s][0])).norm();
    const double stretch = length[s] - model.spring_rest_length[s];
    energy += 0.5 * model.spring_stiffness[s] * stretch * stretch;
  }
  const double rest_volume = model.rest_cell_volume();
  const bool neo_hookean = model.cell_law == CellLaw::kNeoHookean;
  for (int c = 0; c < model.num_cells(); ++c) {
    if (neo_hookean) {
      energy += neo_hookean_cell_energy(model.law_constants[model.cell_material[c]], cell_frame(model, x, c), nullptr);
    }
    Eigen::Vector3d strain;
    for (int axis = 0; axis < 3; ++axis) {
      double sum = 0.0;
      for (int e = 0; e < kEdgesPerAxis; ++e) sum += length[model.cell_edges[c][axis * kEdgesPerAxis + e]];
      strain[axis] = mean_edge_strain(sum, 1.0 / (kEdgesPerAxis * model.cell_size[axis]));
    }
    energy += 0.5 * rest_volume * strain.dot(model.cell_correction[c] * strain);
    if (model.has_twist) {
      std::array<Eigen::Vector3d, kEdgesPerCell> edges;
      for (int e = 0; e < kEdgesPerCell; ++e) {
        const auto& ends = model.spring_nodes[model.cell_edges[c][e]];
        edges[e] = x.col(ends[1]) - x.col(ends[0]);
      }
      energy +=
          twist_energy(edges, model.cell_size.x(), model.cell_twist_stiffness[c], [](int, const Eigen::Vector3d&) {});
    }
    const double ratio = cell_frame(model, x, c).volume() / rest_volume;
    if (!neo_hookean && ratio < kCrushedVolumeFraction) {
      const double excess = ratio - kCrushedVolumeFraction;
      energy += 0.5 * model.cell_inversion_stiffness[c] * rest_volume * excess * excess;
    }
  }
  return energy;
}

double potential_energy(const Model& model, const Loads& loads, const Eigen::Matrix3Xd& x) {
  require_node_columns(model, x, "potential_energy: positions");
  require_node_columns(model, loads.nodal_forces, "potential_energy: loads.nodal_forces", true);
  const Eigen::Matrix3Xd u = x - model.rest_positions;
  double work = (loads.gravity.transpose() * u * model.mass)(0);
  if (loads.nodal_forces.cols() == model.num_nodes()) work += loads.nodal_forces.cwiseProduct(u).sum();
  return elastic_energy(model, x) - work;
}

double kinetic_energy(const Model& model, const State& state) {
  require_node_columns(model, state.velocities, "kinetic_energy: state.velocities");
  return 0.5 * (state.velocities.colwise().squaredNorm().transpose().cwiseProduct(model.inertia())).sum();
}

}  // namespace cubespring
