// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "grid_spring_floor.h"

#include <algorithm>
#include <cmath>

// Built for AVX-512 and AVX2 beside the baseline, like the engine's grid passes
// (src/forces/grid/grid_forces.cpp), so that the floor is as fast as the machine allows.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define CUBESPRING_FLOOR_CLONES __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define CUBESPRING_FLOOR_CLONES
#endif

namespace cubespring::app {

GridSpringFloor::GridSpringFloor(const Eigen::Vector3i& cells, double h, const Eigen::Matrix3Xd& positions,
                                 double edge_k, double diagonal_k)
    : cells_(cells), nodes_(cells + Eigen::Vector3i::Ones()), h_(h), edge_k_(edge_k), diagonal_k_(diagonal_k) {
  const auto count = static_cast<std::size_t>(positions.cols());
  x_.resize(count);
  y_.resize(count);
  z_.resize(count);
  for (std::size_t n = 0; n < count; ++n) {
    x_[n] = positions(0, static_cast<Eigen::Index>(n));
    y_[n] = positions(1, static_cast<Eigen::Index>(n));
    z_[n] = positions(2, static_cast<Eigen::Index>(n));
  }
  fx_.assign(count, 0.0);
  fy_.assign(count, 0.0);
  fz_.assign(count, 0.0);
  const auto row = static_cast<std::size_t>(nodes_.x());
  row_x_.resize(row);
  row_y_.resize(row);
  row_z_.resize(row);
}

// The springs from grid offset `start` to `end` (each 0 or 1 per axis) of every cell-sized step
// that fits in the box: along an axis where start and end differ there are as many as cells,
// elsewhere as many as nodes. Row by row: the forces of a row's springs, then their sums on the
// first and on the second ends, three loops the compiler vectorises.
CUBESPRING_FLOOR_CLONES void GridSpringFloor::family(const Eigen::Vector3i& start, const Eigen::Vector3i& end,
                                                     double rest, double k) {
  Eigen::Vector3i range;
  for (int a = 0; a < 3; ++a) range[a] = start[a] != end[a] ? cells_[a] : nodes_[a];
  const int sy = nodes_.x(), sz = nodes_.x() * nodes_.y();
  const int from = start.x() + sy * start.y() + sz * start.z();
  const int to = end.x() + sy * end.y() + sz * end.z();
  const double* __restrict x = x_.data();
  const double* __restrict y = y_.data();
  const double* __restrict z = z_.data();
  double* __restrict fx = fx_.data();
  double* __restrict fy = fy_.data();
  double* __restrict fz = fz_.data();
  double* __restrict rx = row_x_.data();
  double* __restrict ry = row_y_.data();
  double* __restrict rz = row_z_.data();
  const int count = range.x();
  for (int kz = 0; kz < range.z(); ++kz) {
    for (int jy = 0; jy < range.y(); ++jy) {
      const int a = sy * jy + sz * kz + from, b = sy * jy + sz * kz + to;
#pragma omp simd
      for (int i = 0; i < count; ++i) {
        const double dx = x[b + i] - x[a + i], dy = y[b + i] - y[a + i], dz = z[b + i] - z[a + i];
        const double length = std::sqrt(dx * dx + dy * dy + dz * dz);
        const double scale = k * (length - rest) / length;
        rx[i] = scale * dx;
        ry[i] = scale * dy;
        rz[i] = scale * dz;
      }
#pragma omp simd
      for (int i = 0; i < count; ++i) {
        fx[a + i] += rx[i];
        fy[a + i] += ry[i];
        fz[a + i] += rz[i];
      }
#pragma omp simd
      for (int i = 0; i < count; ++i) {
        fx[b + i] -= rx[i];
        fy[b + i] -= ry[i];
        fz[b + i] -= rz[i];
      }
    }
  }
  springs_ += static_cast<long>(range.x()) * range.y() * range.z();
}

void GridSpringFloor::operator()() {
  std::fill(fx_.begin(), fx_.end(), 0.0);
  std::fill(fy_.begin(), fy_.end(), 0.0);
  std::fill(fz_.begin(), fz_.end(), 0.0);
  springs_ = 0;
  for (int a = 0; a < 3; ++a) family(Eigen::Vector3i::Zero(), Eigen::Vector3i::Unit(a), h_, edge_k_);
  const double diagonal = std::sqrt(3.0) * h_;
  for (int c = 0; c < 4; ++c) {  // corner c to corner 7 - c
    const Eigen::Vector3i start(c & 1, (c >> 1) & 1, 0), end(1 - (c & 1), 1 - ((c >> 1) & 1), 1);
    family(start, end, diagonal, diagonal_k_);
  }
}

double GridSpringFloor::checksum() const {
  double sum = 0.0;
  for (std::size_t n = 0; n < fx_.size(); ++n) sum += fx_[n] * fx_[n] + fy_[n] * fy_[n] + fz_[n] * fz_[n];
  return sum;
}

}  // namespace cubespring::app
