// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Finite-strain experiments (issue 24) and the neo-Hookean law's closed forms they compare with
// (docs/model-neo-hookean.md section 2: W = G/2 (I1bar - 3) + B/2 (J - 1)^2 + W_b(J)).
#include "finite_strain_experiments.h"

#include <cmath>
#include <limits>
#include <sstream>

#include "cubespring/cell_law.h"
#include "cubespring/forces.h"
#include "cubespring/static_solver.h"

namespace cubespring {
namespace {

// dU/dJ of the volumetric energy with its barrier: the Cauchy pressure part of the stress [Pa].
double volumetric_pressure(const Material& material, double j) {
  const double b = bulk_modulus(material);
  double pressure = b * (j - 1.0);
  constexpr double j0 = kBarrierVolumeRatio;
  if (j < j0) {
    const double u = j0 - j;
    pressure -= b * u * u * (3.0 * j + u) / (j0 * j0 * j * j);
  }
  return pressure;
}

// Cauchy stress along an axis of a diagonal stretch (a, b, c) with J = abc: G/J dev(Bbar) + p.
double principal_cauchy_stress(const Material& material, double along, double other_1, double other_2) {
  const double j = along * other_1 * other_2;
  const double i1 = along * along + other_1 * other_1 + other_2 * other_2;
  return shear_modulus(material) / j * std::pow(j, -2.0 / 3.0) * (along * along - i1 / 3.0) +
         volumetric_pressure(material, j);
}

// The nodes of the block's face at index `at` along axis.
template <typename Visit>
void for_face_nodes(const Model& model, int axis, int at, const Visit& visit) {
  for (int n = 0; n < model.num_nodes(); ++n) {
    if (model.node_grid_index[n][axis] == at) visit(n);
  }
}

bool on_boundary(const Model& model, const Eigen::Vector3i& cells, int n) {
  const Eigen::Vector3i& index = model.node_grid_index[n];
  return (index.array() == 0).any() || (index.array() == cells.array()).any();
}

// The constraints of one load level.
Result<Constraints> constraints_at(Experiment experiment, const Model& model, const Eigen::Vector3i& cells,
                                   double strain) {
  Constraints constraints(model);
  const Eigen::Vector3d size = cells.cast<double>().cwiseProduct(model.cell_size);
  switch (experiment) {
    case Experiment::kUniaxial: {
      // the platens: the faces x = 0 and x = L held along x, the second moved by the strain (the
      // targets are finite and the nodes the body's: these cannot fail)
      for_face_nodes(model, 0, 0,
                     [&](int n) { (void)constraints.prescribe_axis_position(n, 0, model.rest_positions(0, n)); });
      for_face_nodes(model, 0, cells.x(), [&](int n) {
        (void)constraints.prescribe_axis_position(n, 0, model.rest_positions(0, n) + strain * size.x());
      });
      if (Status s = hold_face_in_plane(model, cells, 0, constraints); !s) return s;
      break;
    }
    case Experiment::kBondedCompression: {
      // the plates: every node of the face z = 0 held, of the face z = H moved along z
      for (int n = 0; n < model.num_nodes(); ++n) {
        const int at = model.node_grid_index[n].z();
        if (at != 0 && at != cells.z()) continue;
        const Eigen::Vector3d displacement(0, 0, at == 0 ? 0.0 : strain * size.z());
        if (Status s = constraints.prescribe_displacement(model, n, displacement); !s) return s;
      }
      break;
    }
    case Experiment::kSimpleShear:
    case Experiment::kHydrostatic: {
      const double stretch = std::cbrt(1.0 + strain);
      for (int n = 0; n < model.num_nodes(); ++n) {
        if (!on_boundary(model, cells, n)) continue;
        const Eigen::Vector3d rest = model.rest_positions.col(n) - model.origin;
        Eigen::Vector3d displacement = (stretch - 1.0) * rest;
        if (experiment == Experiment::kSimpleShear) displacement = Eigen::Vector3d(strain * rest.z(), 0, 0);
        if (Status s = constraints.prescribe_displacement(model, n, displacement); !s) return s;
      }
      break;
    }
    default: return Status::error(std::string(experiment_name(experiment)) + " is not a finite-strain experiment");
  }
  return constraints;
}

}  // namespace

double face_reaction(const Model& model, const State& state, int face_axis, int at, int direction) {
  Eigen::Matrix3Xd forces;
  ForceWorkspace ws;
  compute_forces(model, state, Loads{}, ForceOptions{false, 1}, ws, forces);
  double force = 0.0;
  for_face_nodes(model, face_axis, at, [&](int n) { force -= forces(direction, n); });
  return force;
}

namespace {

// The nominal stress the constraints carry: the force on the face x = L (uniaxial, hydrostatic)
// along x, z = H along x (simple shear) or along z (bonded compression), over its rest area.
double measured_stress(Experiment experiment, const Model& model, const Eigen::Vector3i& cells, const State& state) {
  const int face_axis = experiment == Experiment::kSimpleShear || experiment == Experiment::kBondedCompression ? 2 : 0;
  const int direction = experiment == Experiment::kBondedCompression ? 2 : 0;
  const Eigen::Vector3d size = cells.cast<double>().cwiseProduct(model.cell_size);
  return face_reaction(model, state, face_axis, cells[face_axis], direction) / (size.prod() / size[face_axis]);
}

double expected_stress(Experiment experiment, const Material& material, double strain) {
  switch (experiment) {
    case Experiment::kUniaxial: return neo_hookean_uniaxial_stress(material, 1.0 + strain);
    case Experiment::kSimpleShear: return neo_hookean_simple_shear_stress(material, strain);
    case Experiment::kBondedCompression: return std::numeric_limits<double>::quiet_NaN();
    default: return neo_hookean_hydrostatic_stress(material, 1.0 + strain);
  }
}

}  // namespace

bool is_finite_strain_experiment(Experiment experiment) {
  return experiment == Experiment::kUniaxial || experiment == Experiment::kSimpleShear ||
         experiment == Experiment::kHydrostatic || experiment == Experiment::kBondedCompression;
}

Status hold_face_in_plane(const Model& model, const Eigen::Vector3i& cells, int axis, Constraints& constraints) {
  const int first = (axis + 1) % 3, second = (axis + 2) % 3;
  const int p = std::min(first, second), q = std::max(first, second);
  Eigen::Vector3i centre = Eigen::Vector3i::Zero();
  centre[p] = cells[p] / 2;
  centre[q] = cells[q] / 2;
  Eigen::Vector3i row_end = centre;
  row_end[p] = cells[p];
  const int centre_node = model.node_at(centre), row_end_node = model.node_at(row_end);
  for (const int other : {p, q}) {
    const double at_rest = model.rest_positions(other, centre_node);
    if (Status s = constraints.prescribe_axis_position(centre_node, other, at_rest); !s) return s;
  }
  return constraints.prescribe_axis_position(row_end_node, q, model.rest_positions(q, row_end_node));
}

Result<std::vector<CurvePoint>> finite_strain_curve(Experiment experiment, const Model& model,
                                                    const ExperimentSettings& settings, State& state,
                                                    StaticReport& solver) {
  std::vector<CurvePoint> curve;
  state = rest_state(model);
  for (int k = 1; k <= settings.curve_points; ++k) {
    const double strain = settings.strain * k / settings.curve_points;
    Result<Constraints> constraints = constraints_at(experiment, model, settings.cells, strain);
    if (!constraints) return constraints.status();
    // from the point before: a continuation, which also keeps to one branch where the lattice
    // has several equilibria
    StaticSettings static_settings;
    static_settings.progress = settings.progress;
    static_settings.start_from_state = true;
    static_settings.initial_load_steps = k == 1 ? 4 : 1;
    const StaticReport report = solve_static(model, constraints.value(), Loads{}, static_settings, state);
    solver.load_steps += report.load_steps;
    solver.newton_iterations += report.newton_iterations;
    solver.unstable_equilibria += report.unstable_equilibria;
    if (!report.converged) {
      std::ostringstream message;
      message << experiment_name(experiment) << " at strain " << strain << ": " << report.message;
      return Status::error(message.str());
    }
    curve.push_back({strain, measured_stress(experiment, model, settings.cells, state),
                     expected_stress(experiment, settings.material, strain)});
  }
  return curve;
}

double neo_hookean_uniaxial_lateral_stretch(const Material& material, double stretch) {
  // the lateral stretch whose Cauchy stress is zero: the stress rises with it (the volume term
  // dominates both ends), so bisect, on a log scale, between J = 0.05 and a hundredfold volume
  double low = std::sqrt(0.05 / stretch), high = std::sqrt(100.0 / stretch);
  for (int i = 0; i < 200 && high / low > 1.0 + 1e-15; ++i) {
    const double middle = std::sqrt(low * high);
    (principal_cauchy_stress(material, middle, middle, stretch) > 0.0 ? high : low) = middle;
  }
  return std::sqrt(low * high);
}

double neo_hookean_uniaxial_stress(const Material& material, double stretch) {
  const double lateral = neo_hookean_uniaxial_lateral_stretch(material, stretch);
  const double j = stretch * lateral * lateral;
  return j * principal_cauchy_stress(material, stretch, lateral, lateral) / stretch;
}

double neo_hookean_simple_shear_stress(const Material& material, double gamma) {
  return shear_modulus(material) * gamma;
}

double neo_hookean_hydrostatic_stress(const Material& material, double volume_ratio) {
  return std::pow(volume_ratio, 2.0 / 3.0) * volumetric_pressure(material, volume_ratio);
}

}  // namespace cubespring
