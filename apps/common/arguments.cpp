// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "arguments.h"

#include <cmath>
#include <sstream>
#include <vector>

#include "message_text.h"

namespace cubespring::app {
namespace {

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> parts;
  std::stringstream stream(text);
  std::string part;
  while (std::getline(stream, part, ',')) parts.push_back(part);
  if (!text.empty() && text.back() == ',') parts.emplace_back();
  return parts;
}

}  // namespace

Result<Eigen::Vector3i> parse_counts(const std::string& flag, const std::string& text) {
  const std::vector<std::string> parts = split(text);
  const std::string expected =
      flag + " " + shown_argument(text) + ": expected three whole numbers from 1 to 100000, as NX,NY,NZ";
  if (parts.size() != 3) return Status::error(expected);
  Eigen::Vector3i counts;
  for (int i = 0; i < 3; ++i) {
    std::size_t used = 0;
    long value = 0;
    try {
      value = std::stol(parts[i], &used);
    } catch (const std::exception&) {
      return Status::error(expected);
    }
    if (used != parts[i].size() || value < 1 || value > 100000) return Status::error(expected);
    counts[i] = static_cast<int>(value);
  }
  return counts;
}

Result<Eigen::Vector3d> parse_sizes(const std::string& flag, const std::string& text) {
  const std::vector<std::string> parts = split(text);
  const std::string expected =
      flag + " " + shown_argument(text) + ": expected one size or three sizes HX,HY,HZ, each a number > 0 (metres)";
  if (parts.size() != 1 && parts.size() != 3) return Status::error(expected);
  Eigen::Vector3d sizes;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    std::size_t used = 0;
    double value = 0;
    try {
      value = std::stod(parts[i], &used);
    } catch (const std::exception&) {
      return Status::error(expected);
    }
    if (used != parts[i].size() || !std::isfinite(value) || value <= 0.0) return Status::error(expected);
    sizes[static_cast<int>(i)] = value;
  }
  if (parts.size() == 1) sizes.setConstant(sizes[0]);
  return sizes;
}

}  // namespace cubespring::app
