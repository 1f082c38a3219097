// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "cubespring/material.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace cubespring {
namespace {

TEST(Material, ModuliFollowTheElasticRelations) {
  Material m;
  m.young_modulus = 3e5;
  m.poisson_ratio = 0.3;
  const double g = shear_modulus(m);
  const double k = bulk_modulus(m);
  // E = 9KG / (3K + G) and nu = (3K - 2G) / (2 (3K + G))
  EXPECT_NEAR(9 * k * g / (3 * k + g), m.young_modulus, 1e-9 * m.young_modulus);
  EXPECT_NEAR((3 * k - 2 * g) / (2 * (3 * k + g)), m.poisson_ratio, 1e-12);
  EXPECT_NEAR(lame_lambda(m) + 2.0 * g / 3.0, k, 1e-9 * k);
}

TEST(Material, DefaultIsValid) { EXPECT_TRUE(validate(Material{}).ok()); }

// the damped, nearly incompressible tissue scenes and the plugin's examples start from, at the
// stiffnesses of soft organs (1-50 kPa); the organs' rest test (test_bullet_organs) runs it
TEST(Material, SoftTissueIsValidAndDamped) {
  for (const double young_modulus : {1e3, 5e3, 5e4}) {
    const Material tissue = soft_tissue(young_modulus);
    EXPECT_TRUE(validate(tissue).ok()) << validate(tissue).message();
    EXPECT_EQ(tissue.young_modulus, young_modulus);
    EXPECT_EQ(tissue.mass_damping, kSoftTissueMassDamping);
    EXPECT_GT(tissue.mass_damping, 0.0) << "an undamped organ never comes to rest";
  }
}

struct BadField {
  const char* field;
  Material material;
};

class MaterialRejects : public ::testing::TestWithParam<BadField> {};

TEST_P(MaterialRejects, NamesTheField) {
  const Status status = validate(GetParam().material);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find(GetParam().field), std::string::npos) << status.message();
}

Material with(double Material::*field, double value) {
  Material m;
  m.*field = value;
  return m;
}

INSTANTIATE_TEST_SUITE_P(BadValues, MaterialRejects,
                         ::testing::Values(BadField{"young_modulus", with(&Material::young_modulus, 0.0)},
                                           BadField{"young_modulus", with(&Material::young_modulus, -1.0)},
                                           BadField{"young_modulus", with(&Material::young_modulus, std::nan(""))},
                                           // finite, but lambda + 2G overflows; or so small that G underflows
                                           BadField{"young_modulus", with(&Material::young_modulus, 1.7e308)},
                                           BadField{"young_modulus", with(&Material::young_modulus, 1e-310)},
                                           BadField{"poisson_ratio", with(&Material::poisson_ratio, 0.5)},
                                           BadField{"poisson_ratio", with(&Material::poisson_ratio, 0.7)},
                                           BadField{"poisson_ratio", with(&Material::poisson_ratio, -0.25)},
                                           BadField{"density", with(&Material::density, 0.0)},
                                           BadField{"density",
                                                    with(&Material::density, std::numeric_limits<double>::infinity())},
                                           BadField{"mass_damping", with(&Material::mass_damping, -1.0)},
                                           BadField{"stiffness_damping", with(&Material::stiffness_damping, -1e-3)}));

TEST(Material, MessageGivesTheAllowedRange) {
  const Status status = validate(with(&Material::poisson_ratio, 0.5));
  EXPECT_NE(status.message().find("0.5"), std::string::npos) << status.message();
  EXPECT_NE(status.message().find("-0.25"), std::string::npos) << status.message();
}

}  // namespace
}  // namespace cubespring
