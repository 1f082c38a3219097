// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Spring constants and the affine response of one cell (model notes section 8, checks 1 and 2).
#include <gtest/gtest.h>

#include "cubespring/model.h"
#include "test_support.h"

namespace cubespring {
namespace {

using test::notes_material;

CellCalibration calibrate(double nu, const Eigen::Vector3d& size = Eigen::Vector3d::Constant(0.01)) {
  Result<CellCalibration> c = calibrate_cell(CellModel::kBaudet2007, notes_material(nu), size);
  EXPECT_TRUE(c.ok()) << c.message();
  return c.value();
}

TEST(Calibration, PaperConstantsAtNu03) {
  const CellCalibration c = calibrate(0.3);
  // k_d = 3 E x0 / (8 (1 + nu)), k_edge = E x0 (4 nu + 1) / (8 (1 + nu)), E = 1e5, x0 = 0.01
  EXPECT_NEAR(c.diagonal_stiffness, 288.4615384615385, 1e-12 * 288.46);
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(c.edge_stiffness[a], 211.5384615384615, 1e-12 * 211.5);
}

TEST(Calibration, CorrectionVanishesAtQuarter) {
  const CellCalibration c = calibrate(0.25);
  EXPECT_NEAR(c.edge_stiffness.x(), 2.0 * c.diagonal_stiffness / 3.0, 1e-12 * c.diagonal_stiffness);
  EXPECT_LT(c.correction.cwiseAbs().maxCoeff(), 1e-9 * 1e5);
}

TEST(Calibration, CorrectionMatchesClosedForm) {
  // D_aa = kappa' nu, D_ab = kappa' / 2, kappa' = E (4 nu - 1) / ((1 + nu)(1 - 2 nu))
  for (double nu : {0.0, 0.1, 0.3, 0.45, 0.49}) {
    const CellCalibration c = calibrate(nu);
    const double kappa = 1e5 * (4 * nu - 1) / ((1 + nu) * (1 - 2 * nu));
    EXPECT_NEAR(c.correction(0, 0), kappa * nu, 1e-9 * std::abs(kappa) + 1e-9) << nu;
    EXPECT_NEAR(c.correction(0, 1), kappa / 2, 1e-9 * std::abs(kappa)) << nu;
  }
}

// Stress of a single cube under the affine strain u = eps X, read from the face reactions.
Eigen::Matrix3d affine_stress(const Model& model, const Eigen::Matrix3d& strain) {
  const Eigen::Matrix3Xd x = model.rest_positions + strain * model.rest_positions;
  const Eigen::Matrix3Xd f = test::elastic_forces(model, x);
  Eigen::Matrix3d stress = Eigen::Matrix3d::Zero();
  const Eigen::Vector3d& h = model.cell_size;
  for (int n = 0; n < model.num_nodes(); ++n) {
    for (int axis = 0; axis < 3; ++axis) {
      // the + face nodes carry the traction sigma_{axis, .} times the face area
      if (model.node_grid_index[n][axis] == 1) stress.row(axis) -= f.col(n).transpose() * h[axis] / h.prod();
    }
  }
  return stress;
}

TEST(Calibration, SpringsAloneGiveTheCauchyLattice) {
  for (double nu : {0.0, 0.3, 0.45}) {
    Model model = test::box_model({1, 1, 1}, notes_material(nu));
    for (auto& d : model.cell_correction) d.setZero();
    model.mark_changed();
    const double eps = 1e-7;
    const Eigen::Matrix3d stress = affine_stress(model, eps * Eigen::Vector3d::UnitX().asDiagonal().toDenseMatrix());
    const double e = 1e5;
    EXPECT_NEAR(stress(0, 0) / eps, e * (1 + 2 * nu) / (1 + nu), 1e-5 * e) << nu;  // C11
    EXPECT_NEAR(stress(1, 1) / eps, e / (2 * (1 + nu)), 1e-5 * e) << nu;           // C12 = G
  }
}

TEST(Calibration, CorrectedCellIsIsotropic) {
  for (double nu : {0.0, 0.3, 0.45, 0.49}) {
    const Material m = notes_material(nu);
    const Model model = test::box_model({1, 1, 1}, m);
    const double eps = 1e-7;
    const Eigen::Matrix3d stress = affine_stress(model, eps * Eigen::Vector3d::UnitX().asDiagonal().toDenseMatrix());
    const double scale = p_wave_modulus(m);
    EXPECT_NEAR(stress(0, 0) / eps, lame_lambda(m) + 2 * shear_modulus(m), 1e-5 * scale) << nu;
    EXPECT_NEAR(stress(1, 1) / eps, lame_lambda(m), 1e-5 * scale) << nu;
  }
}

TEST(Calibration, ParallelepipedKeepsYoungsModulusPerAxis) {
  // k_a = E V / (4 a^2) - k_d (a^2 - nu (b^2 + c^2)) / L_d^2 and the correction make C_iso exact
  const Material m = notes_material(0.3);
  const Eigen::Vector3d size(0.01, 0.01, 0.0125);
  const CellCalibration c = calibrate(0.3, size);
  const double ld2 = size.squaredNorm();
  for (int a = 0; a < 3; ++a) {
    const double others = ld2 - size[a] * size[a];
    const double expected = m.young_modulus * size.prod() / (4 * size[a] * size[a]) -
                            c.diagonal_stiffness * (size[a] * size[a] - 0.3 * others) / ld2;
    EXPECT_NEAR(c.edge_stiffness[a], expected, 1e-9 * std::abs(expected));
  }
}

TEST(Calibration, RefusesCellsWhoseEdgeStiffnessTurnsNegative) {
  // at nu = 0.3 the long edge's stiffness vanishes near an aspect ratio of 1.64
  Result<CellCalibration> fine = calibrate_cell(CellModel::kBaudet2007, notes_material(0.3), {0.01, 0.01, 0.016});
  EXPECT_TRUE(fine.ok()) << fine.message();
  Result<CellCalibration> bad = calibrate_cell(CellModel::kBaudet2007, notes_material(0.3), {0.01, 0.01, 0.02});
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.message().find("0.01 x 0.01 x 0.02"), std::string::npos) << bad.message();
  EXPECT_NE(bad.message().find("aspect ratio below about 1.6"), std::string::npos) << bad.message();
}

TEST(Calibration, RefusesBadCellSize) {
  Result<CellCalibration> bad = calibrate_cell(CellModel::kBaudet2007, notes_material(0.3), {0.01, 0.0, 0.01});
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.message().find("cell size"), std::string::npos) << bad.message();
}

}  // namespace
}  // namespace cubespring
