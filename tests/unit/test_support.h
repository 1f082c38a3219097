// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Shared fixtures of the unit tests.
#pragma once

#include <limits>
#include <random>

#include <gtest/gtest.h>
#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

#include "cubespring/forces.h"
#include "cubespring/model.h"
#include "cubespring/state.h"
#include "cubespring/stiffness.h"

namespace cubespring::test {

/// E = 1e5 Pa, h = 0.01 m: the defaults of the model notes' numeric checks.
inline Material notes_material(double poisson_ratio) {
  Material m;
  m.young_modulus = 1e5;
  m.poisson_ratio = poisson_ratio;
  m.density = 1000.0;
  return m;
}

inline Model box_model(const Eigen::Vector3i& cells, const Material& material,
                       const Eigen::Vector3d& cell_size = Eigen::Vector3d::Constant(0.01)) {
  Result<Model> model = build_model(box_lattice(cells, cell_size, material));
  EXPECT_TRUE(model.ok()) << model.message();
  return std::move(model).value();
}

/// Rest positions plus a random perturbation of the given size [m].
inline Eigen::Matrix3Xd perturbed(const Model& model, double size, unsigned seed = 7) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> dist(-size, size);
  Eigen::Matrix3Xd x = model.rest_positions;
  for (Eigen::Index i = 0; i < x.size(); ++i) x.data()[i] += dist(rng);
  return x;
}

/// Internal (elastic) force at positions, no damping, no loads.
inline Eigen::Matrix3Xd elastic_forces(const Model& model, const Eigen::Matrix3Xd& x) {
  State state;
  state.positions = x;
  state.velocities.setZero(3, x.cols());
  ForceWorkspace ws;
  Eigen::Matrix3Xd forces;
  compute_forces(model, state, Loads{}, ForceOptions{false, 1}, ws, forces);
  return forces;
}

/// The options with a grid fill no body reaches: the force passes take the spring lists.
inline ForceOptions on_spring_lists(ForceOptions options) {
  options.min_grid_fill = std::numeric_limits<double>::quiet_NaN();
  return options;
}

/// The assembled stiffness at positions x as a dense matrix (small bodies only).
inline Eigen::MatrixXd dense_stiffness(const Model& model, const Eigen::Matrix3Xd& x, StiffnessKind kind) {
  StiffnessAssembler assembler(model);
  SparseMatrix k;
  assembler.assemble(model, x, kind, 1.0, 0.0, k);
  return Eigen::MatrixXd(k);
}

/// Zero eigenvalues (below 1e-9 of the largest) of a free body's stiffness at rest; fails the test
/// if any eigenvalue is clearly negative.
inline int zero_modes(const Model& model) {
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(
      dense_stiffness(model, model.rest_positions, StiffnessKind::kExact));
  const Eigen::VectorXd& values = solver.eigenvalues();
  EXPECT_GT(values.minCoeff(), -1e-9 * values.maxCoeff());
  return static_cast<int>((values.array().abs() < 1e-9 * values.maxCoeff()).count());
}

/// Minus the gradient of the elastic energy by central differences of step 1e-7 m [N].
inline Eigen::Matrix3Xd finite_difference_forces(const Model& model, const Eigen::Matrix3Xd& x) {
  const double step = 1e-7;
  Eigen::Matrix3Xd forces(3, x.cols());
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    Eigen::Matrix3Xd plus = x, minus = x;
    plus.data()[i] += step;
    minus.data()[i] -= step;
    forces.data()[i] = -(elastic_energy(model, plus) - elastic_energy(model, minus)) / (2 * step);
  }
  return forces;
}

/// The stiffness as minus the derivative of the elastic forces, by central differences [N/m].
inline Eigen::MatrixXd finite_difference_stiffness(const Model& model, const Eigen::Matrix3Xd& x) {
  const double step = 1e-7;
  Eigen::MatrixXd k(x.size(), x.size());
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    Eigen::Matrix3Xd plus = x, minus = x;
    plus.data()[i] += step;
    minus.data()[i] -= step;
    const Eigen::Matrix3Xd df = elastic_forces(model, plus) - elastic_forces(model, minus);
    k.col(i) = -Eigen::Map<const Eigen::VectorXd>(df.data(), df.size()) / (2 * step);
  }
  return k;
}

}  // namespace cubespring::test
