// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "cubespring/lattice.h"

#include <iomanip>
#include <sstream>

#include "cubespring/voxelize.h"

namespace cubespring {

Status check_lattice_size(double cells, std::uint64_t memory_limit) {
  const std::uint64_t limit = memory_limit > 0 ? memory_limit : default_memory_limit();
  std::ostringstream message;
  message << std::fixed << std::setprecision(0) << cells << " cells";
  if (!(cells <= static_cast<double>(kMaxCells))) {
    message << ": a body may have at most " << kMaxCells << " (its springs are indexed by int)";
    return Status::error(message.str());
  }
  // a compact body has about as many nodes as cells and 7 springs a cell
  const auto count = static_cast<std::uint64_t>(cells);
  const std::uint64_t bytes = estimate_body_bytes(count, count, 7 * count);
  if (bytes > limit) {
    message << std::setprecision(3) << " take about " << static_cast<double>(bytes) / 1e9
            << " GB once built, more than the memory limit of " << static_cast<double>(limit) / 1e9 << " GB"
            << (memory_limit > 0 ? "" : " (half this machine's memory)");
    return Status::error(message.str());
  }
  return {};
}

LatticeDesc box_lattice(const Eigen::Vector3i& counts, const Eigen::Vector3d& cell_size, const Material& material) {
  LatticeDesc desc;
  desc.cell_size = cell_size;
  desc.materials = {material};
  const Eigen::Vector3i n = counts.cwiseMax(0);
  desc.cells.reserve(static_cast<std::size_t>(n.x()) * n.y() * n.z());
  for (int k = 0; k < n.z(); ++k) {
    for (int j = 0; j < n.y(); ++j) {
      for (int i = 0; i < n.x(); ++i) desc.cells.emplace_back(i, j, k);
    }
  }
  return desc;
}

}  // namespace cubespring
