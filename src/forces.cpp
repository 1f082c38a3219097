// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Internal forces of the cube lattice, in passes over flat arrays (docs/model-baudet2007.md):
//   1. springs: current length and its rate;
//   2. cells:   mean edge strains -> correction tension per axis (section 3), crushed-cell flags;
//   3. springs: total tension (spring + correction + damping) -> force on the two ends;
//   4. nodes:   the spring forces summed in ascending spring order;
//   5. crushed cells: inversion recovery (section 5); then mass-proportional damping and loads.
// Pass 4 gathers per node on several threads and scatters on one; both add the same terms in the
// same order, so the result is bit-identical whatever the thread count.
#include "cubespring/forces.h"

#include <algorithm>
#include <cmath>

#include "cell_geometry.h"
#include "force_passes.h"

namespace cubespring {
namespace {

// Below this many springs a parallel region costs more than it saves; the passes run on one thread.
constexpr int kMinSpringsPerThread = 2048;

// Springs shorter than this fraction of their rest length have no direction and give no force.
constexpr double kDegenerateLengthFraction = 1e-12;

// Velocities may be null: rates are then zero.
void measure_springs(const Model& model, const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd* v,
                     [[maybe_unused]] int threads, ForceWorkspace& ws) {
  const int num_springs = model.num_springs();
#pragma omp parallel for num_threads(threads) if (threads > 1) schedule(static)
  for (int s = 0; s < num_springs; ++s) {
    const int i = model.spring_nodes[s][0];
    const int j = model.spring_nodes[s][1];
    const Eigen::Vector3d d = x.col(j) - x.col(i);
    const double length = d.norm();
    ws.spring_length[s] = length;
    ws.spring_rate[s] = v != nullptr && length > 0.0 ? (v->col(j) - v->col(i)).dot(d) / length : 0.0;
  }
}

// Correction tension T_a = V0 (D (eps + beta d(eps)/dt))_a / (4 a0) on each a-edge of a cell.
void correction_tensions(const Model& model, bool with_damping, [[maybe_unused]] int threads,
                         ForceWorkspace& ws) {
  const int num_cells = model.num_cells();
  const Eigen::Vector3d& size = model.cell_size;
  const double volume = size.prod();
#pragma omp parallel for num_threads(threads) if (threads > 1) schedule(static)
  for (int c = 0; c < num_cells; ++c) {
    Eigen::Vector3d strain;
    Eigen::Vector3d strain_rate;
    for (int axis = 0; axis < 3; ++axis) {
      double length_sum = 0.0;
      double rate_sum = 0.0;
      for (int e = 0; e < kEdgesPerAxis; ++e) {
        const int s = model.cell_edges[c][axis * kEdgesPerAxis + e];
        length_sum += ws.spring_length[s];
        rate_sum += ws.spring_rate[s];
      }
      strain[axis] = length_sum / (kEdgesPerAxis * size[axis]) - 1.0;
      strain_rate[axis] = rate_sum / (kEdgesPerAxis * size[axis]);
    }
    const double beta = with_damping ? model.materials[model.cell_material[c]].stiffness_damping : 0.0;
    const Eigen::Vector3d stress = model.cell_correction[c] * (strain + beta * strain_rate);
    ws.cell_tension.col(c) = volume * stress.cwiseQuotient(kEdgesPerAxis * size);
  }
}

double spring_tension(const Model& model, const ForceWorkspace& ws, bool with_damping, int s) {
  double tension = model.spring_stiffness[s] * (ws.spring_length[s] - model.spring_rest_length[s]);
  if (with_damping) tension += model.spring_damping[s] * ws.spring_rate[s];
  for (int e = model.spring_cell_offset[s]; e < model.spring_cell_offset[s + 1]; ++e) {
    const int cell_axis = model.spring_cell_axis[e];
    tension += ws.cell_tension(cell_axis % 3, cell_axis / 3);
  }
  return tension;
}

// Force on spring_nodes[s][0]; the other end gets its negative.
Eigen::Vector3d spring_force(const Model& model, const Eigen::Matrix3Xd& x, const ForceWorkspace& ws, int s) {
  const double length = ws.spring_length[s];
  if (length <= kDegenerateLengthFraction * model.spring_rest_length[s]) return Eigen::Vector3d::Zero();
  const int i = model.spring_nodes[s][0];
  const int j = model.spring_nodes[s][1];
  return (ws.spring_tension[s] / length) * (x.col(j) - x.col(i));
}

void apply_spring_forces(const Model& model, const State& state, bool with_damping, int threads,
                         ForceWorkspace& ws, Eigen::Matrix3Xd& forces) {
  const int num_springs = model.num_springs();
  const Eigen::Matrix3Xd& x = state.positions;
  if (threads <= 1) {
    for (int s = 0; s < num_springs; ++s) {
      ws.spring_tension[s] = spring_tension(model, ws, with_damping, s);
      const Eigen::Vector3d f = spring_force(model, x, ws, s);
      forces.col(model.spring_nodes[s][0]) += f;
      forces.col(model.spring_nodes[s][1]) -= f;
    }
    return;
  }
#pragma omp parallel for num_threads(threads) schedule(static)
  for (int s = 0; s < num_springs; ++s) {
    ws.spring_tension[s] = spring_tension(model, ws, with_damping, s);
    ws.spring_force.col(s) = spring_force(model, x, ws, s);
  }
  const int num_nodes = model.num_nodes();
#pragma omp parallel for num_threads(threads) schedule(static)
  for (int n = 0; n < num_nodes; ++n) {
    Eigen::Vector3d sum = forces.col(n);
    for (int e = model.node_spring_offset[n]; e < model.node_spring_offset[n + 1]; ++e) {
      const int entry = model.node_spring[e];
      if (entry & 1) {
        sum -= ws.spring_force.col(entry >> 1);
      } else {
        sum += ws.spring_force.col(entry >> 1);
      }
    }
    forces.col(n) = sum;
  }
}

void apply_inversion_forces(const Model& model, const Eigen::Matrix3Xd& x, Eigen::Matrix3Xd& forces) {
  const double rest_volume = model.rest_cell_volume();
  for (int c = 0; c < model.num_cells(); ++c) {
    const CellFrame frame = cell_frame(model, x, c);
    const double ratio = frame.volume() / rest_volume;
    if (ratio >= kCrushedVolumeFraction) continue;
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
  correction_tensions(model, false, 1, ws);
  for (int s = 0; s < model.num_springs(); ++s) ws.spring_tension[s] = spring_tension(model, ws, false, s);
}

void ForceWorkspace::resize(const Model& model) {
  const auto num_springs = static_cast<std::size_t>(model.num_springs());
  spring_length.resize(num_springs);
  spring_rate.resize(num_springs);
  spring_tension.resize(num_springs);
  cell_tension.resize(3, model.num_cells());
  spring_force.resize(3, model.num_springs());
}

void compute_forces(const Model& model, const State& state, const Loads& loads,
                    const ForceOptions& options, ForceWorkspace& ws, Eigen::Matrix3Xd& forces) {
  if (static_cast<int>(ws.spring_length.size()) != model.num_springs() ||
      ws.cell_tension.cols() != model.num_cells()) {
    ws.resize(model);
  }
  const int threads = std::max(1, std::min(options.threads, model.num_springs() / kMinSpringsPerThread));
  forces.setZero(3, model.num_nodes());
  measure_springs(model, state.positions, options.damping ? &state.velocities : nullptr, threads, ws);
  correction_tensions(model, options.damping, threads, ws);
  apply_spring_forces(model, state, options.damping, threads, ws, forces);
  apply_inversion_forces(model, state.positions, forces);

  // mass-proportional damping and external loads
  if (options.damping) {
    forces -= state.velocities * model.mass_damping.asDiagonal();
  }
  if (!loads.gravity.isZero()) forces += loads.gravity * model.mass.transpose();
  if (loads.nodal_forces.cols() == model.num_nodes()) forces += loads.nodal_forces;
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
