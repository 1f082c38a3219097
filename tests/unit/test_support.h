// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Shared fixtures of the unit tests.
#pragma once

#include <random>

#include <gtest/gtest.h>

#include "cubespring/forces.h"
#include "cubespring/model.h"
#include "cubespring/state.h"

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

}  // namespace cubespring::test
