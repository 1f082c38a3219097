// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Internal forces of the cube lattice, in passes over flat arrays (docs/model-baudet2007.md):
//   1. springs: current vector, length and (with stiffness damping) length rate;
//   2. cells:   mean edge strains -> correction tension per axis (section 3); signed volume from
//               the body diagonals -> crushed-cell flag (section 5);
//   3. springs: total tension (spring + correction + damping) -> force on both ends;
//   4. crushed cells: inversion recovery; then mass-proportional damping and loads.
// On one thread pass 3 walks the springs grouped by their first node (they are sorted so), keeping
// that node's sum in a register and scattering to the second node. On several threads it stores
// each spring's force and gathers per node, adding the same terms in the same order (second-node
// terms first, then the first-node sum), so results are bit-identical whatever the thread count.
#include "cubespring/forces.h"

#include <algorithm>
#include <cmath>

#include "cell_geometry.h"
#include "force_passes.h"
#include "twist.h"

namespace cubespring {
namespace {

// Below this many springs per thread a parallel region costs more than it saves.
constexpr int kMinSpringsPerThread = 2048;

// Springs shorter than this fraction of their rest length have no direction and give no force.
constexpr double kDegenerateLengthFraction = 1e-12;

template <bool kWithRate>
void measure_springs(const Model& model, const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v,
                     [[maybe_unused]] int threads, ForceWorkspace& ws) {
  const int num_springs = model.num_springs();
#pragma omp parallel for num_threads(threads) if (threads > 1) schedule(static)
  for (int s = 0; s < num_springs; ++s) {
    const int i = model.spring_nodes[s][0];
    const int j = model.spring_nodes[s][1];
    const Eigen::Vector3d d = x.col(j) - x.col(i);
    const double length = d.norm();
    ws.spring_vector.col(s) = d;
    ws.spring_length[s] = length;
    if constexpr (kWithRate) ws.spring_rate[s] = length > 0.0 ? (v.col(j) - v.col(i)).dot(d) / length : 0.0;
  }
}

void measure_springs(const Model& model, const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd* v, int threads,
                     ForceWorkspace& ws) {
  if (v != nullptr) {
    measure_springs<true>(model, x, *v, threads, ws);
  } else {
    measure_springs<false>(model, x, x, threads, ws);
  }
}

// Correction tension T_a = V0 (D (eps + beta d(eps)/dt))_a / (4 a0) on each a-edge of a cell, and
// the crushed flag from the signed volume of the mean edge vectors, which the diagonals give:
// sum_k s_a(k) x_k = sum over diagonals c -> 7-c of s_a(7-c) (x_{7-c} - x_c).
void cell_pass(const Model& model, bool with_rate, [[maybe_unused]] int threads, ForceWorkspace& ws) {
  const int num_cells = model.num_cells();
  const Eigen::Vector3d& size = model.cell_size;
  const double volume = size.prod();
  const double crushed_volume = kCrushedVolumeFraction * volume;
#pragma omp parallel for num_threads(threads) if (threads > 1) schedule(static)
  for (int c = 0; c < num_cells; ++c) {
    Eigen::Vector3d strain;
    Eigen::Vector3d strain_rate = Eigen::Vector3d::Zero();
    for (int axis = 0; axis < 3; ++axis) {
      double length_sum = 0.0;
      for (int e = 0; e < kEdgesPerAxis; ++e) length_sum += ws.spring_length[model.cell_edges[c][axis * kEdgesPerAxis + e]];
      strain[axis] = length_sum / (kEdgesPerAxis * size[axis]) - 1.0;
      if (with_rate) {
        double rate_sum = 0.0;
        for (int e = 0; e < kEdgesPerAxis; ++e) rate_sum += ws.spring_rate[model.cell_edges[c][axis * kEdgesPerAxis + e]];
        strain_rate[axis] = rate_sum / (kEdgesPerAxis * size[axis]);
      }
    }
    const double beta = with_rate ? model.materials[model.cell_material[c]].stiffness_damping : 0.0;
    const Eigen::Vector3d stress = model.cell_correction[c] * (strain + beta * strain_rate);
    ws.cell_tension.col(c) = volume * stress.cwiseQuotient(kEdgesPerAxis * size);

    std::array<Eigen::Vector3d, 3> edge;
    edge.fill(Eigen::Vector3d::Zero());
    for (int corner = 0; corner < 4; ++corner) {
      const Eigen::Vector3d diagonal = ws.spring_vector.col(model.cell_diagonals[c][corner]);
      for (int axis = 0; axis < 3; ++axis) edge[axis] += corner_side(7 - corner, axis) * diagonal;
    }
    // the 1/4 of each mean edge vector gives 1/64 on the volume
    ws.cell_crushed[c] = edge[0].dot(edge[1].cross(edge[2])) < 64.0 * crushed_volume;

    if (model.has_twist) {
      std::array<Eigen::Vector3d, kEdgesPerCell> edges;
      for (int e = 0; e < kEdgesPerCell; ++e) edges[e] = ws.spring_vector.col(model.cell_edges[c][e]);
      auto out = ws.cell_edge_force.middleCols<kEdgesPerCell>(static_cast<Eigen::Index>(c) * kEdgesPerCell);
      out.setZero();
      twist_energy(edges, size.x(), model.cell_twist_stiffness[c],
                   [&](int slot, const Eigen::Vector3d& f) { out.col(slot) += f; });
    }
  }
}

inline double spring_tension(const Model& model, const ForceWorkspace& ws, bool with_rate, int s) {
  double tension = model.spring_stiffness[s] * (ws.spring_length[s] - model.spring_rest_length[s]);
  if (with_rate) tension += model.spring_damping[s] * ws.spring_rate[s];
  const double* cell_tension = ws.cell_tension.data();
  for (int e = model.spring_cell_offset[s]; e < model.spring_cell_offset[s + 1]; ++e) {
    tension += cell_tension[model.spring_cell_tension[e]];
  }
  return tension;
}

// Force on spring_nodes[s][0]; the other end gets its negative. The twist term adds non-central
// but balanced forces on the same two ends.
Eigen::Vector3d spring_force(const Model& model, const ForceWorkspace& ws, double tension, int s) {
  const double length = ws.spring_length[s];
  Eigen::Vector3d force = length > kDegenerateLengthFraction * model.spring_rest_length[s]
                              ? Eigen::Vector3d((tension / length) * ws.spring_vector.col(s))
                              : Eigen::Vector3d::Zero();
  if (model.has_twist) {
    for (int e = model.spring_cell_offset[s]; e < model.spring_cell_offset[s + 1]; ++e) {
      force += ws.cell_edge_force.col(model.spring_cell_edge[e]);
    }
  }
  return force;
}

void apply_spring_forces(const Model& model, bool with_rate, int threads, ForceWorkspace& ws,
                         Eigen::Matrix3Xd& forces) {
  const int num_nodes = model.num_nodes();
  if (threads <= 1) {
    for (int n = 0; n < num_nodes; ++n) {
      Eigen::Vector3d first_node_sum = Eigen::Vector3d::Zero();
      for (int s = model.node_first_spring[n]; s < model.node_first_spring[n + 1]; ++s) {
        const Eigen::Vector3d f = spring_force(model, ws, spring_tension(model, ws, with_rate, s), s);
        first_node_sum += f;
        forces.col(model.spring_nodes[s][1]) -= f;
      }
      forces.col(n) += first_node_sum;
    }
    return;
  }
  const int num_springs = model.num_springs();
#pragma omp parallel for num_threads(threads) schedule(static)
  for (int s = 0; s < num_springs; ++s) {
    ws.spring_force.col(s) = spring_force(model, ws, spring_tension(model, ws, with_rate, s), s);
  }
#pragma omp parallel for num_threads(threads) schedule(static)
  for (int n = 0; n < num_nodes; ++n) {
    // second-node terms come first in spring order, then the first-node sum, as in the scatter
    Eigen::Vector3d second_node_sum = forces.col(n);
    Eigen::Vector3d first_node_sum = Eigen::Vector3d::Zero();
    for (int e = model.node_spring_offset[n]; e < model.node_spring_offset[n + 1]; ++e) {
      const int entry = model.node_spring[e];
      if (entry & 1) {
        second_node_sum -= ws.spring_force.col(entry >> 1);
      } else {
        first_node_sum += ws.spring_force.col(entry >> 1);
      }
    }
    forces.col(n) = second_node_sum + first_node_sum;
  }
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

}  // namespace

void measure_tensions(const Model& model, const Eigen::Matrix3Xd& x, ForceWorkspace& ws) {
  ws.resize(model);
  measure_springs(model, x, nullptr, 1, ws);
  cell_pass(model, false, 1, ws);
  for (int s = 0; s < model.num_springs(); ++s) ws.spring_tension[s] = spring_tension(model, ws, false, s);
}

void ForceWorkspace::resize(const Model& model) {
  const auto num_springs = static_cast<std::size_t>(model.num_springs());
  spring_vector.resize(3, model.num_springs());
  spring_length.resize(num_springs);
  spring_rate.resize(num_springs);
  spring_tension.resize(num_springs);
  cell_tension.resize(3, model.num_cells());
  cell_crushed.resize(model.num_cells());
  spring_force.resize(3, model.num_springs());
  cell_edge_force.resize(3, model.has_twist ? static_cast<Eigen::Index>(model.num_cells()) * kEdgesPerCell : 0);
}

void compute_forces(const Model& model, const State& state, const Loads& loads,
                    const ForceOptions& options, ForceWorkspace& ws, Eigen::Matrix3Xd& forces) {
  if (ws.spring_vector.cols() != model.num_springs() || ws.cell_tension.cols() != model.num_cells()) ws.resize(model);
  const int threads = std::max(1, std::min(options.threads, model.num_springs() / kMinSpringsPerThread));
  const bool with_rate = options.damping && model.has_stiffness_damping;
  const int num_nodes = model.num_nodes();
  if (forces.cols() != num_nodes) forces.resize(3, num_nodes);
  forces.setZero();
  measure_springs(model, state.positions, with_rate ? &state.velocities : nullptr, threads, ws);
  cell_pass(model, with_rate, threads, ws);
  apply_spring_forces(model, with_rate, threads, ws, forces);
  apply_inversion_forces(model, state.positions, ws, forces);

  // mass-proportional damping and external loads
  const bool with_mass_damping = options.damping && model.has_mass_damping;
  const bool with_gravity = !loads.gravity.isZero();
  const bool with_nodal = loads.nodal_forces.cols() == num_nodes;
  if (!with_mass_damping && !with_gravity && !with_nodal) return;
  for (int n = 0; n < num_nodes; ++n) {
    if (with_mass_damping) forces.col(n) -= model.mass_damping[n] * state.velocities.col(n);
    if (with_gravity) forces.col(n) += model.mass[n] * loads.gravity;
    if (with_nodal) forces.col(n) += loads.nodal_forces.col(n);
  }
}

double cell_signed_volume(const Model& model, const Eigen::Matrix3Xd& positions, int cell) {
  return cell_frame(model, positions, cell).volume();
}

double elastic_energy(const Model& model, const Eigen::Matrix3Xd& x) {
  double energy = 0.0;
  std::vector<double> length(model.num_springs());
  for (int s = 0; s < model.num_springs(); ++s) {
    length[s] = (x.col(model.spring_nodes[s][1]) - x.col(model.spring_nodes[s][0])).norm();
    const double stretch = length[s] - model.spring_rest_length[s];
    energy += 0.5 * model.spring_stiffness[s] * stretch * stretch;
  }
  const double rest_volume = model.rest_cell_volume();
  for (int c = 0; c < model.num_cells(); ++c) {
    Eigen::Vector3d strain;
    for (int axis = 0; axis < 3; ++axis) {
      double sum = 0.0;
      for (int e = 0; e < kEdgesPerAxis; ++e) sum += length[model.cell_edges[c][axis * kEdgesPerAxis + e]];
      strain[axis] = sum / (kEdgesPerAxis * model.cell_size[axis]) - 1.0;
    }
    energy += 0.5 * rest_volume * strain.dot(model.cell_correction[c] * strain);
    if (model.has_twist) {
      std::array<Eigen::Vector3d, kEdgesPerCell> edges;
      for (int e = 0; e < kEdgesPerCell; ++e) {
        const auto& ends = model.spring_nodes[model.cell_edges[c][e]];
        edges[e] = x.col(ends[1]) - x.col(ends[0]);
      }
      energy += twist_energy(edges, model.cell_size.x(), model.cell_twist_stiffness[c],
                             [](int, const Eigen::Vector3d&) {});
    }
    const double ratio = cell_frame(model, x, c).volume() / rest_volume;
    if (ratio < kCrushedVolumeFraction) {
      const double excess = ratio - kCrushedVolumeFraction;
      energy += 0.5 * model.cell_inversion_stiffness[c] * rest_volume * excess * excess;
    }
  }
  return energy;
}

double potential_energy(const Model& model, const Loads& loads, const Eigen::Matrix3Xd& x) {
  const Eigen::Matrix3Xd u = x - model.rest_positions;
  double work = (loads.gravity.transpose() * u * model.mass)(0);
  if (loads.nodal_forces.cols() == model.num_nodes()) work += loads.nodal_forces.cwiseProduct(u).sum();
  return elastic_energy(model, x) - work;
}

double kinetic_energy(const Model& model, const State& state) {
  return 0.5 * (state.velocities.colwise().squaredNorm().transpose().cwiseProduct(model.mass)).sum();
}

}  // namespace cubespring
