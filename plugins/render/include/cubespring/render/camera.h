// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#pragma once

#include <Eigen/Core>

#include "cubespring/result.h"

/// Units are SI throughout the API: metres, kilograms, seconds, newtons, pascals. Angles of the
/// camera are in degrees, image sizes in pixels.
namespace cubespring {

/// A pinhole camera with OpenGL's conventions (right-handed, looking down its own -z). The
/// renderer loads exactly view() and projection() into OpenGL, so project() predicts where a point
/// lands in a frame without asking OpenGL.
struct Camera {
  Eigen::Vector3d position{0.0, -0.5, 0.2};  ///< eye [m]
  Eigen::Vector3d target{0.0, 0.0, 0.0};     ///< point seen at the image centre [m]
  Eigen::Vector3d up{0.0, 0.0, 1.0};         ///< world direction shown upward [-]; not parallel to target - position
  double vertical_fov_degrees = 40;          ///< full vertical opening angle [deg], in (0, 180)
  double near = 0.01;                        ///< near clipping distance [m], > 0
  double far = 100;                          ///< far clipping distance [m], > near

  /// World to eye transform (gluLookAt's matrix).
  Eigen::Matrix4d view() const;
  /// Eye to clip transform for an image of aspect = width / height (gluPerspective's matrix).
  Eigen::Matrix4d projection(double aspect) const;
  /// Where a world point [m] lands in a width x height image [pixels]: x to the right from the left
  /// edge, y down from the top edge, so pixel (col, row) covers [col, col + 1) x [row, row + 1) and
  /// its centre is (col + 0.5, row + 0.5). Meaningless for points behind the camera.
  Eigen::Vector2d project(const Eigen::Vector3d& point, int width, int height) const;
};

/// Checks that a camera can form an image: finite values, fov in (0, 180), 0 < near < far, an eye
/// apart from the target and an up direction not along the line of sight. Names the field at fault.
Status validate(const Camera& camera);

}  // namespace cubespring
