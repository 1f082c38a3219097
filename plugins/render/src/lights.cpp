// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "cubespring/render/lights.h"

namespace cubespring {

std::vector<Light> default_lights() {
  return {Light{Eigen::Vector3d(0.4, 0.6, -1.0), Eigen::Vector3f(0.75f, 0.75f, 0.72f)},
          Light{Eigen::Vector3d(-0.6, -0.2, -0.3), Eigen::Vector3f(0.25f, 0.27f, 0.32f)}};
}

}  // namespace cubespring
