// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Between Eigen's doubles and Bullet's btScalar (float or double, as Bullet was built): vectors
// (positions [m], velocities [m/s], forces [N], ...) and rigid poses (rotation and translation
// [m]). The plugin, the scene runtime and a simulator app share these.
#pragma once

#include <LinearMath/btTransform.h>
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

/// A pose as Bullet's transform (its rotation through a quaternion).
inline btTransform to_bt(const Eigen::Isometry3d& pose) {
  const Eigen::Quaterniond q(pose.linear());
  return btTransform(btQuaternion(static_cast<btScalar>(q.x()), static_cast<btScalar>(q.y()),
                                  static_cast<btScalar>(q.z()), static_cast<btScalar>(q.w())),
                     to_bt(Eigen::Vector3d(pose.translation())));
}

/// Bullet's transform as a pose (its quaternion normalised, as btScalar may be float).
inline Eigen::Isometry3d to_eigen(const btTransform& transform) {
  const btQuaternion q = transform.getRotation();
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::Quaterniond(q.w(), q.x(), q.y(), q.z()).normalized().toRotationMatrix();
  pose.translation() = to_eigen(transform.getOrigin());
  return pose;
}

}  // namespace cubespring::bullet
