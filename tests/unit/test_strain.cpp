// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The equivalent strain used to colour bodies, against closed forms for affine motions of a
// lattice of non-cubic cells (so the cell size's axes matter), and its node means; the volume
// a body encloses, against the determinant and the divergence theorem.
#include <array>
#include <cmath>
#include <cstdlib>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "cubespring/strain.h"
#include "unit/test_support.h"

namespace cubespring {
namespace {

const Eigen::Vector3d kCellSize(0.01, 0.013, 0.008);

Model non_cubic_box() { return test::box_model(Eigen::Vector3i(3, 2, 4), test::notes_material(0.3), kCellSize); }

Eigen::VectorXd strains_under(const Model& model, const Eigen::Matrix3d& map) {
  const Eigen::Matrix3Xd moved = (map * model.rest_positions).colwise() + Eigen::Vector3d(0.3, -0.2, 0.1);
  return cell_equivalent_strains(model, moved);
}

const Eigen::Matrix3d kRotation = Eigen::AngleAxisd(0.9, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();

TEST(Strain, RigidMotionIsUnstrained) {
  const Model model = non_cubic_box();
  const Eigen::VectorXd strains = strains_under(model, kRotation);
  ASSERT_EQ(strains.size(), model.num_cells());
  EXPECT_LT(strains.cwiseAbs().maxCoeff(), 1e-14);
}

TEST(Strain, SimpleShearMatchesItsClosedFormEvenWhenRotated) {
  // F = R (I + gamma e_x e_y^T): E = [[0, g/2, 0], [g/2, g^2/2, 0], [0, 0, 0]],
  // dev(E):dev(E) = g^2/2 + g^4/6, so the equivalent strain is sqrt(g^2/3 + g^4/9)
  const Model model = non_cubic_box();
  const double gamma = 0.4;
  Eigen::Matrix3d shear = Eigen::Matrix3d::Identity();
  shear(0, 1) = gamma;
  const double expected = std::sqrt(gamma * gamma / 3.0 + std::pow(gamma, 4) / 9.0);
  const Eigen::VectorXd strains = strains_under(model, kRotation * shear);
  EXPECT_LT((strains.array() - expected).abs().maxCoeff(), 1e-13);
}

TEST(Strain, SmallUniaxialStretchGivesTwoThirdsOfOnePlusNuTimesTheStrain) {
  const Model model = non_cubic_box();
  const double strain = 1e-5;
  const double nu = 0.3;
  for (int axis = 0; axis < 3; ++axis) {
    Eigen::Vector3d stretches = Eigen::Vector3d::Constant(1.0 - nu * strain);
    stretches[axis] = 1.0 + strain;
    const Eigen::VectorXd strains = strains_under(model, stretches.asDiagonal());
    const double expected = 2.0 / 3.0 * (1.0 + nu) * strain;
    // Green-Lagrange differs from the small strain by O(strain^2)
    EXPECT_LT((strains.array() - expected).abs().maxCoeff(), 1e-4 * expected) << "axis " << axis;
  }
}

TEST(Strain, DilatationAloneIsNotAnEquivalentStrain) {
  const Model model = non_cubic_box();
  EXPECT_LT(strains_under(model, 1.3 * Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(), 1e-14);
}

TEST(Strain, OneStretchedCellReadsAloneAndItsNodesAverage) {
  // two cells along x; the second one's far face pulled out by 10%
  const Model model = test::box_model(Eigen::Vector3i(2, 1, 1), test::notes_material(0.3));
  Eigen::Matrix3Xd x = model.rest_positions;
  for (int node = 0; node < model.num_nodes(); ++node) {
    if (x(0, node) > 0.015) x(0, node) += 0.001;
  }
  const Eigen::VectorXd cells = cell_equivalent_strains(model, x);
  const double stretched = 2.0 / 3.0 * 0.5 * (1.1 * 1.1 - 1.0);  // dev of diag(E11, 0, 0)
  const int far_cell = model.cell_grid_index[0].x() == 1 ? 0 : 1;
  EXPECT_NEAR(cells[far_cell], stretched, 1e-12);
  EXPECT_NEAR(cells[1 - far_cell], 0.0, 1e-15);

  const Eigen::VectorXd nodes = node_means_of_cells(model, cells);
  for (int node = 0; node < model.num_nodes(); ++node) {
    const double rest_x = model.rest_positions(0, node);
    const double expected = rest_x < 0.005 ? 0.0 : rest_x < 0.015 ? stretched / 2.0 : stretched;
    EXPECT_NEAR(nodes[node], expected, 1e-12) << "node at x = " << rest_x;
  }
}

TEST(Strain, BodyVolumeIsTheDeterminantTimesTheRestVolumeUnderAnAffineMap) {
  const Model model = non_cubic_box();
  Eigen::Matrix3d map;
  map << 1.2, 0.3, -0.1, 0.05, 0.8, 0.2, -0.15, 0.1, 1.1;
  const Eigen::Matrix3d turned = kRotation * map;
  const double rest = body_volume(model, model.rest_positions);
  EXPECT_NEAR(rest, 24 * kCellSize.prod(), 1e-12 * rest);
  const Eigen::Matrix3Xd moved = (turned * model.rest_positions).colwise() + Eigen::Vector3d(0.3, -0.2, 0.1);
  EXPECT_NEAR(body_volume(model, moved), turned.determinant() * rest, 1e-12 * rest);
}

// The volume a cell's six bilinear faces enclose, by the divergence theorem: V = 1/3 sum over
// faces of the integral of x . (x_u x x_v) du dv, which 2 x 2 Gauss points give exactly (the
// integrand is of degree 2 in u and in v). Independent of the cell's own Jacobian.
double enclosed_by_bilinear_faces(const std::array<Eigen::Vector3d, 8>& corner) {
  // each face's corners at (u, v) = (0, 0), (1, 0), (1, 1), (0, 1), counter-clockwise seen from
  // outside; corner index bits are x, y, z
  const int faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  const double gauss[2] = {0.5 - 0.5 / std::sqrt(3.0), 0.5 + 0.5 / std::sqrt(3.0)};
  double volume = 0.0;
  for (const auto& face : faces) {
    const Eigen::Vector3d &a = corner[face[0]], &b = corner[face[1]], &c = corner[face[2]], &d = corner[face[3]];
    for (double u : gauss) {
      for (double v : gauss) {
        const Eigen::Vector3d x = (1 - u) * (1 - v) * a + u * (1 - v) * b + u * v * c + (1 - u) * v * d;
        const Eigen::Vector3d x_u = (1 - v) * (b - a) + v * (c - d);
        const Eigen::Vector3d x_v = (1 - u) * (d - a) + u * (c - b);
        volume += x.dot(x_u.cross(x_v)) / 4.0 / 3.0;
      }
    }
  }
  return volume;
}

TEST(Strain, TrilinearCellVolumeIsWhatItsBilinearFacesEnclose) {
  const Model model = test::box_model(Eigen::Vector3i(1, 1, 1), test::notes_material(0.3), kCellSize);
  std::srand(7);
  for (int trial = 0; trial < 5; ++trial) {
    // each corner moved by up to 30% of the cell: the faces warp, the cell is far from affine
    Eigen::Matrix3Xd x = model.rest_positions + 0.3 * kCellSize.minCoeff() * Eigen::Matrix3Xd::Random(3, 8);
    std::array<Eigen::Vector3d, 8> corner;
    for (int k = 0; k < 8; ++k) corner[k] = x.col(model.cell_nodes[0][k]);
    const double expected = enclosed_by_bilinear_faces(corner);
    EXPECT_NEAR(trilinear_cell_volume(model, x, 0), expected, 1e-12 * kCellSize.prod()) << "trial " << trial;
    EXPECT_NEAR(body_volume(model, x), expected, 1e-12 * kCellSize.prod());
  }
}

}  // namespace
}  // namespace cubespring
