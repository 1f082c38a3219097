// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "cubespring/lattice.h"

namespace cubespring {

LatticeDesc box_lattice(const Eigen::Vector3i& counts, const Eigen::Vector3d& cell_size,
                        const Material& material) {
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
