// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Hertz's force for a rigid sphere pressed into an elastic layer bonded to a rigid base, with the
// correction of Dimitriadis, Horkay, Maresca, Kachar and Chadwick (Biophys. J. 82, 2002) for the
// layer's finite thickness t: F = F_Hertz (1 - 2 a0/pi chi + 4 a0^2/pi^2 chi^2 - 8/pi^3 (a0^3 +
// 4 pi^2/15 b0) chi^3 - 16 a0/pi^4 (a0^3 + 3 pi^2/5 b0) chi^4), chi = sqrt(R d) / t; at nu = 0.5 its
// coefficients are 1.133, 1.283, 0.769, 0.0975. The indentation tests' closed form.
#pragma once

#include <cmath>

namespace cubespring::validation {

/// The bonded layer's factor on Hertz's force at chi = sqrt(R d) / t.
inline double bonded_layer_factor(double chi, double nu) {
  const double pi = 3.14159265358979323846;
  const double a0 = -(1.2876 - 1.4678 * nu + 1.3442 * nu * nu) / (1.0 - nu);
  const double b0 = (0.6387 - 1.0277 * nu + 1.5164 * nu * nu) / (1.0 - nu);
  return 1.0 - 2.0 * a0 / pi * chi + 4.0 * a0 * a0 / (pi * pi) * chi * chi -
         8.0 / (pi * pi * pi) * (a0 * a0 * a0 + 4.0 * pi * pi / 15.0 * b0) * chi * chi * chi -
         16.0 * a0 / (pi * pi * pi * pi) * (a0 * a0 * a0 + 3.0 * pi * pi / 5.0 * b0) * chi * chi * chi * chi;
}

/// Hertz's force [N] of a sphere of radius R [m] pressed d [m] into a layer t [m] thick of
/// Young's modulus E [Pa] and Poisson's ratio nu, bonded to its base.
inline double hertz_on_bonded_layer(double young, double nu, double radius, double depth, double thickness) {
  const double hertz = 4.0 / 3.0 * young / (1.0 - nu * nu) * std::sqrt(radius) * std::pow(depth, 1.5);
  return hertz * bonded_layer_factor(std::sqrt(radius * depth) / thickness, nu);
}

}  // namespace cubespring::validation
