// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#pragma once

#include <vector>

#include <Eigen/Core>

namespace cubespring {

/// A colour scale: colours at evenly spaced stops over [0, 1], linear in between (in sRGB values,
/// which is how the published tables are sampled).
class ColourMap {
 public:
  /// Perceptually uniform, dark blue to yellow, readable in grey and by colour-blind viewers (van
  /// der Walt and Smith's viridis, sampled at 15 stops). The default for magnitudes.
  static ColourMap viridis();
  /// Diverging blue - white - red (ColorBrewer RdBu, 7 classes): for signed values centred on 0.
  static ColourMap blue_white_red();

  /// A map through `stops` (at least one), each an RGB colour in [0, 1].
  explicit ColourMap(std::vector<Eigen::Vector3f> stops);

  /// The colour at t in [0, 1]; t outside is clamped; NaN gives nan_colour().
  Eigen::Vector3f colour(double t) const;
  /// Colour of each value with `low` at t = 0 and `high` at t = 1, (3 x values.size()); when
  /// high <= low every finite value maps to t = 0.
  Eigen::Matrix3Xf colours(const Eigen::VectorXd& values, double low, double high) const;

  /// Magenta: no scale uses it, so a NaN (a blown-up simulation) stands out.
  static Eigen::Vector3f nan_colour() { return {1.0f, 0.0f, 1.0f}; }
  const std::vector<Eigen::Vector3f>& stops() const { return stops_; }

 private:
  std::vector<Eigen::Vector3f> stops_;
};

/// Distance each vertex moved [m]: |current - rest| per column of two (3 x n) position arrays of
/// the same size, e.g. to colour a deformed mesh by displacement.
Eigen::VectorXd displacement_magnitudes(const Eigen::Matrix3Xd& rest, const Eigen::Matrix3Xd& current);

}  // namespace cubespring
