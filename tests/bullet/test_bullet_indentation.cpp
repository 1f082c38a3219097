// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Indentation of a block by a rigid sphere against Hertz's law, F = 4/3 E / (1 - nu^2) R^1/2 d^3/2,
// corrected for a layer of finite thickness t bonded to its base (Dimitriadis et al. 2002,
// validation/bonded_layer.h). Here t = 2R: the correction is 19-24% at 0.13-0.2 R. (slow: label
// validation).
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "bullet_scene.h"
#include "validation/bonded_layer.h"

namespace cubespring {
namespace {

using validation::bonded_layer_factor;

TEST(BulletIndentation, LayerFactorHasThePublishedCoefficientsAtHalf) {
  // F / F_Hertz = 1 + 1.133 chi + 1.283 chi^2 + 0.769 chi^3 + 0.0975 chi^4 at nu = 0.5
  for (double chi : {0.1, 0.2, 0.4}) {
    const double published = 1 + 1.133 * chi + 1.283 * chi * chi + 0.769 * std::pow(chi, 3) + 0.0975 * std::pow(chi, 4);
    EXPECT_NEAR(bonded_layer_factor(chi, 0.5), published, 2e-3) << "chi " << chi;
  }
}

TEST(BulletIndentation, SphereForceFollowsHertzOnABondedLayerWithinTenPercent) {
  const double h = 1e-3;
  const Eigen::Vector3i cells(24, 24, 12);
  const double radius = 6 * h;
  Material material;
  material.young_modulus = 1e4;
  material.poisson_ratio = 0.3;
  material.density = 1000.0;
  material.mass_damping = 300.0;  // quasi-static pressing
  test::BulletScene scene(Eigen::Vector3d::Zero());
  bullet::SoftBodySettings settings = test::block(cells, h, material);
  settings.lattice.model = CellModel::kExactBending;
  settings.contact.friction = 0.0;  // Hertz's contact is frictionless
  bullet::SoftBody* soft = scene.add_soft(settings);
  ASSERT_NE(soft, nullptr);
  ASSERT_TRUE(
      soft->constraints().fix_box(soft->model(), Eigen::Vector3d(-1, -1, -1e-9), Eigen::Vector3d(1, 1, 1e-9)).ok());
  const double top = cells.z() * h;
  // centred over a node, so that the first contact is one vertex
  btRigidBody* indenter =
      scene.add_rigid(new btSphereShape(static_cast<btScalar>(radius)), 0.0, test::at(0, 0, top + radius), true);
  const double step = 1.0 / 600.0;
  const double press_time = 1.2;
  const double deepest = 0.2 * radius;
  double previous = 0.0;
  std::vector<std::pair<double, double>> checked;
  const int steps = static_cast<int>(press_time / step);
  for (int i = 1; i <= steps; ++i) {
    const double depth = deepest * i / steps;
    indenter->setWorldTransform(test::at(0, 0, top + radius - depth));
    scene.world().stepSimulation(static_cast<btScalar>(step), 1, static_cast<btScalar>(step));
    ASSERT_TRUE(scene.world().getSoftBodyError().empty()) << scene.world().getSoftBodyError();
    const double force = scene.world().getContactWrench(indenter).force.z();  // the tissue pushes it up
    if (i % (steps / 6) == 0) {
      // rises monotonically (sampled), and matches Hertz past the first cell of depth's worth
      EXPECT_GT(force, previous) << "at depth " << depth;
      previous = force;
      const double hertz =
          validation::hertz_on_bonded_layer(material.young_modulus, material.poisson_ratio, radius, depth, top);
      std::printf("depth %.3f R: force %.5f N, Hertz on the layer %.5f N, ratio %.3f\n", depth / radius, force, hertz,
                  force / hertz);
      if (depth >= 0.1 * radius) checked.emplace_back(force, hertz);
    }
  }
  ASSERT_FALSE(checked.empty());
  for (const auto& [force, hertz] : checked) EXPECT_NEAR(force, hertz, 0.10 * hertz);
}

}  // namespace
}  // namespace cubespring
