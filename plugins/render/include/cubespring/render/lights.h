// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#pragma once

#include <vector>

#include <Eigen/Core>

/// Units are SI throughout the API: metres, kilograms, seconds, newtons, pascals.
namespace cubespring {

/// A directional light (the sun: parallel rays, no falloff).
struct Light {
  Eigen::Vector3d direction{0.0, 0.0, -1.0};  ///< direction the light travels, world frame [-]; non-zero
  Eigen::Vector3f colour{1.0f, 1.0f, 1.0f};   ///< diffuse and specular intensity per channel, >= 0
};

/// A key light from above front left and a weaker, cooler fill light from the right and behind.
std::vector<Light> default_lights();

}  // namespace cubespring
