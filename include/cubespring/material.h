// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#pragma once

#include <string>

#include "cubespring/result.h"

/// Units are SI throughout the API: metres, kilograms, seconds, newtons, pascals.
namespace cubespring {

/// A linear elastic, isotropic tissue with Rayleigh damping.
struct Material {
  double young_modulus = 1e6;      ///< E [Pa], > 0.
  double poisson_ratio = 0.3;      ///< nu [-], in (kMinPoissonRatio, kMaxPoissonRatio).
  double density = 1000.0;         ///< rho [kg/m^3], > 0.
  double mass_damping = 0.0;       ///< Rayleigh alpha [1/s], >= 0: force -alpha m v.
  double stiffness_damping = 0.0;  ///< Rayleigh beta [s], >= 0: force -beta K v.
};

/// The cube model (Baudet et al. 2007) has positive edge springs only for nu > -1/4
/// (k_edge is proportional to 4 nu + 1), and a finite bulk modulus only for nu < 1/2.
/// Non-cubic cells narrow this range further; build_model() checks each cell shape.
inline constexpr double kMinPoissonRatio = -0.25;
inline constexpr double kMaxPoissonRatio = 0.5;

/// The ranges validate() takes for E and rho: wide enough for any tissue or engineering material
/// (tissue is 1e2-1e5 Pa, steel 2e11 Pa; aerogel 1 kg/m^3, osmium 2.3e4 kg/m^3), narrow enough that
/// forces, masses and time steps stay finite (at E = 1e308 Pa a strain of 1e-4 already overflows).
inline constexpr double kMinYoungModulus = 1e-3;  ///< [Pa]
inline constexpr double kMaxYoungModulus = 1e13;  ///< [Pa]
inline constexpr double kMinDensity = 1e-3;       ///< [kg/m^3]
inline constexpr double kMaxDensity = 1e6;        ///< [kg/m^3]

/// Soft tissue as scenes and the Bullet plugin's examples take it: E = young_modulus [Pa],
/// nu = 0.45, rho = 1060 kg/m^3, and mass damping alpha = 40/s (no stiffness damping). Soft
/// organs with their visual meshes come to rest on a table with that damping (mass-weighted RMS
/// node speed under 1 mm/s: tests/bullet/test_bullet_organs.cpp); without damping an elastic body
/// dissipates nothing and never does (docs/bullet-plugin.md section 5). Material{}'s own damping
/// stays 0, an undamped elastic solid. The scenes' default tissue is soft_tissue(8e3).
Material soft_tissue(double young_modulus);
/// soft_tissue()'s mass damping [1/s].
inline constexpr double kSoftTissueMassDamping = 40.0;

/// Checks every field; the message names the field, its value and the allowed range.
Status validate(const Material& material);

/// Continuum moduli of the material [Pa].
double shear_modulus(const Material& material);   ///< G = E / (2 (1 + nu))
double bulk_modulus(const Material& material);    ///< B = E / (3 (1 - 2 nu))
double lame_lambda(const Material& material);     ///< lambda = E nu / ((1 + nu)(1 - 2 nu))
double p_wave_modulus(const Material& material);  ///< lambda + 2 G
/// Speed of the fastest (pressure) wave [m/s]: sqrt((lambda + 2 G) / rho).
double pressure_wave_speed(const Material& material);

}  // namespace cubespring
