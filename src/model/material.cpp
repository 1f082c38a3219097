// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "cubespring/material.h"

#include <cmath>
#include <sstream>

namespace cubespring {
namespace {

std::string format(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

}  // namespace

Status validate(const Material& material) {
  if (!std::isfinite(material.young_modulus) || material.young_modulus <= 0.0) {
    return Status::error("young_modulus = " + format(material.young_modulus) +
                         " Pa: Young's modulus must be a finite number > 0");
  }
  if (material.young_modulus < kMinYoungModulus || material.young_modulus > kMaxYoungModulus) {
    return Status::error("young_modulus = " + format(material.young_modulus) + " Pa: must be " +
                         format(kMinYoungModulus) + " to " + format(kMaxYoungModulus) +
                         " Pa (beyond, forces and time steps leave the range of double)");
  }
  if (!std::isfinite(material.poisson_ratio) || material.poisson_ratio <= kMinPoissonRatio ||
      material.poisson_ratio >= kMaxPoissonRatio) {
    return Status::error("poisson_ratio = " + format(material.poisson_ratio) + ": the cube model needs " +
                         format(kMinPoissonRatio) + " < nu < " + format(kMaxPoissonRatio) +
                         " (edge springs vanish at -0.25, the bulk modulus is infinite at 0.5)");
  }
  // the moduli the springs and corrections come from (near the ends of double's range they
  // overflow, or underflow to a stiffness of 0)
  if (!std::isnormal(shear_modulus(material)) || !std::isnormal(p_wave_modulus(material))) {
    return Status::error("young_modulus = " + format(material.young_modulus) +
                         " Pa with poisson_ratio = " + format(material.poisson_ratio) + ": the shear modulus " +
                         format(shear_modulus(material)) + " Pa or the P-wave modulus " +
                         format(p_wave_modulus(material)) + " Pa is out of the range of double");
  }
  if (!std::isfinite(material.density) || material.density <= 0.0) {
    return Status::error("density = " + format(material.density) + " kg/m^3: density must be a finite number > 0");
  }
  if (material.density < kMinDensity || material.density > kMaxDensity) {
    return Status::error("density = " + format(material.density) + " kg/m^3: must be " + format(kMinDensity) + " to " +
                         format(kMaxDensity) +
                         " kg/m^3 (beyond, masses, weights and time steps "
                         "leave the range of double)");
  }
  if (!std::isfinite(material.mass_damping) || material.mass_damping < 0.0) {
    return Status::error("mass_damping = " + format(material.mass_damping) +
                         " 1/s: Rayleigh alpha must be a finite number >= 0");
  }
  if (!std::isfinite(material.stiffness_damping) || material.stiffness_damping < 0.0) {
    return Status::error("stiffness_damping = " + format(material.stiffness_damping) +
                         " s: Rayleigh beta must be a finite number >= 0");
  }
  return {};
}

Material soft_tissue(double young_modulus) {
  Material tissue;
  tissue.young_modulus = young_modulus;
  tissue.poisson_ratio = 0.45;
  tissue.density = 1060.0;
  tissue.mass_damping = kSoftTissueMassDamping;
  tissue.stiffness_damping = 0.0;
  return tissue;
}

double shear_modulus(const Material& m) { return m.young_modulus / (2.0 * (1.0 + m.poisson_ratio)); }

double bulk_modulus(const Material& m) { return m.young_modulus / (3.0 * (1.0 - 2.0 * m.poisson_ratio)); }

double lame_lambda(const Material& m) {
  const double nu = m.poisson_ratio;
  return m.young_modulus * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
}

double p_wave_modulus(const Material& m) { return lame_lambda(m) + 2.0 * shear_modulus(m); }

double pressure_wave_speed(const Material& m) { return std::sqrt(p_wave_modulus(m) / m.density); }

}  // namespace cubespring
