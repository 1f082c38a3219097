// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The exact-bending model (docs/model-exact-bending.md): constants, exact affine response, the twist
// term on each mode, zero modes, gradients, the cantilever, and checkerboard motion.
#include <cmath>
#include <random>

#include <gtest/gtest.h>
#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "cubespring/integrator.h"
#include "cubespring/stiffness.h"
#include "cubespring/validation/experiments.h"
#include "test_support.h"

namespace cubespring {
namespace {

using test::dense_stiffness;
using test::notes_material;
using test::zero_modes;

Model exact_model(const Eigen::Vector3i& cells, const Material& material, ExactBendingParameters p = {}) {
  LatticeDesc desc = box_lattice(cells, Eigen::Vector3d::Constant(0.01), material);
  desc.model = CellModel::kExactBending;
  desc.exact_bending = p;
  Result<Model> model = build_model(desc);
  EXPECT_TRUE(model.ok()) << model.message();
  return std::move(model).value();
}

TEST(ExactBending, ConstantsAtNu03) {
  Result<CellCalibration> c =
      calibrate_cell(CellModel::kExactBending, notes_material(0.3), Eigen::Vector3d::Constant(0.01));
  ASSERT_TRUE(c.ok()) << c.message();
  EXPECT_NEAR(c->edge_stiffness.x(), 70.0, 1e-12);              // beta E h
  EXPECT_NEAR(c->diagonal_stiffness, 288.4615384615385, 1e-9);  // 3 G h / 4
  EXPECT_NEAR(c->correction(0, 0), 6.8154e4, 1);                // lambda + G - 4 beta E
  EXPECT_NEAR(c->correction(0, 1), 1.9231e4, 1);                // lambda - G
  EXPECT_NEAR(c->twist_stiffness, shear_modulus(notes_material(0.3)) / 48, 1e-9);
}

TEST(ExactBending, AffineResponseIsIsotropicAndMeasuredModuliExact) {
  for (double nu : {0.0, 0.3, 0.45, 0.49}) {
    ExperimentSettings s;
    s.material = notes_material(nu);
    s.model = CellModel::kExactBending;
    s.strain = 1e-7;
    for (Experiment e : {Experiment::kElongation, Experiment::kInflation, Experiment::kShear}) {
      Result<ExperimentResult> r = run_experiment(e, s);
      ASSERT_TRUE(r.ok()) << r.message();
      if (r->error.young_modulus) {
        EXPECT_NEAR(*r->error.young_modulus, 0.0, 1e-5) << nu;
      }
      if (r->error.poisson_ratio) {
        EXPECT_NEAR(*r->error.poisson_ratio, 0.0, 1e-5) << nu;
      }
      if (r->error.bulk_modulus) {
        EXPECT_NEAR(*r->error.bulk_modulus, 0.0, 1e-5) << nu;
      }
      if (r->error.shear_modulus) {
        EXPECT_NEAR(*r->error.shear_modulus, 0.0, 1e-5) << nu;
      }
    }
  }
}

// Twist energy alone: the model with zeta minus the same model without.
double twist_energy_of(const Model& with, const Model& without, const Eigen::Matrix3Xd& x) {
  return elastic_energy(with, x) - elastic_energy(without, x);
}

TEST(ExactBending, TwistTermSeesOnlyTheTwistModes) {
  const Material m = notes_material(0.3);
  const Model with = exact_model({1, 1, 1}, m);
  const Model without = exact_model({1, 1, 1}, m, {0.07, 0.0});
  const double h = 0.01;
  const double scale = shear_modulus(m) * h * h * h;
  // any uniform deformation, finite too: zero
  std::mt19937 rng(3);
  std::normal_distribution<double> normal;
  Eigen::Matrix3d f = Eigen::Matrix3d::Identity();
  for (int i = 0; i < 9; ++i) f.data()[i] += 0.2 * normal(rng);
  EXPECT_NEAR(twist_energy_of(with, without, f * with.rest_positions), 0.0, 1e-12 * scale);
  // u_x = eps s_y s_z h / 2: W = zeta G h^3 (2 eps)^2, zeta = 1/48 by default
  const double eps = 1e-3;
  Eigen::Matrix3Xd x = with.rest_positions;
  for (int n = 0; n < with.num_nodes(); ++n) {
    const Eigen::Vector3i& i = with.node_grid_index[n];
    x(0, n) += eps * (2 * i.y() - 1) * (2 * i.z() - 1) * h / 2;
  }
  EXPECT_NEAR(twist_energy_of(with, without, x), shear_modulus(m) / 48 * h * h * h * 4 * eps * eps,
              1e-9 * scale * eps * eps);
  // the six bending modes u_a = s_a s_b and the mode u_a = s_x s_y s_z: zero
  for (int a = 0; a < 3; ++a) {
    for (int b = -1; b < 3; ++b) {
      if (b == a) continue;
      Eigen::Matrix3Xd y = with.rest_positions;
      for (int n = 0; n < with.num_nodes(); ++n) {
        const Eigen::Vector3i s = 2 * with.node_grid_index[n].array() - 1;
        y(a, n) += eps * h * (b < 0 ? s.x() * s.y() * s.z() : s[a] * s[b]);
      }
      EXPECT_NEAR(twist_energy_of(with, without, y), 0.0, 1e-12 * scale) << a << " " << b;
    }
  }
}

TEST(ExactBending, FreeBlocksHaveOnlyTheSixRigidZeroModes) {
  for (double nu : {0.0, 0.3, 0.49}) {
    EXPECT_EQ(zero_modes(exact_model({1, 1, 1}, notes_material(nu))), 6) << nu;
    EXPECT_EQ(zero_modes(exact_model({2, 2, 2}, notes_material(nu))), 6) << nu;
  }
  EXPECT_EQ(zero_modes(exact_model({2, 2, 2}, notes_material(0.3), {0.07, 0.0})), 9);
}

TEST(ExactBending, ForcesAndStiffnessMatchFiniteDifferences) {
  const Model model = exact_model({2, 1, 1}, notes_material(0.3));
  const Eigen::Matrix3Xd x = test::perturbed(model, 1.5e-3);
  const Eigen::Matrix3Xd f = test::elastic_forces(model, x);
  const Eigen::MatrixXd k = dense_stiffness(model, x, StiffnessKind::kExact);
  const double step = 1e-7;
  double worst_force = 0, worst_stiffness = 0;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    Eigen::Matrix3Xd plus = x, minus = x;
    plus.data()[i] += step;
    minus.data()[i] -= step;
    const double de = (elastic_energy(model, plus) - elastic_energy(model, minus)) / (2 * step);
    worst_force = std::max(worst_force, std::abs(de + f.data()[i]));
    const Eigen::Matrix3Xd df = test::elastic_forces(model, plus) - test::elastic_forces(model, minus);
    const Eigen::VectorXd column = -Eigen::Map<const Eigen::VectorXd>(df.data(), df.size()) / (2 * step);
    worst_stiffness = std::max(worst_stiffness, (column - k.col(i)).cwiseAbs().maxCoeff());
  }
  EXPECT_LT(worst_force, 1e-6 * f.cwiseAbs().maxCoeff());
  EXPECT_LT(worst_stiffness, 1e-6 * k.cwiseAbs().maxCoeff());
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> psd(dense_stiffness(model, x, StiffnessKind::kPositiveSemiDefinite));
  EXPECT_GT(psd.eigenvalues().minCoeff(), -1e-9 * psd.eigenvalues().maxCoeff());
}

TEST(ExactBending, RigidRotationGivesNoForceAndForcesBalance) {
  const Model model = exact_model({2, 2, 2}, notes_material(0.45));
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(M_PI / 6, Eigen::Vector3d(0.3, -0.5, 0.8).normalized()).toRotationMatrix();
  EXPECT_LT(test::elastic_forces(model, rotation * model.rest_positions).cwiseAbs().maxCoeff(), 1e-10 * 1e5 * 1e-4);
  const Eigen::Matrix3Xd x = test::perturbed(model, 2e-3);
  const Eigen::Matrix3Xd f = test::elastic_forces(model, x);
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();
  for (int n = 0; n < model.num_nodes(); ++n) torque += Eigen::Vector3d(x.col(n)).cross(Eigen::Vector3d(f.col(n)));
  EXPECT_LT(f.rowwise().sum().cwiseAbs().maxCoeff(), 1e-12 * f.cwiseAbs().maxCoeff());
  EXPECT_LT(torque.cwiseAbs().maxCoeff(), 1e-12 * f.cwiseAbs().maxCoeff());
  const Eigen::Matrix3Xd rotated = test::elastic_forces(model, rotation * x);
  EXPECT_LT((rotated - rotation * f).cwiseAbs().maxCoeff(), 1e-9 * f.cwiseAbs().maxCoeff());
}

double cantilever_tip_mm(double nu, const Eigen::Vector3i& cells, CellModel model, ExactBendingParameters p = {}) {
  ExperimentSettings s;
  s.material.young_modulus = 1e6;
  s.material.poisson_ratio = nu;
  s.cells = cells;
  s.cell_size = Eigen::Vector3d::Constant(0.16 / cells.x());
  s.gravity = 9.81e-3;  // linear; scaled back below
  s.model = model;
  s.exact_bending = p;
  Result<ExperimentResult> r = run_experiment(Experiment::kCantilever, s);
  EXPECT_TRUE(r.ok()) << r.message();
  return r.ok() ? -*r->tip_deflection * 1e6 : 0.0;
}

TEST(ExactBending, CantileverMatchesTheNotes) {
  // beyond-the-paper.md section 4.7: 6.374 / 6.274 / 6.054 / 5.965 mm (+-0.3%)
  const std::vector<std::pair<double, double>> table = {{0.0, 6.374}, {0.3, 6.274}, {0.45, 6.054}, {0.49, 5.965}};
  for (const auto& [nu, tip] : table) {
    EXPECT_NEAR(cantilever_tip_mm(nu, {16, 4, 4}, CellModel::kExactBending, {0.07, 1.0 / 12}) / tip, 1.0, 3e-3) << nu;
    // the default twist factor moves the tip by less than 0.2%
    EXPECT_NEAR(cantilever_tip_mm(nu, {16, 4, 4}, CellModel::kExactBending) / tip, 1.0, 2e-3) << nu;
  }
}

TEST(ExactBending, RefinedCantileverWithinHalfAPercent) {
  // 32x8x8 cells of 0.005 m at nu = 0.3 against the converged 3D reference of 6.282 mm
  EXPECT_NEAR(cantilever_tip_mm(0.3, {32, 8, 8}, CellModel::kExactBending) / 6.282, 1.0, 5e-3);
}

TEST(ExactBending, PaperParametersReproduceThePaper) {
  // beta = (4 nu + 1) / (8 (1 + nu)) and zeta = 0 give the paper's springs and correction
  const double nu = 0.3;
  const double tip = cantilever_tip_mm(nu, {16, 4, 4}, CellModel::kExactBending, {(4 * nu + 1) / (8 * (1 + nu)), 0.0});
  EXPECT_NEAR(tip / cantilever_tip_mm(nu, {16, 4, 4}, CellModel::kBaudet2007), 1.0, 1e-9);
}

TEST(ExactBending, RefusesNonCubicCellsAndBadParameters) {
  Result<CellCalibration> flat =
      calibrate_cell(CellModel::kExactBending, notes_material(0.3), Eigen::Vector3d(0.01, 0.01, 0.012));
  ASSERT_FALSE(flat.ok());
  EXPECT_NE(flat.message().find("cubic cells only"), std::string::npos) << flat.message();
  Result<CellCalibration> beta =
      calibrate_cell(CellModel::kExactBending, notes_material(0.3), Eigen::Vector3d::Constant(0.01), {0.0, 1.0 / 12});
  ASSERT_FALSE(beta.ok());
  EXPECT_NE(beta.message().find("edge_fraction"), std::string::npos);
  Result<CellCalibration> zeta =
      calibrate_cell(CellModel::kExactBending, notes_material(0.3), Eigen::Vector3d::Constant(0.01), {0.07, -1.0});
  ASSERT_FALSE(zeta.ok());
  EXPECT_NE(zeta.message().find("twist_factor"), std::string::npos);
  EXPECT_FALSE(parse_cell_model("exact").ok());
  EXPECT_EQ(parse_cell_model("exact-bending").value(), CellModel::kExactBending);
}

// Amplitude of the checkerboard mode u_x = (-1)^(j+k) in a displacement field (mass-weighted).
double checkerboard_amplitude(const Model& model, const Eigen::Matrix3Xd& u) {
  double projection = 0, norm = 0;
  for (int n = 0; n < model.num_nodes(); ++n) {
    const Eigen::Vector3i& i = model.node_grid_index[n];
    const double phi = (i.y() + i.z()) % 2 ? -1.0 : 1.0;
    projection += model.mass[n] * phi * u(0, n);
    norm += model.mass[n];
  }
  return projection / norm;
}

TEST(ExactBending, CheckerboardMotionStaysBounded) {
  // an undamped free 4x4x4 block started with the checkerboard velocity pattern of amplitude v0:
  // a zero-energy mode drifts as v0 t under the paper's model; the twist term bounds it
  const double v0 = 1e-3;
  for (CellModel cell_model : {CellModel::kBaudet2007, CellModel::kExactBending}) {
    LatticeDesc desc = box_lattice({4, 4, 4}, Eigen::Vector3d::Constant(0.01), notes_material(0.3));
    desc.model = cell_model;
    const Model model = build_model(desc).value();
    // lowest non-rigid frequency of the exact-bending block: sqrt of the 7th eigenvalue of M^-1/2 K M^-1/2
    const Eigen::MatrixXd k = dense_stiffness(model, model.rest_positions, StiffnessKind::kExact);
    Eigen::VectorXd inv_sqrt_mass(3 * model.num_nodes());
    for (int n = 0; n < model.num_nodes(); ++n)
      inv_sqrt_mass.segment<3>(3 * n).setConstant(1 / std::sqrt(model.mass[n]));
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> modes(inv_sqrt_mass.asDiagonal() * k * inv_sqrt_mass.asDiagonal());
    const int first_elastic = cell_model == CellModel::kBaudet2007 ? 9 : 6;
    const double omega_min = std::sqrt(modes.eigenvalues()[first_elastic]);

    State state = rest_state(model);
    for (int n = 0; n < model.num_nodes(); ++n) {
      const Eigen::Vector3i& i = model.node_grid_index[n];
      state.velocities(0, n) = v0 * ((i.y() + i.z()) % 2 ? -1.0 : 1.0);
    }
    StepSettings settings;
    settings.integrator = Integrator::kVelocityVerlet;
    settings.time_step = 0.2 * max_stable_time_step(model);
    Stepper stepper(model);
    // the paper's model: short enough for the drift (v0 t) to stay far below the cell size, where
    // the springs' second-order stretch would slow it; the twisted block: several periods of its
    // lowest elastic mode
    const double duration = cell_model == CellModel::kBaudet2007 ? 0.01 : 0.1;
    double largest = 0;
    while (state.time < duration) {
      ASSERT_TRUE(stepper.step(model, Constraints(model), Loads{}, settings, state).ok());
      largest = std::max(largest, std::abs(checkerboard_amplitude(model, state.positions - model.rest_positions)));
    }
    if (cell_model == CellModel::kBaudet2007) {
      EXPECT_NEAR(largest / (v0 * duration), 1.0, 0.05);  // free drift
    } else {
      EXPECT_LT(largest, 1.1 * v0 / omega_min);
      EXPECT_LT(largest, 0.1 * v0 * duration);
    }
  }
}

}  // namespace
}  // namespace cubespring
