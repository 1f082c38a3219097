// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The paper's virtual experiments against the continuum moduli (model notes section 8, 3-6, 10, 12).
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "cubespring/constraints.h"
#include "cubespring/forces.h"
#include "cubespring/lattice.h"
#include "cubespring/static_solver.h"
#include "cubespring/validation/experiments.h"
#include "test_support.h"

namespace cubespring {
namespace {

// Runs an experiment; a failed run fails the test and stops it (the result would be empty).
ExperimentResult run(Experiment experiment, const ExperimentSettings& settings) {
  Result<ExperimentResult> result = run_experiment(experiment, settings);
  if (!result.ok()) {
    ADD_FAILURE() << experiment_name(experiment) << ": " << result.message();
    throw std::runtime_error(result.message());
  }
  return std::move(result).value();
}

ExperimentSettings cube(double nu, const Eigen::Vector3i& cells = {1, 1, 1}) {
  ExperimentSettings s;
  s.material = test::notes_material(nu);
  s.cells = cells;
  return s;
}

class SingleCube : public ::testing::TestWithParam<double> {};

TEST_P(SingleCube, ElongationGivesYoungsModulusAndPoissonRatio) {
  const ExperimentResult r = run(Experiment::kElongation, cube(GetParam()));
  EXPECT_NEAR(*r.error.young_modulus, 0.0, 1e-3);
  EXPECT_NEAR(*r.error.poisson_ratio, 0.0, 1e-3);
}

TEST_P(SingleCube, InflationGivesBulkModulus) {
  const ExperimentResult r = run(Experiment::kInflation, cube(GetParam()));
  EXPECT_NEAR(*r.error.bulk_modulus, 0.0, 1e-3);
}

TEST_P(SingleCube, AffineShearGivesShearModulusExactly) {
  ExperimentSettings s = cube(GetParam());
  s.strain = 1e-8;  // geometric nonlinearity ~ strain
  const ExperimentResult r = run(Experiment::kShear, s);
  EXPECT_NEAR(*r.error.shear_modulus, 0.0, 1e-7);
  for (int plane = 0; plane < 3; ++plane) EXPECT_NEAR((*r.shear_moduli)[plane] / shear_modulus(s.material), 1.0, 1e-7);
}

TEST_P(SingleCube, ForceControlledShearShowsTheFreeCornerSoftening) {
  // a free cube under pure-shear tractions: G / G0 = (1 + 4 nu) / (2 + 4 nu) (model notes 4.2)
  ExperimentSettings s = cube(GetParam());
  s.shear_control = ShearControl::kForce;
  const double nu = GetParam();
  const ExperimentResult r = run(Experiment::kShear, s);
  EXPECT_NEAR(*r.measured.shear_modulus / shear_modulus(s.material), (1 + 4 * nu) / (2 + 4 * nu), 1e-3);
}

INSTANTIATE_TEST_SUITE_P(PoissonRatios, SingleCube, ::testing::Values(0.0, 0.1, 0.3, 0.45, 0.49));

TEST(Experiments, SpringsAloneMissTheModuliAsTheNotesPredict) {
  // regression on the calibration: without the correction E/E0 = 2(4nu+1)/(4nu+3), nu = 1/(3+4nu)
  const double nu = 0.3;
  ExperimentSettings s = cube(nu);
  LatticeDesc desc = box_lattice(s.cells, s.cell_size, s.material);
  Result<Model> model = build_model(desc);
  ASSERT_TRUE(model.ok());
  for (auto& d : model->cell_correction) d.setZero();
  model->mark_changed();
  // uniaxial load of the paper's experiment, by hand on the springs-only model
  Loads loads;
  loads.nodal_forces = Eigen::Matrix3Xd::Zero(3, model->num_nodes());
  const double stress = 1e5 * 1e-4;
  for (int n = 0; n < model->num_nodes(); ++n) {
    loads.nodal_forces(0, n) = (model->node_grid_index[n].x() == 1 ? 1 : -1) * stress * 1e-4 / 4;
  }
  State state = rest_state(*model);
  ASSERT_TRUE(solve_static(*model, Constraints(*model), loads, StaticSettings{}, state).converged);
  const Eigen::Matrix3Xd u = displacements(*model, state);
  double axial = 0, lateral = 0;
  for (int n = 0; n < model->num_nodes(); ++n) {
    axial += (model->node_grid_index[n].x() == 1 ? 1 : -1) * u(0, n) / 4 / 0.01;
    lateral += (model->node_grid_index[n].y() == 1 ? 1 : -1) * u(1, n) / 4 / 0.01;
  }
  EXPECT_NEAR(stress / axial / 1e5, 2 * (4 * nu + 1) / (4 * nu + 3), 1e-3);
  EXPECT_NEAR(-lateral / axial, 1 / (3 + 4 * nu), 1e-3);
}

TEST(Experiments, LargerBlocksKeepTheModuli) {
  for (double nu : {0.3, 0.49}) {
    const ExperimentResult e = run(Experiment::kElongation, cube(nu, {4, 4, 4}));
    EXPECT_NEAR(*e.error.young_modulus, 0.0, 1e-3) << nu;
    EXPECT_NEAR(*e.error.poisson_ratio, 0.0, 1e-3) << nu;
    const ExperimentResult b = run(Experiment::kInflation, cube(nu, {4, 4, 4}));
    EXPECT_NEAR(*b.error.bulk_modulus, 0.0, 1e-3) << nu;
  }
}

TEST(Experiments, NonCubicCellsKeepEAndNuAndReportThreeShearModuli) {
  ExperimentSettings s = cube(0.3, {3, 5, 8});
  s.cell_size = {0.01, 0.011, 0.0125};
  const ExperimentResult e = run(Experiment::kElongation, s);
  EXPECT_NEAR(*e.error.young_modulus, 0.0, 1e-3);
  EXPECT_NEAR(*e.error.poisson_ratio, 0.0, 1e-3);
  const ExperimentResult b = run(Experiment::kInflation, s);
  EXPECT_NEAR(*b.error.bulk_modulus, 0.0, 1e-3);
  // displacement-controlled shear in each plane: C_abab = 4 k_d a b / (L_d^2 c), computed here
  s.strain = 1e-6;
  const ExperimentResult g = run(Experiment::kShear, s);
  const Eigen::Vector3d& h = s.cell_size;
  const double ld2 = h.squaredNorm();
  const double kd =
      3 * shear_modulus(s.material) * ld2 * h.prod() /
      (4 * (h.x() * h.x() * h.y() * h.y() + h.y() * h.y() * h.z() * h.z() + h.z() * h.z() * h.x() * h.x()));
  const Eigen::Vector3d expected(4 * kd * h.y() * h.z() / (ld2 * h.x()), 4 * kd * h.z() * h.x() / (ld2 * h.y()),
                                 4 * kd * h.x() * h.y() / (ld2 * h.z()));
  for (int plane = 0; plane < 3; ++plane) {
    EXPECT_NEAR((*g.shear_moduli)[plane] / expected[plane], 1.0, 1e-5) << plane;
    EXPECT_NEAR((*g.expected_shear_moduli)[plane] / expected[plane], 1.0, 1e-12) << plane;
  }
  EXPECT_NEAR(expected.mean() / shear_modulus(s.material), 1.0, 1e-12);  // mean shear modulus is G
}

TEST(Experiments, LongAxisElongationOfParallelepipedCells) {
  ExperimentSettings s = cube(0.3);
  s.cell_size = {0.0125, 0.01, 0.01};
  const ExperimentResult e = run(Experiment::kElongation, s);
  EXPECT_NEAR(*e.error.young_modulus, 0.0, 1e-3);
  EXPECT_NEAR(*e.error.poisson_ratio, 0.0, 1e-3);
}

TEST(Experiments, TwoMaterialsInSeriesStretchAsTheSumOfTheirParts) {
  // a 4x1x1 bar, soft half and stiff half, pulled at its ends: elongation = sum L_i sigma / E_i
  LatticeDesc desc = box_lattice({4, 1, 1}, Eigen::Vector3d::Constant(0.01), test::notes_material(0.0));
  Material stiff = test::notes_material(0.0);
  stiff.young_modulus = 3e5;
  desc.materials.push_back(stiff);
  desc.cell_material = {0, 0, 1, 1};
  Result<Model> model = build_model(desc);
  ASSERT_TRUE(model.ok());
  Loads loads;
  loads.nodal_forces = Eigen::Matrix3Xd::Zero(3, model->num_nodes());
  const double stress = 10.0;
  for (int n = 0; n < model->num_nodes(); ++n) {
    const int i = model->node_grid_index[n].x();
    if (i == 0 || i == 4) loads.nodal_forces(0, n) = (i == 4 ? 1 : -1) * stress * 1e-4 / 4;
  }
  State state = rest_state(*model);
  ASSERT_TRUE(solve_static(*model, Constraints(*model), loads, StaticSettings{}, state).converged);
  const Eigen::Matrix3Xd u = displacements(*model, state);
  double elongation = 0;
  for (int n = 0; n < model->num_nodes(); ++n) {
    const int i = model->node_grid_index[n].x();
    if (i == 0 || i == 4) elongation += (i == 4 ? 1 : -1) * u(0, n) / 4;
  }
  const double expected = 0.02 * stress / 1e5 + 0.02 * stress / 3e5;
  EXPECT_NEAR(elongation / expected, 1.0, 1e-3);
}

TEST(Experiments, CantileverMatchesTheNotesTable) {
  // model notes section 7, linear: g scaled down by 1e3 and the deflection scaled back [mm]
  const std::vector<std::pair<double, double>> table = {{0.0, 6.127}, {0.25, 5.748}, {0.3, 5.649},
                                                        {0.4, 5.408}, {0.45, 5.255}, {0.49, 5.110}};
  for (const auto& [nu, tip_mm] : table) {
    ExperimentSettings s;
    s.material.young_modulus = 1e6;
    s.material.poisson_ratio = nu;
    s.cells = {16, 4, 4};
    s.gravity = 9.81e-3;
    const ExperimentResult r = run(Experiment::kCantilever, s);
    EXPECT_NEAR(-*r.tip_deflection * 1e6 / tip_mm, 1.0, 5e-3) << "nu " << nu;
    EXPECT_LT(*r.timoshenko, *r.euler_bernoulli);  // shear adds sag
  }
}

TEST(Experiments, SoftCantileverSagsFarAndStaysInEquilibrium) {
  ExperimentSettings s;
  s.material.young_modulus = 1e5;
  s.cells = {16, 4, 4};
  const ExperimentResult r = run(Experiment::kCantilever, s);
  // about a third of the beam's length; CalculiX NLGEOM neo-Hookean gives -52.82 mm (the README's
  // accuracy table), which the paper's cells overshoot by 8-10% at this deflection
  EXPECT_LT(*r.tip_deflection, -0.04);
  EXPECT_NEAR(*r.tip_deflection, -52.82e-3, 0.15 * 52.82e-3);
}

// With nu = 0 a block whose base is bonded, or on a frictionless floor, is in uniaxial stress
// rho g (H - z) (the base holds no lateral strain back): the top sags rho g H^2 / (2 E) and the
// volume changes by the mean strain, -rho g H / (2 E); the strain here is 1e-3, so the linear
// values hold to about that. (With nu > 0 the floor keeps the base flat where the column's base
// would dish: no closed form; tests/validation/test_self_weight_fem.cpp compares with CalculiX.)
TEST(Experiments, SelfWeightWithoutPoissonEffectIsAUniaxialColumn) {
  for (const Support support : {Support::kBonded, Support::kFloor}) {
    for (const CellLaw law : {CellLaw::kSprings, CellLaw::kNeoHookean}) {
      ExperimentSettings s;
      s.support = support;
      s.material.young_modulus = 1e6;
      s.material.poisson_ratio = 0.0;
      s.material.density = 1000;
      s.law = law;
      s.cells = {3, 4, 5};
      s.cell_size = Eigen::Vector3d::Constant(0.02);
      const ExperimentResult r = run(Experiment::kSelfWeight, s);
      const double height = 0.1, column = 1000 * 9.81 * height / 1e6;
      EXPECT_NEAR(*r.top_centre_uz, -column * height / 2, 3e-3 * column * height / 2)
          << cell_law_name(law) << ", " << support_name(support);
      EXPECT_NEAR(*r.volume_change, -column / 2, 3e-3 * column / 2)
          << cell_law_name(law) << ", " << support_name(support);
      EXPECT_GT(*r.least_cell_volume_ratio, 1.0 - 1.01 * column);
      EXPECT_LT(*r.least_cell_volume_ratio, 1.0);
    }
  }
  EXPECT_STREQ(support_name(parse_support("floor").value()), "floor");
  EXPECT_FALSE(parse_support("glue").ok());
  ExperimentSettings s;
  s.gravity = 0;
  s.cells = {2, 2, 2};
  const Result<ExperimentResult> unloaded = run_experiment(Experiment::kSelfWeight, s);
  ASSERT_FALSE(unloaded.ok());
  EXPECT_NE(unloaded.message().find("gravity"), std::string::npos) << unloaded.message();
}

// The law written out (docs/model-neo-hookean.md section 2, above the barrier) per rest volume.
double neo_hookean_energy(const Material& m, const Eigen::Matrix3d& f) {
  const double g = m.young_modulus / (2 * (1 + m.poisson_ratio));
  const double b = m.young_modulus / (3 * (1 - 2 * m.poisson_ratio));
  const double j = f.determinant();
  return g / 2 * (std::pow(j, -2.0 / 3.0) * (f.transpose() * f).trace() - 3) + b / 2 * (j - 1) * (j - 1);
}

// The closed forms against derivatives of the energy by central differences: P_xz = dW/dgamma;
// P = dW/dlambda / 3 for F = lambda I; uniaxial P_xx = d/dlambda of min over the lateral stretch
// of W (the envelope theorem: the lateral stress is zero at the minimum).
TEST(Experiments, NeoHookeanClosedFormsAreDerivativesOfTheEnergy) {
  for (const double nu : {0.3, 0.45, 0.49}) {
    Material m;
    m.young_modulus = 5e3;
    m.poisson_ratio = nu;
    const double d = 1e-5;
    const auto shear = [&](double gamma) {
      Eigen::Matrix3d f = Eigen::Matrix3d::Identity();
      f(0, 2) = gamma;
      return neo_hookean_energy(m, f);
    };
    for (const double gamma : {0.1, 0.5}) {
      EXPECT_NEAR(neo_hookean_simple_shear_stress(m, gamma), (shear(gamma + d) - shear(gamma - d)) / (2 * d),
                  1e-6 * m.young_modulus);
    }
    const auto dilated = [&](double stretch) { return neo_hookean_energy(m, stretch * Eigen::Matrix3d::Identity()); };
    for (const double j : {0.9, 1.05}) {
      const double stretch = std::cbrt(j);
      EXPECT_NEAR(neo_hookean_hydrostatic_stress(m, j), (dilated(stretch + d) - dilated(stretch - d)) / (6 * d),
                  1e-6 * m.young_modulus);
    }
    const auto relaxed = [&](double stretch) {  // min over the lateral stretch, by golden sections
      double low = 0.5, high = 2.0;
      const auto energy = [&](double lateral) {
        return neo_hookean_energy(m, Eigen::Vector3d(stretch, lateral, lateral).asDiagonal());
      };
      for (int i = 0; i < 200; ++i) {
        const double a = high - 0.618 * (high - low), b = low + 0.618 * (high - low);
        (energy(a) < energy(b) ? high : low) = energy(a) < energy(b) ? b : a;
      }
      return energy(0.5 * (low + high));
    };
    for (const double stretch : {0.6, 0.8, 1.2, 1.5}) {
      EXPECT_NEAR(neo_hookean_uniaxial_stress(m, stretch), (relaxed(stretch + d) - relaxed(stretch - d)) / (2 * d),
                  1e-4 * m.young_modulus)
          << "nu " << nu << ", stretch " << stretch;
    }
    EXPECT_NEAR(neo_hookean_uniaxial_stress(m, 1.0 + 1e-6) / 1e-6, m.young_modulus, 1e-4 * m.young_modulus);
  }
}

// Finite-strain curves of both cell models (4^3 cells): the nominal stress within 3% of the law
// at every point (issue 24's target), in tissue's range of nu and at 0.3, from 40% compression to
// 50% tension. They come out exact (1e-6 is asserted): the homogeneous state is the lattice's
// equilibrium and, since the edges' share of the cell term is taken on their mean lengths, a
// stable one (the paper's cells: neutral in their zero-energy modes). Before that, compression
// softened the non-affine modes: exact-bending cells buckled past 30% (1.7% short at 40%), the
// paper's under any compression (a quarter short at 5%).
TEST(Experiments, FiniteStrainCurvesOfBothCellModelsFollowTheLaw) {
  struct Curve {
    Experiment experiment;
    double poisson, strain;
  };
  std::vector<Curve> curves;
  for (const double nu : {0.3, 0.45, 0.49}) {
    for (const double strain : {-0.4, 0.5}) curves.push_back({Experiment::kUniaxial, nu, strain});
    curves.push_back({Experiment::kSimpleShear, nu, 0.5});
    curves.push_back({Experiment::kHydrostatic, nu, -0.1});
    curves.push_back({Experiment::kHydrostatic, nu, 0.05});
  }
  for (const CellModel model : {CellModel::kExactBending, CellModel::kBaudet2007}) {
    for (const Curve& c : curves) {
      ExperimentSettings s;
      s.material.young_modulus = 5e3;
      s.material.poisson_ratio = c.poisson;
      s.model = model;
      s.law = CellLaw::kNeoHookean;
      s.cells = {4, 4, 4};
      s.strain = c.strain;
      s.curve_points = 4;
      const ExperimentResult r = run(c.experiment, s);
      ASSERT_EQ(r.curve.size(), 4u);
      EXPECT_DOUBLE_EQ(r.curve.back().strain, c.strain);
      for (const CurvePoint& point : r.curve) {
        EXPECT_NEAR(point.stress, point.expected, 1e-6 * std::abs(point.expected))
            << cell_model_name(model) << ", " << experiment_name(c.experiment) << ", nu " << c.poisson << ", strain "
            << point.strain;
      }
    }
  }
}

// Uniaxial stress along an axis that is not the lattice's: the deformation gradient of the law's
// uniaxial state, F = R diag(l, m, m) R^T (m its lateral stretch), imposed on every boundary node
// of 4^3 exact-bending cells, the interior free; R turns by 0.5 rad about (1, 2, 3). The nominal
// stress the boundary carries, by the virial P = sum_n r_n X_n^T / V over the boundary nodes'
// reactions r_n, is the law's R diag(P_l, 0, 0) R^T within 3% of P_l in every component, from
// 40% compression to 50% tension (it comes out exact: held at its whole boundary, the interior
// does not buckle, unlike the platens' block at 40%).
TEST(Experiments, UniaxialStressAlongARotatedAxisFollowsTheLaw) {
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(0.5, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  for (const double nu : {0.3, 0.45, 0.49}) {
    Material material;
    material.young_modulus = 5e3;
    material.poisson_ratio = nu;
    LatticeDesc desc = box_lattice({4, 4, 4}, Eigen::Vector3d::Constant(0.01), material);
    desc.model = CellModel::kExactBending;
    desc.law = CellLaw::kNeoHookean;
    const Model model = build_model(desc).value();
    const Eigen::Vector3d centre = model.origin + Eigen::Vector3d::Constant(0.02);
    for (const double strain : {-0.4, -0.3, 0.5}) {
      const double along = 1.0 + strain, lateral = neo_hookean_uniaxial_lateral_stretch(material, along);
      const Eigen::Matrix3d f = rotation * Eigen::Vector3d(along, lateral, lateral).asDiagonal() * rotation.transpose();
      Constraints constraints(model);
      std::vector<int> boundary;
      for (int n = 0; n < model.num_nodes(); ++n) {
        const Eigen::Vector3i& index = model.node_grid_index[n];
        if (!(index.array() == 0).any() && !(index.array() == 4).any()) continue;
        const Eigen::Vector3d rest = model.rest_positions.col(n) - centre;
        ASSERT_TRUE(constraints.prescribe_displacement(model, n, f * rest - rest));
        boundary.push_back(n);
      }
      State state = rest_state(model);
      StaticSettings settings;
      settings.initial_load_steps = 4;
      const StaticReport report = solve_static(model, constraints, Loads{}, settings, state);
      ASSERT_TRUE(report.converged) << report.message;
      Eigen::Matrix3Xd forces;
      ForceWorkspace ws;
      compute_forces(model, state, Loads{}, ForceOptions{false, 1}, ws, forces);
      Eigen::Matrix3d virial = Eigen::Matrix3d::Zero();
      for (const int n : boundary) virial -= forces.col(n) * (model.rest_positions.col(n) - centre).transpose();
      const Eigen::Matrix3d nominal = virial / 0.04 / 0.04 / 0.04;
      const double expected_along = neo_hookean_uniaxial_stress(material, along);
      const Eigen::Matrix3d expected =
          rotation * Eigen::Vector3d(expected_along, 0, 0).asDiagonal() * rotation.transpose();
      const double error = (nominal - expected).cwiseAbs().maxCoeff() / std::abs(expected_along);
      std::printf("nu %.2f, stretch - 1 = %+.2f along a rotated axis: largest stress error %.3f%% of P = %.1f Pa\n", nu,
                  strain, 100 * error, expected_along);
      EXPECT_LT(error, 0.03) << "nu " << nu << ", strain " << strain;
    }
  }
}

TEST(Experiments, RejectBadSettings) {
  ExperimentSettings s = cube(0.3);
  s.cells = {0, 1, 1};
  Result<ExperimentResult> r = run_experiment(Experiment::kElongation, s);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.message().find("cells"), std::string::npos);
  s = cube(0.3);
  s.material.poisson_ratio = 0.5;
  r = run_experiment(Experiment::kElongation, s);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.message().find("poisson_ratio"), std::string::npos);
  // 2^22 x 2^21 x 2^21 cells: a product that wraps to 0 in 64 bits is still refused
  s = cube(0.3);
  s.cells = {1 << 22, 1 << 21, 1 << 21};
  r = run_experiment(Experiment::kElongation, s);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.message().find("a body may have at most"), std::string::npos) << r.message();
  s = cube(0.3);
  s.strain = 0.0;
  r = run_experiment(Experiment::kUniaxial, s);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.message().find("nominal strain"), std::string::npos) << r.message();
  s.strain = -0.7;
  EXPECT_FALSE(run_experiment(Experiment::kHydrostatic, s).ok());
  s.strain = 0.1;
  s.curve_points = 0;
  EXPECT_FALSE(run_experiment(Experiment::kSimpleShear, s).ok());
  Result<Experiment> unknown = parse_experiment("twist");
  ASSERT_FALSE(unknown.ok());
  EXPECT_NE(unknown.message().find("twist"), std::string::npos);
}

}  // namespace
}  // namespace cubespring
