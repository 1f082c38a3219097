// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Spring stiffnesses and correction of one cell: docs/model-baudet2007.md, sections 2 to 4, and
// docs/model-exact-bending.md section 2.
#include <cmath>
#include <sstream>

#include "cubespring/model.h"

namespace cubespring {
namespace {

struct SpringSet {
  Eigen::Vector3d edge;  // per-cell share of each edge along x, y, z [N/m]
  double diagonal = 0;   // each body diagonal [N/m]
};

// Paper's springs generalised to a x b x c cells (section 4): the diagonal makes the mean of the
// three shear moduli G; each edge then makes Young's modulus exact along its axis.
SpringSet baudet_springs(const Material& material, const Eigen::Vector3d& size) {
  const double g = shear_modulus(material);
  const double e = material.young_modulus;
  const double nu = material.poisson_ratio;
  const Eigen::Vector3d sq = size.cwiseProduct(size);
  const double diagonal_sq = sq.sum();
  const double volume = size.prod();
  SpringSet springs;
  springs.diagonal = 3.0 * g * diagonal_sq * volume / (4.0 * (sq.x() * sq.y() + sq.y() * sq.z() + sq.z() * sq.x()));
  for (int a = 0; a < 3; ++a) {
    const double others = diagonal_sq - sq[a];
    springs.edge[a] = e * volume / (4.0 * sq[a]) - springs.diagonal * (sq[a] - nu * others) / diagonal_sq;
  }
  return springs;
}

// Normal block of the lattice's elasticity tensor that the springs alone give (section 2):
// C_ab = (1/V) sum_springs k l^2 n_a^2 n_b^2.
Eigen::Matrix3d spring_normal_stiffness(const SpringSet& springs, const Eigen::Vector3d& size) {
  const Eigen::Vector3d sq = size.cwiseProduct(size);
  const double diagonal_sq = sq.sum();
  const double volume = size.prod();
  Eigen::Matrix3d c;
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) {
      c(a, b) = 4.0 * springs.diagonal * sq[a] * sq[b] / (diagonal_sq * volume);
    }
    c(a, a) += 4.0 * springs.edge[a] * sq[a] / volume;
  }
  return c;
}

Eigen::Matrix3d isotropic_normal_stiffness(const Material& material) {
  const double lambda = lame_lambda(material);
  const double g = shear_modulus(material);
  Eigen::Matrix3d c = Eigen::Matrix3d::Constant(lambda);
  c.diagonal().array() += 2.0 * g;
  return c;
}

// Largest aspect ratio (long / short side) at which every edge stiffness stays positive, for this
// Poisson's ratio, found by bisection on a 1 x 1 x r cell.
double aspect_ratio_limit(const Material& material) {
  double low = 1.0;
  double high = 10.0;
  for (int iteration = 0; iteration < 60; ++iteration) {
    const double mid = 0.5 * (low + high);
    const SpringSet springs = baudet_springs(material, Eigen::Vector3d(1.0, 1.0, mid));
    (springs.edge.minCoeff() > 0.0 ? low : high) = mid;
  }
  return low;
}

// Exact-bending springs (docs/model-exact-bending.md section 2): edges beta E h, the paper's diagonals.
SpringSet exact_bending_springs(const Material& material, double h, double edge_fraction) {
  SpringSet springs;
  springs.edge.setConstant(edge_fraction * material.young_modulus * h);
  springs.diagonal = 0.75 * shear_modulus(material) * h;
  return springs;
}

Status check_exact_bending(const ExactBendingParameters& p, const Eigen::Vector3d& cell_size) {
  if (!std::isfinite(p.edge_fraction) || p.edge_fraction <= 0.0) {
    std::ostringstream message;
    message << "edge_fraction = " << p.edge_fraction << ": the exact-bending model needs a finite beta > 0";
    return Status::error(message.str());
  }
  if (!std::isfinite(p.twist_factor) || p.twist_factor < 0.0) {
    std::ostringstream message;
    message << "twist_factor = " << p.twist_factor << ": the exact-bending model needs a finite zeta >= 0";
    return Status::error(message.str());
  }
  if (cell_size.maxCoeff() - cell_size.minCoeff() > 1e-9 * cell_size.maxCoeff()) {
    std::ostringstream message;
    message << "cell size " << cell_size.x() << " x " << cell_size.y() << " x " << cell_size.z()
            << " m: the exact-bending model is derived for cubic cells only; use equal sides or the "
               "baudet2007 model";
    return Status::error(message.str());
  }
  return {};
}

}  // namespace

const char* cell_model_name(CellModel model) {
  switch (model) {
    case CellModel::kBaudet2007: return "baudet2007";
    case CellModel::kExactBending: return "exact-bending";
  }
  return "unknown";
}

Result<CellModel> parse_cell_model(const std::string& name) {
  for (CellModel model : {CellModel::kBaudet2007, CellModel::kExactBending}) {
    if (name == cell_model_name(model)) return model;
  }
  return Status::error("unknown cell model '" + name + "': expected baudet2007 or exact-bending");
}

Result<CellCalibration> calibrate_cell(CellModel model, const Material& material, const Eigen::Vector3d& cell_size,
                                       const ExactBendingParameters& parameters) {
  if (Status status = validate(material); !status) return status;
  if (!cell_size.allFinite() || cell_size.minCoeff() <= 0.0) {
    std::ostringstream message;
    message << "cell size " << cell_size.transpose() << " m: every side must be a finite number > 0";
    return Status::error(message.str());
  }
  SpringSet springs{Eigen::Vector3d::Zero(), 0.0};
  double twist_stiffness = 0.0;
  switch (model) {
    case CellModel::kBaudet2007: springs = baudet_springs(material, cell_size); break;
    case CellModel::kExactBending:
      if (Status status = check_exact_bending(parameters, cell_size); !status) return status;
      springs = exact_bending_springs(material, cell_size.x(), parameters.edge_fraction);
      twist_stiffness = parameters.twist_factor * shear_modulus(material);
      break;
  }
  if (springs.edge.minCoeff() <= 0.0) {
    Eigen::Index axis = 0;
    springs.edge.minCoeff(&axis);
    std::ostringstream message;
    message << "cell size " << cell_size.x() << " x " << cell_size.y() << " x " << cell_size.z() << " m (aspect ratio "
            << cell_size.maxCoeff() / cell_size.minCoeff() << ") gives the "
            << "xyz"[axis] << "-edges a stiffness of " << springs.edge[axis]
            << " N/m <= 0 at nu = " << material.poisson_ratio << "; with the " << cell_model_name(model)
            << " model a cell elongated along one axis needs an aspect ratio below about "
            << aspect_ratio_limit(material) << " at this nu (docs/model-baudet2007.md section 4)";
    return Status::error(message.str());
  }
  CellCalibration calibration;
  calibration.edge_stiffness = springs.edge;
  calibration.diagonal_stiffness = springs.diagonal;
  calibration.correction = isotropic_normal_stiffness(material) - spring_normal_stiffness(springs, cell_size);
  calibration.twist_stiffness = twist_stiffness;
  return calibration;
}

}  // namespace cubespring
