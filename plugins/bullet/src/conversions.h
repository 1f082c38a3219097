// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Between Eigen's doubles and Bullet's btScalar (float or double, as Bullet was built).
#pragma once

#include <LinearMath/btVector3.h>
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace cubespring::bullet {

inline btVector3 to_bt(const Eigen::Vector3d& v) {
  return btVector3(static_cast<btScalar>(v.x()), static_cast<btScalar>(v.y()), static_cast<btScalar>(v.z()));
}

inline Eigen::Vector3d to_eigen(const btVector3& v) {
  return Eigen::Vector3d(static_cast<double>(v.x()), static_cast<double>(v.y()), static_cast<double>(v.z()));
}

}  // namespace cubespring::bullet
