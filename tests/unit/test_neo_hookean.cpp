// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The neo-Hookean cell law (docs/model-neo-hookean.md): forces and stiffness against finite
// differences of the energy, rotation invariance, the closed form of the law under homogeneous
// deformations (the test writes it out itself), the barrier, the small-strain moduli.
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "cubespring/static_solver.h"
#include "cubespring/validation/experiments.h"
#include "model/neo_hookean_cell.h"
#include "test_support.h"

namespace cubespring {
namespace {

Model law_model(const Eigen::Vector3i& cells, double poisson, CellModel cell_model,
                const Eigen::Vector3d& cell_size = Eigen::Vector3d::Constant(0.01)) {
  Material material = test::notes_material(poisson);
  material.young_modulus = 5e3;
  LatticeDesc desc = box_lattice(cells, cell_size, material);
  desc.model = cell_model;
  desc.law = CellLaw::kNeoHookean;
  Result<Model> model = build_model(desc);
  EXPECT_TRUE(model.ok()) << model.message();
  return std::move(model).value();
}

// The compressible neo-Hookean energy density in CalculiX's form, written out here:
// W = C10 (J^-2/3 I1 - 3) + (J - 1)^2 / D1, C10 = G / 2, D1 = 2 / B; plus the barrier
// B (J0 - J)^3 / (J0^2 J) below J0 = 0.5.
double closed_form_density(const Material& m, const Eigen::Matrix3d& f) {
  const double g = m.young_modulus / (2.0 * (1.0 + m.poisson_ratio));
  const double b = m.young_modulus / (3.0 * (1.0 - 2.0 * m.poisson_ratio));
  const double j = f.determinant();
  double w = 0.5 * g * (std::pow(j, -2.0 / 3.0) * (f.transpose() * f).trace() - 3.0) + 0.5 * b * (j - 1.0) * (j - 1.0);
  if (j < 0.5) w += b * std::pow(0.5 - j, 3) / (0.25 * j);
  return w;
}

Eigen::Matrix3Xd deformed(const Model& model, const Eigen::Matrix3d& f) { return f * model.rest_positions; }

Eigen::Matrix3d rotation(double angle, const Eigen::Vector3d& axis) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

// A large, non-homogeneous deformation: a stretch, a shear, a twist and noise of 15% of a cell.
Eigen::Matrix3Xd large_deformation(const Model& model, double compression) {
  Eigen::Matrix3d f;
  f << 1.1, 0.2, 0.0, -0.1, 0.95, 0.15, 0.05, 0.0, compression;
  Eigen::Matrix3Xd x = rotation(0.4, {1, 2, 3}) * f * test::perturbed(model, 0.0015, 11);
  return x;
}

class NeoHookeanCell : public ::testing::TestWithParam<CellModel> {};

// The least and the largest J of a body's cells.
std::pair<double, double> volume_ratio_range(const Model& model, const Eigen::Matrix3Xd& x) {
  double least = 1e300, largest = -1e300;
  for (int c = 0; c < model.num_cells(); ++c) {
    const double j = cell_signed_volume(model, x, c) / model.rest_cell_volume();
    least = std::min(least, j);
    largest = std::max(largest, j);
  }
  return {least, largest};
}

TEST_P(NeoHookeanCell, ForcesAreMinusTheEnergyGradient) {
  for (double compression : {0.9, 0.3}) {  // 0.3: every cell's J in the barrier's range
    const Model model = law_model({2, 2, 2}, 0.45, GetParam());
    const Eigen::Matrix3Xd x = large_deformation(model, compression);
    if (compression < 0.5) {
      ASSERT_LT(volume_ratio_range(model, x).second, kBarrierVolumeRatio);
    }
    const Eigen::Matrix3Xd forces = test::elastic_forces(model, x);
    const double largest_error = (test::finite_difference_forces(model, x) - forces).cwiseAbs().maxCoeff();
    EXPECT_LT(largest_error, 1e-6 * forces.cwiseAbs().maxCoeff()) << "compression " << compression;
  }
}

TEST_P(NeoHookeanCell, ExactStiffnessIsTheForcesDerivative) {
  for (double compression : {0.9, 0.3}) {
    const Model model = law_model({2, 1, 1}, 0.45, GetParam());
    const Eigen::Matrix3Xd x = large_deformation(model, compression);
    if (compression < 0.5) {
      ASSERT_LT(volume_ratio_range(model, x).second, kBarrierVolumeRatio);
    }
    const Eigen::MatrixXd k = test::dense_stiffness(model, x, StiffnessKind::kExact);
    const Eigen::MatrixXd difference = test::finite_difference_stiffness(model, x);
    EXPECT_LT((k - difference).cwiseAbs().maxCoeff(), 1e-5 * k.cwiseAbs().maxCoeff()) << "compression " << compression;
  }
}

// Below J = 0.05 the volume terms go on as Taylor polynomials, inverted cells included: forces
// and stiffness stay the energy's derivatives there too.
TEST_P(NeoHookeanCell, DerivativesHoldWhereTheBarrierIsContinuedAndInverted) {
  for (double j : {0.02, -0.03}) {
    const Model model = law_model({1, 1, 1}, 0.45, GetParam());
    const Eigen::Matrix3Xd x = Eigen::Vector3d(1.0, 1.0, j).asDiagonal() * test::perturbed(model, 2e-4, 5);
    const auto [least, largest] = volume_ratio_range(model, x);
    ASSERT_LT(largest, 0.05) << "J " << j;
    const Eigen::Matrix3Xd forces = test::elastic_forces(model, x);
    ASSERT_TRUE(forces.allFinite());
    EXPECT_LT((test::finite_difference_forces(model, x) - forces).cwiseAbs().maxCoeff(),
              1e-6 * forces.cwiseAbs().maxCoeff())
        << "J " << j;
    const Eigen::MatrixXd k = test::dense_stiffness(model, x, StiffnessKind::kExact);
    EXPECT_LT((k - test::finite_difference_stiffness(model, x)).cwiseAbs().maxCoeff(), 1e-5 * k.cwiseAbs().maxCoeff())
        << "J " << j;
  }
}

TEST_P(NeoHookeanCell, ApproximateStiffnessIsPositiveSemiDefinite) {
  const Model model = law_model({2, 2, 1}, 0.49, GetParam());
  for (const Eigen::Matrix3Xd& x : {model.rest_positions, large_deformation(model, 0.6)}) {
    const Eigen::MatrixXd k = test::dense_stiffness(model, x, StiffnessKind::kPositiveSemiDefinite);
    const Eigen::VectorXd eigenvalues = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(k).eigenvalues();
    EXPECT_GT(eigenvalues.minCoeff(), -1e-9 * eigenvalues.maxCoeff());
  }
}

TEST_P(NeoHookeanCell, EnergyAndForcesAreRotationInvariant) {
  const Model model = law_model({2, 2, 2}, 0.45, GetParam());
  const Eigen::Matrix3Xd x = large_deformation(model, 0.7);
  const Eigen::Matrix3d r = rotation(2.1, {-1, 0.5, 2});
  EXPECT_NEAR(elastic_energy(model, r * x), elastic_energy(model, x), 1e-10 * elastic_energy(model, x));
  const Eigen::Matrix3Xd forces = test::elastic_forces(model, x);
  EXPECT_LT((test::elastic_forces(model, r * x) - r * forces).cwiseAbs().maxCoeff(),
            1e-9 * forces.cwiseAbs().maxCoeff());
}

// Under any homogeneous deformation the lattice stores exactly the law's energy, whatever the
// springs: stretches, compressions down into the barrier, shears, each also rotated.
TEST_P(NeoHookeanCell, HomogeneousDeformationsStoreTheClosedFormEnergy) {
  for (double poisson : {0.3, 0.45, 0.49}) {
    const Model model = law_model({3, 2, 2}, poisson, GetParam());
    const double volume = model.num_cells() * model.rest_cell_volume();
    std::vector<Eigen::Matrix3d> gradients;
    for (double stretch : {0.6, 0.8, 1.0, 1.5}) {
      gradients.push_back(Eigen::Vector3d(stretch, 1.0 / std::sqrt(stretch), 1.0 / std::sqrt(stretch)).asDiagonal());
    }
    for (double j : {0.3, 0.9, 1.05}) gradients.push_back(std::cbrt(j) * Eigen::Matrix3d::Identity());
    Eigen::Matrix3d shear = Eigen::Matrix3d::Identity();
    shear(0, 1) = 0.5;
    gradients.push_back(shear);
    for (const Eigen::Matrix3d& f : gradients) {
      for (const Eigen::Matrix3d& r : {Eigen::Matrix3d(Eigen::Matrix3d::Identity()), rotation(0.7, {1, 1, 0})}) {
        const double expected = volume * closed_form_density(model.materials[0], r * f);
        EXPECT_NEAR(elastic_energy(model, deformed(model, r * f)), expected, 1e-9 * std::max(1e-6, std::abs(expected)))
            << "nu " << poisson << ", F\n"
            << r * f;
      }
    }
  }
}

// The interior of a block whose boundary is driven homogeneously relaxes to the homogeneous
// state (the static solver from rest, the boundary ramped to its place), so the block stores
// V W(F).
TEST_P(NeoHookeanCell, DrivenBlockRelaxesToTheClosedForm) {
  const Model model = law_model({4, 4, 4}, 0.45, GetParam());
  Eigen::Matrix3d f = Eigen::Matrix3d::Identity();
  f(0, 2) = 0.5;  // simple shear, gamma = 0.5
  f *= 0.97;      // and a compression, J = 0.91
  Constraints constraints(model);
  for (int n = 0; n < model.num_nodes(); ++n) {
    const Eigen::Vector3i g = model.node_grid_index[n];
    if ((g.array() == 0).any() || (g.array() == 4).any()) {
      ASSERT_TRUE(constraints.prescribe_position(n, f * model.rest_positions.col(n)));
    }
  }
  State state = rest_state(model);
  StaticSettings settings;
  settings.initial_load_steps = 4;
  const StaticReport report = solve_static(model, constraints, Loads{}, settings, state);
  ASSERT_TRUE(report.converged) << report.message;
  const double expected = 64 * model.rest_cell_volume() * closed_form_density(model.materials[0], f);
  EXPECT_NEAR(elastic_energy(model, state.positions), expected, 1e-6 * expected);
  EXPECT_LT((state.positions - deformed(model, f)).cwiseAbs().maxCoeff(), 1e-9);
}

TEST_P(NeoHookeanCell, BarrierGrowsWithoutBoundAsTheVolumeVanishes) {
  const Model model = law_model({1, 1, 1}, 0.45, GetParam());
  double previous = 0.0;
  for (double j : {0.5, 0.2, 0.1, 0.06}) {
    const double energy = elastic_energy(model, deformed(model, Eigen::Vector3d(1, 1, j).asDiagonal()));
    EXPECT_GT(energy, 1.5 * previous) << "J " << j;
    previous = energy;
  }
  // a cell turned inside out is pushed back out: its force opens it
  const Eigen::Matrix3Xd x = deformed(model, Eigen::Vector3d(1, 1, -0.05).asDiagonal());
  const Eigen::Matrix3Xd forces = test::elastic_forces(model, x);
  ASSERT_TRUE(forces.allFinite());
  for (int n = 0; n < model.num_nodes(); ++n) {
    const double side = model.node_grid_index[n].z() == 1 ? 1.0 : -1.0;
    EXPECT_GT(side * forces(2, n), 0.0) << "node " << n;  // the z = 1 face, below z = 0 now, goes up
  }
}

INSTANTIATE_TEST_SUITE_P(BothCellModels, NeoHookeanCell,
                         ::testing::Values(CellModel::kBaudet2007, CellModel::kExactBending), [](const auto& test) {
                           return test.param == CellModel::kBaudet2007 ? "Baudet2007" : "ExactBending";
                         });

// E, nu, B and G at small strain, from the virtual experiments, for either cell model.
TEST(NeoHookeanLaw, SmallStrainModuliAreExact) {
  for (CellModel cell_model : {CellModel::kBaudet2007, CellModel::kExactBending}) {
    for (double poisson : {0.3, 0.45, 0.49}) {
      ExperimentSettings settings;
      settings.material = test::notes_material(poisson);
      settings.model = cell_model;
      settings.law = CellLaw::kNeoHookean;
      settings.cells = {4, 4, 4};
      for (Experiment experiment : {Experiment::kElongation, Experiment::kInflation, Experiment::kShear}) {
        const Result<ExperimentResult> result = run_experiment(experiment, settings);
        ASSERT_TRUE(result.ok()) << result.message();
        const Moduli& measured = result.value().measured;
        const Moduli& expected = result.value().expected;
        const std::string where = std::string(experiment_name(experiment)) + ", nu " + std::to_string(poisson) + ", " +
                                  cell_model_name(cell_model);
        if (measured.young_modulus) {
          EXPECT_NEAR(*measured.young_modulus / *expected.young_modulus, 1.0, 1e-3) << where;
        }
        if (measured.poisson_ratio) {
          EXPECT_NEAR(*measured.poisson_ratio, *expected.poisson_ratio, 1e-3) << where;
        }
        if (measured.bulk_modulus) {
          EXPECT_NEAR(*measured.bulk_modulus / *expected.bulk_modulus, 1.0, 1e-3) << where;
        }
        if (measured.shear_modulus) {
          EXPECT_NEAR(*measured.shear_modulus / *expected.shear_modulus, 1.0, 1e-3) << where;
        }
      }
    }
  }
}

// A model whose law was switched after it was built has none of the law's constants: refused.
TEST(NeoHookeanLaw, AModelWithoutTheLawsConstantsIsRefused) {
  Model model = test::box_model({1, 1, 1}, test::notes_material(0.3));
  model.cell_law = CellLaw::kNeoHookean;
  EXPECT_THROW((void)elastic_energy(model, model.rest_positions), std::invalid_argument);
  EXPECT_THROW((void)test::elastic_forces(model, model.rest_positions), std::invalid_argument);
}

// The term's own inverse cube root (multiplications only, so that the grid passes vectorise it)
// against the C library's cube root, over the range it claims: relative error within 4 ulp.
TEST(NeoHookeanLaw, LatticeInverseCubeRootFollowsTheLibrarys) {
  double worst = 0.0, worst_at = 0.0;
  for (int exponent = -93; exponent < 93; ++exponent) {
    for (double mantissa = 1.0; mantissa < 2.0; mantissa += 1.0 / 64.0 + 1e-9) {
      const double x = std::ldexp(mantissa, exponent);
      const double error = std::abs(lattice_inverse_cube_root(x) * std::cbrt(x) - 1.0);
      if (error > worst) worst = error, worst_at = x;
    }
  }
  EXPECT_LT(worst, 4.0 * std::numeric_limits<double>::epsilon()) << "at " << worst_at;
  for (const double x : {kSmallestVolumeRatio, kBarrierVolumeRatio, 1.0, 8.0, 27.0, 1e-27}) {
    EXPECT_NEAR(lattice_inverse_cube_root(x), 1.0 / std::cbrt(x), 4e-16 / std::cbrt(x)) << x;
  }
  EXPECT_TRUE(std::isnan(lattice_inverse_cube_root(std::nan(""))));
}

TEST(NeoHookeanLaw, NamesParseBothWays) {
  for (CellLaw law : {CellLaw::kSprings, CellLaw::kNeoHookean}) {
    const Result<CellLaw> parsed = parse_cell_law(cell_law_name(law));
    ASSERT_TRUE(parsed.ok());
    EXPECT_EQ(parsed.value(), law);
  }
  const Result<CellLaw> bad = parse_cell_law("mooney");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.message().find("'mooney'"), std::string::npos) << bad.message();
  EXPECT_NE(bad.message().find("neo-hookean"), std::string::npos) << bad.message();
}

}  // namespace
}  // namespace cubespring
