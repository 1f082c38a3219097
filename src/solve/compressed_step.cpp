// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// compressed_step_factor() and compressed_time_step(): the thin cells of a body, which the Bullet
// plugin looks for every few explicit sub-steps (stable_time_step.h says why a thin cell shortens
// the step).
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "cubespring/stable_time_step.h"
#include "forces/grid/vector_clones.h"
#include "model/cell_geometry.h"

namespace cubespring {
namespace {

constexpr double kWideEnough = 2.0;  // a face up to twice its rest area: as at rest
constexpr double kLeast = 0.2;

// A cell's thickness across `axis` as a fraction of its rest size, divided by the square root of
// how far its face is widened beyond kWideEnough, from its frame; 0 for a cell flat or inside out.
double effective_thickness(const Model& model, const CellFrame& frame, int axis) {
  const double volume = frame.volume();
  const double face = frame.edge[(axis + 1) % 3].cross(frame.edge[(axis + 2) % 3]).norm();
  const double thickness = face > 0.0 ? volume / face / model.cell_size[axis] : 0.0;  // of the rest size
  // stretched flat, it is stiffer across than its thickness says
  const double rest_face = model.cell_size[(axis + 1) % 3] * model.cell_size[(axis + 2) % 3];
  const double widened = face / (kWideEnough * rest_face);
  return std::max(thickness, 0.0) / (widened > 1.0 ? std::sqrt(widened) : 1.0);
}

// Cells are searched a block at a time: a loop over the block's cells without a branch, which
// vectorises (its corners gathered), writes each cell's least squared effective thickness and its
// axis, and a short scalar scan then keeps the first least one, as a cell-by-cell search would.
constexpr int kBlock = 256;

struct BlockResult {
  bool flat = false;  // some cell is flat, inside out or not a number
};

// The squared effective thickness of cells [first, first + count) across their thinnest axis
// (`square`, `axis`), as effective_thickness() squared gives it but for rounding.
CUBESPRING_VECTOR_CLONES BlockResult thickness_squares(const Model& model, const double* x, int first, int count,
                                                       double* square, int* axis) {
  const std::array<int, kCornersPerCell>* nodes = model.cell_nodes.data() + first;
  double rest_face[3], widest_square[3], size_square[3];
  for (int a = 0; a < 3; ++a) {
    rest_face[a] = model.cell_size[(a + 1) % 3] * model.cell_size[(a + 2) % 3];
    widest_square[a] = (kWideEnough * rest_face[a]) * (kWideEnough * rest_face[a]);
    size_square[a] = model.cell_size[a] * model.cell_size[a];
  }
  int flat = 0;
#pragma omp simd reduction(| : flat)
  for (int i = 0; i < count; ++i) {
    double m[3][3];  // 4 x the mean edge vectors (the 1/256 and the 16 below take the factor out)
    for (int c = 0; c < 3; ++c) {
      const double p0 = x[3 * nodes[i][0] + c], p1 = x[3 * nodes[i][1] + c], p2 = x[3 * nodes[i][2] + c];
      const double p3 = x[3 * nodes[i][3] + c], p4 = x[3 * nodes[i][4] + c], p5 = x[3 * nodes[i][5] + c];
      const double p6 = x[3 * nodes[i][6] + c], p7 = x[3 * nodes[i][7] + c];
      m[0][c] = ((p1 - p0) + (p3 - p2)) + ((p5 - p4) + (p7 - p6));
      m[1][c] = ((p2 - p0) + (p3 - p1)) + ((p6 - p4) + (p7 - p5));
      m[2][c] = ((p4 - p0) + (p5 - p1)) + ((p6 - p2) + (p7 - p3));
    }
    double face[3][3];  // the face spanned by the other two mean edges: m_{a+1} x m_{a+2}
    for (int a = 0; a < 3; ++a) {
      const double(&q)[3] = m[(a + 1) % 3];
      const double(&r)[3] = m[(a + 2) % 3];
      face[a][0] = q[1] * r[2] - q[2] * r[1];
      face[a][1] = q[2] * r[0] - q[0] * r[2];
      face[a][2] = q[0] * r[1] - q[1] * r[0];
    }
    const double volume = m[0][0] * face[0][0] + m[0][1] * face[0][1] + m[0][2] * face[0][2];
    flat |= static_cast<int>(!(volume > 0.0));
    double least = 0.0;
    int least_axis = 0;
    for (int a = 0; a < 3; ++a) {
      // with the factor 4 of m: volume 64 V, face 16 F, so volume^2 / (face^2 h^2) = 16 V^2 / (F^2 h^2)
      const double face_square = (face[a][0] * face[a][0] + face[a][1] * face[a][1]) + face[a][2] * face[a][2];
      const double real_face_square = face_square * (1.0 / 256.0);
      const bool widened = real_face_square > widest_square[a];
      const double narrowing = widened ? std::sqrt(widest_square[a] / real_face_square) : 1.0;
      const double thickness_square = (volume * volume) / (16.0 * face_square * size_square[a]) * narrowing;
      const bool thinner = a == 0 || thickness_square < least;
      least = thinner ? thickness_square : least;
      least_axis = thinner ? a : least_axis;
    }
    square[i] = volume > 0.0 ? least : 0.0;  // flat, inside out or not a number: as thin as can be
    axis[i] = least_axis;
  }
  return {flat != 0};
}

}  // namespace

double compressed_step_factor(const Model& model, const Eigen::Matrix3Xd& positions) {
  if (model.cell_law == CellLaw::kSprings) return 1.0;
  double square[kBlock];
  int axis[kBlock];
  double least_square = 1.0;  // of the effective thickness; 1 = at rest
  int thinnest_cell = -1, thinnest_axis = 0;
  for (int first = 0; first < model.num_cells(); first += kBlock) {
    const int count = std::min(kBlock, model.num_cells() - first);
    if (thickness_squares(model, positions.data(), first, count, square, axis).flat) return kLeast;
    for (int i = 0; i < count; ++i) {
      if (square[i] < least_square) {
        least_square = square[i];
        thinnest_cell = first + i;
        thinnest_axis = axis[i];
      }
    }
  }
  // the thinnest cell's thickness as effective_thickness() gives it (the search's squares may
  // round differently)
  const double thinnest =
      thinnest_cell < 0
          ? 1.0
          : std::min(1.0, effective_thickness(model, cell_frame(model, positions, thinnest_cell), thinnest_axis));
  return std::clamp(thinnest / kThickEnough, kLeast, 1.0);
}

double compressed_time_step(const Model& model, const Eigen::Matrix3Xd& positions, const Eigen::VectorXd& cell_steps) {
  if (cell_steps.size() != model.num_cells()) {
    throw std::invalid_argument("compressed_time_step: " + std::to_string(cell_steps.size()) + " cell steps for " +
                                std::to_string(model.num_cells()) + " cells");
  }
  double least = std::numeric_limits<double>::infinity();
  if (model.cell_law == CellLaw::kSprings) return least;
  constexpr double kThinSquare = kThickEnough * kThickEnough;
  double square[kBlock];
  int axis[kBlock];
  for (int first = 0; first < model.num_cells(); first += kBlock) {
    const int count = std::min(kBlock, model.num_cells() - first);
    (void)thickness_squares(model, positions.data(), first, count, square, axis);
    for (int i = 0; i < count; ++i) {
      if (square[i] >= kThinSquare) continue;  // keeps its rest step, which the body's sub-step is within
      const double factor = std::max(std::sqrt(square[i]) / kThickEnough, kLeast);
      least = std::min(least, factor * cell_steps[first + i]);
    }
  }
  return least;
}

}  // namespace cubespring
