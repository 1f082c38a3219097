// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "cubespring/render/camera.h"

#include <cmath>
#include <sstream>
#include <string>

#include <Eigen/Geometry>

namespace cubespring {
namespace {

constexpr double kPi = 3.14159265358979323846;

bool finite(const Eigen::Vector3d& v) { return v.allFinite(); }

std::string text(const Eigen::Vector3d& v) {
  std::ostringstream out;
  out << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")";
  return out.str();
}

}  // namespace

Eigen::Matrix4d Camera::view() const {
  // orthonormal eye frame: s to the right, u up, the camera looks down -f
  const Eigen::Vector3d f = (target - position).normalized();
  const Eigen::Vector3d s = f.cross(up).normalized();
  const Eigen::Vector3d u = s.cross(f);
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.block<1, 3>(0, 0) = s.transpose();
  m.block<1, 3>(1, 0) = u.transpose();
  m.block<1, 3>(2, 0) = -f.transpose();
  m(0, 3) = -s.dot(position);
  m(1, 3) = -u.dot(position);
  m(2, 3) = f.dot(position);
  return m;
}

Eigen::Matrix4d Camera::projection(double aspect) const {
  const double focal = 1.0 / std::tan(0.5 * vertical_fov_degrees * kPi / 180.0);
  Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
  m(0, 0) = focal / aspect;
  m(1, 1) = focal;
  m(2, 2) = (far + near) / (near - far);
  m(2, 3) = 2.0 * far * near / (near - far);
  m(3, 2) = -1.0;
  return m;
}

Eigen::Vector2d Camera::project(const Eigen::Vector3d& point, int width, int height) const {
  const double aspect = static_cast<double>(width) / static_cast<double>(height);
  const Eigen::Vector4d clip = projection(aspect) * view() * point.homogeneous();
  // normalized device coordinates in [-1, 1], y up; the image counts rows from the top
  const double x_ndc = clip.x() / clip.w();
  const double y_ndc = clip.y() / clip.w();
  return {0.5 * (x_ndc + 1.0) * width, 0.5 * (1.0 - y_ndc) * height};
}

Status validate(const Camera& camera) {
  if (!finite(camera.position)) return Status::error("camera.position is not finite: " + text(camera.position));
  if (!finite(camera.target)) return Status::error("camera.target is not finite: " + text(camera.target));
  if (!finite(camera.up)) return Status::error("camera.up is not finite: " + text(camera.up));
  if (!(camera.vertical_fov_degrees > 0.0 && camera.vertical_fov_degrees < 180.0)) {
    return Status::error("camera.vertical_fov_degrees is " + std::to_string(camera.vertical_fov_degrees) +
                         ": it must be between 0 and 180 degrees (exclusive)");
  }
  if (!(camera.near > 0.0 && std::isfinite(camera.near))) {
    return Status::error("camera.near is " + std::to_string(camera.near) + " m: it must be > 0");
  }
  if (!(camera.far > camera.near && std::isfinite(camera.far))) {
    return Status::error("camera.far is " + std::to_string(camera.far) + " m: it must be finite and > near (" +
                         std::to_string(camera.near) + " m)");
  }
  const Eigen::Vector3d sight = camera.target - camera.position;
  if (!(sight.norm() > 0.0)) {
    return Status::error("camera.position equals camera.target " + text(camera.target) +
                         ": the camera needs a direction to look in");
  }
  if (!(sight.normalized().cross(camera.up).norm() > 1e-9 * camera.up.norm())) {
    return Status::error("camera.up " + text(camera.up) + " is zero or along the line of sight " + text(sight) +
                         ": choose an up direction across it");
  }
  return {};
}

}  // namespace cubespring
