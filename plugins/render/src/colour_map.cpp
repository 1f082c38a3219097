// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "cubespring/render/colour_map.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <utility>

namespace cubespring {
namespace {

Eigen::Vector3f from_hex(std::uint32_t rgb) {
  return Eigen::Vector3f(static_cast<float>((rgb >> 16) & 0xff), static_cast<float>((rgb >> 8) & 0xff),
                         static_cast<float>(rgb & 0xff)) /
         255.0f;
}

std::vector<Eigen::Vector3f> from_hex(std::initializer_list<std::uint32_t> table) {
  std::vector<Eigen::Vector3f> stops;
  for (std::uint32_t rgb : table) stops.push_back(from_hex(rgb));
  return stops;
}

}  // namespace

ColourMap ColourMap::viridis() {
  // matplotlib's viridis at 15 evenly spaced stops (R viridisLite::viridis(15))
  return ColourMap(from_hex({0x440154, 0x481B6D, 0x46337E, 0x3F4889, 0x365C8D, 0x2E6E8E, 0x277F8E, 0x21908C, 0x1FA187,
                             0x2DB27D, 0x4AC16D, 0x71CF57, 0x9FDA3A, 0xCFE11C, 0xFDE725}));
}

ColourMap ColourMap::blue_white_red() {
  // ColorBrewer RdBu with 7 classes, reversed so that low is blue
  return ColourMap(from_hex({0x2166AC, 0x67A9CF, 0xD1E5F0, 0xF7F7F7, 0xFDDBC7, 0xEF8A62, 0xB2182B}));
}

ColourMap::ColourMap(std::vector<Eigen::Vector3f> stops) : stops_(std::move(stops)) {
  if (stops_.empty()) stops_.push_back(Eigen::Vector3f::Zero());
}

Eigen::Vector3f ColourMap::colour(double t) const {
  if (std::isnan(t)) return nan_colour();
  if (stops_.size() == 1) return stops_.front();
  // position among the stops: segment i from stop i to stop i + 1, fraction f along it
  const double last = static_cast<double>(stops_.size() - 1);
  const double position = std::clamp(t, 0.0, 1.0) * last;
  const std::size_t i = std::min(static_cast<std::size_t>(position), stops_.size() - 2);
  const float f = static_cast<float>(position - static_cast<double>(i));
  return (1.0f - f) * stops_[i] + f * stops_[i + 1];
}

Eigen::Matrix3Xf ColourMap::colours(const Eigen::VectorXd& values, double low, double high) const {
  Eigen::Matrix3Xf result(3, values.size());
  const double range = high - low;
  for (Eigen::Index i = 0; i < values.size(); ++i) {
    const double v = values[i];
    const double t = range > 0.0 ? (v - low) / range : (std::isnan(v) ? v : 0.0);
    result.col(i) = colour(t);
  }
  return result;
}

Eigen::VectorXd displacement_magnitudes(const Eigen::Matrix3Xd& rest, const Eigen::Matrix3Xd& current) {
  return (current - rest).colwise().norm().transpose();
}

}  // namespace cubespring
