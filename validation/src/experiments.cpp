// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The paper's virtual experiments (Baudet et al. 2007, section 3) on a block of cells, measured from
// area-weighted face-mean displacements.
#include "cubespring/validation/experiments.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <iomanip>
#include <limits>
#include <sstream>

#include "cubespring/constraints.h"
#include "cubespring/forces.h"
#include "cubespring/static_solver.h"
#include "cubespring/strain.h"
#include "cubespring/voxelize.h"
#include "finite_strain_experiments.h"

namespace cubespring {
namespace {

// Tributary area of every node on the face of the block normal to axis, on side 0 (min) or 1 (max):
// each boundary cell face gives a quarter of its area to each of its four corners.
Eigen::VectorXd face_weights(const Model& model, int axis, int side, int extent) {
  Eigen::VectorXd weights = Eigen::VectorXd::Zero(model.num_nodes());
  const double area = model.cell_size.prod() / model.cell_size[axis];
  for (int c = 0; c < model.num_cells(); ++c) {
    if (model.cell_grid_index[c][axis] != (side == 0 ? 0 : extent - 1)) continue;
    for (int corner = 0; corner < kCornersPerCell; ++corner) {
      if (((corner >> axis) & 1) == side) weights[model.cell_nodes[c][corner]] += area / 4.0;
    }
  }
  return weights;
}

// Area-weighted mean displacement of a face along a direction [m].
double face_mean(const Eigen::Matrix3Xd& u, const Eigen::VectorXd& weights, int direction) {
  return u.row(direction).dot(weights) / weights.sum();
}

// Mean strain along axis between the two opposite faces.
double face_strain(const Model& model, const Eigen::Matrix3Xd& u, const Eigen::Vector3i& cells, int axis) {
  const double length = cells[axis] * model.cell_size[axis];
  return (face_mean(u, face_weights(model, axis, 1, cells[axis]), axis) -
          face_mean(u, face_weights(model, axis, 0, cells[axis]), axis)) /
         length;
}

// Below this size a strain's displacements are lost in the positions' round-off, and the moduli
// measured from them come out infinite or NaN.
constexpr double kSmallestStrain = 1e-9;
// 1e5 g: far beyond any load a body here carries, far from overflowing its weight.
constexpr double kLargestGravity = 1e6;  // [m/s^2]

Status check_settings(Experiment experiment, const ExperimentSettings& s) {
  if (s.cells.minCoeff() < 1) {
    std::ostringstream message;
    message << "cells = " << s.cells.x() << "," << s.cells.y() << "," << s.cells.z() << ": every count must be >= 1";
    return Status::error(message.str());
  }
  // before box_lattice() lists them
  // in double: three ints' product can pass 2^64
  const double cells = static_cast<double>(s.cells.x()) * s.cells.y() * s.cells.z();
  if (Status size = check_lattice_size(cells, s.max_memory_bytes); !size) {
    std::ostringstream message;
    message << "cells = " << s.cells.x() << "," << s.cells.y() << "," << s.cells.z() << ": " << size.message();
    return Status::error(message.str());
  }
  // the static solver's factor, beside the body, before either is built (a 40^3 block took
  // minutes and 3.8 GB with no word; 100^3 would take over 100 GB)
  const std::uint64_t limit = s.max_memory_bytes > 0 ? s.max_memory_bytes : default_memory_limit();
  const auto count = static_cast<std::uint64_t>(cells);
  const double bytes = estimate_block_factorisation(s.cells).peak_bytes +
                       static_cast<double>(estimate_body_bytes(count, count, 7 * count));
  if (bytes > static_cast<double>(limit)) {
    std::ostringstream message;
    message << std::setprecision(3) << "cells = " << s.cells.x() << "," << s.cells.y() << "," << s.cells.z()
            << ": the block and its static solver's factorisation take about " << bytes / 1e9
            << " GB, more than the memory limit of " << static_cast<double>(limit) / 1e9 << " GB"
            << (s.max_memory_bytes > 0 ? "" : " (half this machine's memory)");
    return Status::error(message.str());
  }
  if (is_finite_strain_experiment(experiment)) {
    const bool shear = experiment == Experiment::kSimpleShear;
    if (!std::isfinite(s.strain) || s.strain == 0.0 || s.strain < (shear ? -1.0 : -0.6) || s.strain > 1.0) {
      std::ostringstream message;
      message << "strain = " << s.strain << ": " << experiment_name(experiment) << " takes "
              << (shear                                    ? "a shear gamma in [-1, 1]"
                  : experiment == Experiment::kHydrostatic ? "a volume change (J - 1) in [-0.6, 1]"
                                                           : "a nominal strain (stretch - 1) in [-0.6, 1]")
              << ", not 0";
      return Status::error(message.str());
    }
    if (s.curve_points < 1 || s.curve_points > 1000) {
      return Status::error("curve_points = " + std::to_string(s.curve_points) + ": must be 1 to 1000");
    }
  } else if (!std::isfinite(s.strain) || s.strain < kSmallestStrain || s.strain > 0.5) {
    std::ostringstream message;
    message << "strain = " << s.strain << ": must be " << kSmallestStrain << " to 0.5";
    return Status::error(message.str());
  }
  if (std::abs(s.strain) < kSmallestStrain) {  // the curves' (0 is refused above)
    std::ostringstream message;
    message << "strain = " << s.strain << ": must be at least " << kSmallestStrain
            << " in size (smaller displacements are lost in the positions' round-off)";
    return Status::error(message.str());
  }
  if (!std::isfinite(s.gravity) || s.gravity < 0.0 || s.gravity > kLargestGravity) {
    std::ostringstream message;
    message << "gravity = " << s.gravity << " m/s^2: must be 0 to " << kLargestGravity
            << " m/s^2 (beyond, the weight leaves the range of double)";
    return Status::error(message.str());
  }
  return {};
}

double relative_error(double measured, double expected) { return (measured - expected) / expected; }

// Affine shear u_p = gamma X_q imposed on every boundary node, interior free; the modulus is the
// reaction on the face normal to q (the force the clamps apply there) per area, over gamma.
Result<double> affine_shear_modulus(const Model& model, const Eigen::Vector3i& cells, int p, int q, double gamma,
                                    const StaticSettings& static_settings) {
  Constraints constraints(model);
  for (int n = 0; n < model.num_nodes(); ++n) {
    const Eigen::Vector3i& index = model.node_grid_index[n];
    if (!(index.array() == 0).any() && !(index.array() == cells.array()).any()) continue;
    Eigen::Vector3d displacement = Eigen::Vector3d::Zero();
    displacement[p] = gamma * (model.rest_positions(q, n) - model.origin[q]);
    if (Status s = constraints.prescribe_displacement(model, n, displacement); !s) return s;
  }
  State state = rest_state(model);
  const StaticReport report = solve_static(model, constraints, Loads{}, static_settings, state);
  if (!report.converged) return Status::error("shear: " + report.message);
  Eigen::Matrix3Xd forces;
  ForceWorkspace ws;
  compute_forces(model, state, Loads{}, ForceOptions{false, 1}, ws, forces);
  double face_force = 0.0;
  for (int n = 0; n < model.num_nodes(); ++n) {
    if (model.node_grid_index[n][q] == cells[q]) face_force -= forces(p, n);
  }
  const Eigen::Vector3d size = cells.cast<double>().cwiseProduct(model.cell_size);
  return face_force / (size.prod() / size[q]) / gamma;
}

// Shear moduli (yz, xz, xy) that a lattice of a x b x c cells has: only the body diagonals resist
// affine shear, C_abab = 4 k_d a b / (L_d^2 c) (docs/model-baudet2007.md section 4). The cell
// materials must be one; the first is used.
Eigen::Vector3d lattice_shear_moduli(const Model& model) {
  const Result<CellCalibration> calibration = calibrate_cell(model.cell_model, model.materials[0], model.cell_size);
  const Eigen::Vector3d& h = model.cell_size;
  const double diagonal_sq = h.squaredNorm();
  Eigen::Vector3d moduli;
  for (int plane = 0; plane < 3; ++plane) {
    const int a = (plane + 1) % 3;
    const int b = (plane + 2) % 3;
    moduli[plane] = 4.0 * calibration.value().diagonal_stiffness * h[a] * h[b] / (diagonal_sq * h[plane]);
  }
  return moduli;
}

// The displacement along `axis` at the centre of the body's far face normal to it (index
// cells[axis]): the mean of the face's nodes nearest to its centre (one when both other counts of
// cells are even, else 2 or 4), which is the bilinear value there.
double face_centre_displacement(const Model& model, const Eigen::Matrix3Xd& u, const Eigen::Vector3i& cells, int axis) {
  const int a = (axis + 1) % 3, b = (axis + 2) % 3;
  double sum = 0.0;
  int count = 0;
  for (int n = 0; n < model.num_nodes(); ++n) {
    const Eigen::Vector3i& index = model.node_grid_index[n];
    if (index[axis] != cells[axis]) continue;
    // twice the distance from the centre in cells: 0 on the centre, 1 next to it (odd counts)
    if (std::abs(2 * index[a] - cells[a]) > 1 || std::abs(2 * index[b] - cells[b]) > 1) continue;
    sum += u(axis, n);
    ++count;
  }
  return sum / count;
}

// The body's volume change (deformed / rest - 1) and its cells' least volume ratio.
void measure_volume(ExperimentResult& result) {
  const Model& model = result.model;
  const double rest_volume = body_volume(model, model.rest_positions);
  result.volume_change = body_volume(model, result.state.positions) / rest_volume - 1.0;
  double least = std::numeric_limits<double>::infinity();
  for (int c = 0; c < model.num_cells(); ++c) {
    least = std::min(least, cell_signed_volume(model, result.state.positions, c) / model.rest_cell_volume());
  }
  result.least_cell_volume_ratio = least;
}

// The self-weight block's base (z = 0): bonded, or on a frictionless floor, which holds the base
// nodes along z only (and two of them against sliding and turning: hold_face_in_plane).
Status support_base(const Model& model, const Eigen::Vector3i& cells, Support support, Constraints& constraints) {
  const double tolerance = 1e-9 * model.cell_size.z();
  const Eigen::Vector3d lower(-1e9, -1e9, -tolerance), upper(1e9, 1e9, tolerance);
  if (support == Support::kBonded) return constraints.fix_box(model, lower, upper);
  if (Status s = constraints.prescribe_box_axis_displacement(model, lower, upper, 2, 0.0); !s) return s;
  return hold_face_in_plane(model, cells, 2, constraints);
}

}  // namespace

const char* support_name(Support support) { return support == Support::kBonded ? "bonded" : "floor"; }

Result<Support> parse_support(const std::string& name) {
  for (Support support : {Support::kBonded, Support::kFloor}) {
    if (name == support_name(support)) return support;
  }
  return Status::error("unknown support '" + name + "': expected bonded or floor");
}

const char* experiment_name(Experiment experiment) {
  switch (experiment) {
    case Experiment::kElongation: return "elongation";
    case Experiment::kShear: return "shear";
    case Experiment::kInflation: return "inflation";
    case Experiment::kCantilever: return "cantilever";
    case Experiment::kSelfWeight: return "self-weight";
    case Experiment::kUniaxial: return "uniaxial";
    case Experiment::kSimpleShear: return "simple-shear";
    case Experiment::kHydrostatic: return "hydrostatic";
    case Experiment::kBondedCompression: return "bonded-compression";
  }
  return "unknown";
}

Result<Experiment> parse_experiment(const std::string& name) {
  for (Experiment e : {Experiment::kElongation, Experiment::kShear, Experiment::kInflation, Experiment::kCantilever,
                       Experiment::kSelfWeight, Experiment::kUniaxial, Experiment::kSimpleShear,
                       Experiment::kHydrostatic, Experiment::kBondedCompression}) {
    if (name == experiment_name(e)) return e;
  }
  return Status::error("unknown experiment '" + name +
                       "': expected elongation, shear, inflation, cantilever, self-weight, uniaxial, simple-shear, "
                       "hydrostatic or bonded-compression");
}

const char* shear_control_name(ShearControl control) {
  return control == ShearControl::kDisplacement ? "displacement" : "force";
}

Status check_experiment(Experiment experiment, const ExperimentSettings& settings) {
  return check_settings(experiment, settings);
}

Result<ExperimentResult> run_experiment(Experiment experiment, const ExperimentSettings& settings) {
  if (Status status = check_settings(experiment, settings); !status) return status;
  if ((experiment == Experiment::kCantilever || experiment == Experiment::kSelfWeight) && settings.gravity == 0.0) {
    // no load: no deflection to compare, and 0 / 0 for its error
    return Status::error("gravity = 0 m/s^2: the " + std::string(experiment_name(experiment)) +
                         " experiment's only load; must be > 0");
  }
  LatticeDesc desc = box_lattice(settings.cells, settings.cell_size, settings.material);
  desc.model = settings.model;
  desc.exact_bending = settings.exact_bending;
  desc.law = settings.law;
  Result<Model> built = build_model(desc);
  if (!built) return built.status();

  ExperimentResult result;
  result.experiment = experiment;
  result.settings = settings;
  result.model = std::move(built).value();
  const Model& model = result.model;
  const Material& material = settings.material;
  const Eigen::Vector3i& cells = settings.cells;
  const Eigen::Vector3d size = cells.cast<double>().cwiseProduct(settings.cell_size);
  const double e = material.young_modulus;
  const double g = shear_modulus(material);
  const double b = bulk_modulus(material);

  if (is_finite_strain_experiment(experiment)) {
    StaticReport solver;
    Result<std::vector<CurvePoint>> curve = finite_strain_curve(experiment, model, settings, result.state, solver);
    result.load_steps = solver.load_steps;
    result.newton_iterations = solver.newton_iterations;
    if (!curve) return curve.status();
    result.curve = std::move(curve).value();
    if (experiment == Experiment::kBondedCompression) {
      measure_volume(result);
      result.platen_force = face_reaction(model, result.state, 2, cells.z(), 2);
      result.bulge = face_centre_displacement(model, displacements(model, result.state), cells, 0);
    }
    return result;
  }

  Constraints constraints(model);
  Loads loads;
  loads.nodal_forces = Eigen::Matrix3Xd::Zero(3, model.num_nodes());
  StaticSettings static_settings;
  static_settings.progress = settings.progress;

  // loads and constraints
  switch (experiment) {
    case Experiment::kElongation: {
      const double stress = e * settings.strain;
      loads.nodal_forces.row(0) =
          stress * (face_weights(model, 0, 1, cells.x()) - face_weights(model, 0, 0, cells.x())).transpose();
      break;
    }
    case Experiment::kInflation: {
      const double pressure = 3.0 * b * settings.strain;
      for (int axis = 0; axis < 3; ++axis) {
        loads.nodal_forces.row(axis) -=
            pressure *
            (face_weights(model, axis, 1, cells[axis]) - face_weights(model, axis, 0, cells[axis])).transpose();
      }
      break;
    }
    case Experiment::kShear: {
      if (settings.shear_control == ShearControl::kForce) {
        const double stress = g * settings.strain;
        loads.nodal_forces.row(0) =
            stress * (face_weights(model, 2, 1, cells.z()) - face_weights(model, 2, 0, cells.z())).transpose();
        loads.nodal_forces.row(2) =
            stress * (face_weights(model, 0, 1, cells.x()) - face_weights(model, 0, 0, cells.x())).transpose();
      } else {
        // three affine shears, one per plane, each its own solve
        Eigen::Vector3d moduli;
        for (int plane = 0; plane < 3; ++plane) {
          Result<double> modulus =
              affine_shear_modulus(model, cells, (plane + 1) % 3, (plane + 2) % 3, settings.strain, static_settings);
          if (!modulus) return modulus.status();
          moduli[plane] = modulus.value();
        }
        result.shear_moduli = moduli;
        // the springs law's cells are anisotropic in shear when not cubic; the neo-Hookean law's
        // term makes every plane's G exact
        result.expected_shear_moduli =
            model.cell_law == CellLaw::kNeoHookean ? Eigen::Vector3d::Constant(g) : lattice_shear_moduli(model);
        result.measured.shear_modulus = moduli[1];
        result.expected.shear_modulus = g;
        result.error.shear_modulus = relative_error(moduli[1], g);
        result.state = rest_state(model);
        return result;
      }
      break;
    }
    case Experiment::kCantilever: {
      const double tolerance = 1e-9 * settings.cell_size.x();
      if (Status s = constraints.fix_box(model, Eigen::Vector3d::Constant(-tolerance) + Eigen::Vector3d(0, -1e9, -1e9),
                                         Eigen::Vector3d(tolerance, 1e9, 1e9));
          !s) {
        return s;
      }
      loads.gravity = Eigen::Vector3d(0.0, 0.0, -settings.gravity);
      static_settings.initial_load_steps = 4;
      break;
    }
    case Experiment::kSelfWeight: {
      if (Status s = support_base(model, cells, settings.support, constraints); !s) return s;
      loads.gravity = Eigen::Vector3d(0.0, 0.0, -settings.gravity);
      // soft tissue sags by a tenth of its height: ramp the weight in
      static_settings.initial_load_steps = 8;
      break;
    }
    case Experiment::kUniaxial:
    case Experiment::kSimpleShear:
    case Experiment::kHydrostatic:
    case Experiment::kBondedCompression: break;  // finite_strain_curve's, above
  }

  result.state = rest_state(model);
  const StaticReport report = solve_static(model, constraints, loads, static_settings, result.state);
  result.load_steps = report.load_steps;
  result.newton_iterations = report.newton_iterations;
  if (!report.converged) return Status::error(std::string(experiment_name(experiment)) + ": " + report.message);
  const Eigen::Matrix3Xd u = displacements(model, result.state);

  // measurements
  switch (experiment) {
    case Experiment::kElongation: {
      const double axial = face_strain(model, u, cells, 0);
      const double lateral = 0.5 * (face_strain(model, u, cells, 1) + face_strain(model, u, cells, 2));
      result.measured.young_modulus = e * settings.strain / axial;
      result.measured.poisson_ratio = -lateral / axial;
      result.expected.young_modulus = e;
      result.expected.poisson_ratio = material.poisson_ratio;
      result.error.young_modulus = relative_error(*result.measured.young_modulus, e);
      result.error.poisson_ratio = *result.measured.poisson_ratio - material.poisson_ratio;
      break;
    }
    case Experiment::kInflation: {
      double volume_ratio = 1.0;
      for (int axis = 0; axis < 3; ++axis) volume_ratio *= 1.0 + face_strain(model, u, cells, axis);
      result.measured.bulk_modulus = 3.0 * b * settings.strain / (1.0 - volume_ratio);
      result.expected.bulk_modulus = b;
      result.error.bulk_modulus = relative_error(*result.measured.bulk_modulus, b);
      break;
    }
    case Experiment::kShear: {
      // force control: engineering shear strain from the face-mean slips of both face pairs
      const double shear_stress = g * settings.strain;
      const Eigen::VectorXd top = face_weights(model, 2, 1, cells.z());
      const Eigen::VectorXd bottom = face_weights(model, 2, 0, cells.z());
      const Eigen::VectorXd right = face_weights(model, 0, 1, cells.x());
      const Eigen::VectorXd left = face_weights(model, 0, 0, cells.x());
      const double shear_strain = (face_mean(u, top, 0) - face_mean(u, bottom, 0)) / size.z() +
                                  (face_mean(u, right, 2) - face_mean(u, left, 2)) / size.x();
      result.measured.shear_modulus = shear_stress / shear_strain;
      result.expected.shear_modulus = g;
      result.error.shear_modulus = relative_error(*result.measured.shear_modulus, g);
      break;
    }
    case Experiment::kCantilever: {
      double sum = 0.0;
      int count = 0;
      for (int n = 0; n < model.num_nodes(); ++n) {
        if (model.node_grid_index[n].x() != cells.x()) continue;
        sum += u(2, n);
        ++count;
      }
      result.tip_deflection = sum / count;
      const double area = size.y() * size.z();
      const double inertia = size.y() * std::pow(size.z(), 3) / 12.0;
      const double q = material.density * settings.gravity * area;
      const double nu = material.poisson_ratio;
      const double shear_coefficient = 10.0 * (1.0 + nu) / (12.0 + 11.0 * nu);
      result.euler_bernoulli = -q * std::pow(size.x(), 4) / (8.0 * e * inertia);
      result.timoshenko = *result.euler_bernoulli - q * size.x() * size.x() / (2.0 * shear_coefficient * g * area);
      break;
    }
    case Experiment::kSelfWeight: {
      result.top_centre_uz = face_centre_displacement(model, u, cells, 2);
      measure_volume(result);
      break;
    }
    case Experiment::kUniaxial:
    case Experiment::kSimpleShear:
    case Experiment::kHydrostatic:
    case Experiment::kBondedCompression: break;
  }
  return result;
}

}  // namespace cubespring
