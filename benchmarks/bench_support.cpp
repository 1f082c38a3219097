// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "bench_support.h"

#include <algorithm>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "arguments.h"

namespace cubespring::app {

std::string cpu_name() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line)) {
    if (line.rfind("model name", 0) != 0) continue;
    const std::size_t colon = line.find(':');
    if (colon != std::string::npos) return line.substr(std::min(line.size(), colon + 2));
  }
  return "";
}

std::vector<Eigen::Vector3i> parse_size_list(const std::string& text) {
  std::vector<Eigen::Vector3i> sizes;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ';')) {
    Result<Eigen::Vector3i> counts = parse_counts("--sizes", item);
    if (!counts) throw std::runtime_error(counts.message());
    sizes.push_back(counts.value());
  }
  if (sizes.empty()) throw std::runtime_error("--sizes: expected at least one NX,NY,NZ");
  return sizes;
}

std::vector<double> parse_number_list(const std::string& text, const std::string& flag, bool (*accept)(double),
                                      const std::string& expected) {
  std::vector<double> numbers;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) {
    std::size_t used = 0;
    double value = 0.0;
    try {
      value = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != item.size() || !accept(value)) throw std::runtime_error(flag + ": '" + item + "' is not " + expected);
    numbers.push_back(value);
  }
  if (numbers.empty()) throw std::runtime_error(flag + ": expected at least one value, got '" + text + "'");
  return numbers;
}

LatticeDesc ball_lattice(int across, double cell_size, const Material& material, double hollow) {
  LatticeDesc desc;
  desc.cell_size.setConstant(cell_size);
  desc.materials = {material};
  const double radius = 0.5 * across;
  for (int k = 0; k < across; ++k) {
    for (int j = 0; j < across; ++j) {
      for (int i = 0; i < across; ++i) {
        const double distance = (Eigen::Vector3d(i, j, k).array() + 0.5 - radius).matrix().norm();
        if (distance <= radius && distance >= hollow * radius) desc.cells.emplace_back(i, j, k);
      }
    }
  }
  return desc;
}

}  // namespace cubespring::app
