// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Where the grid passes (grid_forces.cpp) keep their arrays: the state and forces of every point
// of the grid, and the passes' temporaries for a few z-layers only (docs/data-layout.md, "Dense
// bodies: the grid passes").
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "forces/grid/grid_layout.h"
#include "invariant.h"

namespace cubespring {

// Arrays of every point of the grid, each padded by grid.padding points on both sides: the state
// the passes read and the forces they make.
enum GridSlot : int {
  kPosition = 0,  // x, y, z
  kVelocity = 3,  // x, y, z
  kForce = 6,     // x, y, z
  kGridSlots = 9
};
// The passes' temporaries, kept for kRingLayers z-layers only, per thread: a ring that holds
// layer L in place L % kRingLayers, so that they stay in cache (the whole grid's temporaries
// spill out of L2 from 32x8x8 cells on, and out of L3 from 32x32x32). The top layer of points
// has a place of its own: no z-edge, diagonal or cell starts there, so their arrays in that
// place keep the zeros they were first set to.
enum LayerSlot : int {
  kCellTension = kGridSlots,  // x, y, z
  // per family x, y, z: the spring's force on its first end (edges: the unit vector until pass 3)
  kFamilyForce = kCellTension + 3,
  kEdgeLength = kFamilyForce + 3 * kSpringFamilies,
  kEdgeRate = kEdgeLength + kEdgeFamilies,
  kEdgeOwnTension = kEdgeRate + kEdgeFamilies,
  kEdgeVector = kEdgeOwnTension + kEdgeFamilies,  // x, y, z per edge family (twist only)
  kCellTwist = kEdgeVector + 3 * kEdgeFamilies,   // Q per face normal x, y, z (twist only)
  // per face normal d, the face at g: 0.5 (Q_d of the cell at g - unit(d), minus Q_d of the
  // cell at g) (twist only)
  kFaceTwist = kCellTwist + 3,
  // per axis p, x, y, z: a quarter of the neo-Hookean term's dC/dm_p of the cell at g, the force
  // each of the cell's 4 edges along p puts on its first end (neo-Hookean bodies only)
  kCellNeoHookean = kFaceTwist + 3,
  kSlots = kCellNeoHookean + 9
};
constexpr int kLayerSlots = static_cast<int>(kSlots) - static_cast<int>(kGridSlots);
// The passes of layer L read the temporaries of layers L - 1 to L + 1 (run_chunk).
constexpr int kRingLayers = 3;
constexpr int kRingPlaces = kRingLayers + 1;

// A layer's values of one slot, index i for point layer * stride_z + i. The grid's slots run on
// through the other layers; a ring's hold their layer, and zeros a row and a point beyond it on
// both sides (the in-layer reach of a spring or a cell); layers below the grid read as zeros.
// The passes write a layer's span of nodes only (GridLayout::layer_spans): a ring's place holds
// zeros outside the span of the layer it holds, which is what a spring or cell of the body reads
// there (a place taken by another layer first clears what the one before wrote outside its span).
class LayerArrays {
 public:
  LayerArrays(const GridLayout& grid, double* grid_arrays, const double* zeros, double* ring, double* held)
      : grid_(grid), grid_arrays_(grid_arrays), zeros_(zeros), ring_(ring), held_(held) {}

  /// `slot` at the points g + step of layer `layer` (step in cells along x, y, z).
  [[gnu::always_inline]] const double* in(int slot, int layer,
                                          const Eigen::Vector3i& step = Eigen::Vector3i::Zero()) const {
    const int in_layer = step.x() + grid_.stride_y * step.y();
    layer += step.z();
    if (slot >= kGridSlots && layer < 0) return zeros_ + ring_offset(slot) + in_layer;
    return place(slot, layer) + in_layer;
  }
  /// A ring's slots of one layer lie this far apart (the x, y, z of a vector, for instance).
  std::size_t slot_stride() const { return layer_stride(grid_); }
  /// Only layers of the grid are written (the passes return for the layers beyond it).
  [[gnu::always_inline]] double* out(int slot, int layer) const {
    CUBESPRING_ASSERT(layer >= 0);
    if (slot >= kGridSlots && held_[ring_place(layer)] != layer) hold(layer);
    return place(slot, layer);
  }

  static int layer_padding(const GridLayout& grid) { return grid.stride_y + 1; }
  static std::size_t layer_stride(const GridLayout& grid) {
    return static_cast<std::size_t>(grid.stride_z + 2 * layer_padding(grid));
  }
  static std::size_t grid_stride(const GridLayout& grid) {
    return static_cast<std::size_t>(grid.num_points + 2 * grid.padding);
  }

 private:
  [[gnu::always_inline]] double* place(int slot, int layer) const {
    CUBESPRING_ASSERT(layer >= 0 && layer < grid_.points.z());
    if (slot < kGridSlots) {
      const std::size_t point = grid_.padding + static_cast<std::size_t>(layer) * grid_.stride_z;
      return grid_arrays_ + grid_stride(grid_) * slot + point;
    }
    return ring_ + layer_stride(grid_) * kLayerSlots * static_cast<std::size_t>(ring_place(layer)) + ring_offset(slot);
  }
  int ring_place(int layer) const { return layer == grid_.points.z() - 1 ? kRingLayers : layer % kRingLayers; }
  // Gives `layer` its place: zeros where the layer held there before wrote outside its span.
  void hold(int layer) const {
    const int place_index = ring_place(layer);
    const double before = held_[place_index];
    held_[place_index] = layer;
    if (before < 0.0) return;  // the zeros the place was first set to
    const PointSpan was = grid_.layer_spans[static_cast<std::size_t>(before)];
    const PointSpan now = grid_.layer_spans[static_cast<std::size_t>(layer)];
    const int left_end = std::max(was.begin, std::min(was.end, now.begin));
    const int right_begin = std::min(was.end, std::max(was.begin, now.end));
    for (int slot = kGridSlots; slot < kSlots; ++slot) {
      double* values = place(slot, layer);
      std::fill(values + was.begin, values + left_end, 0.0);
      std::fill(values + right_begin, values + was.end, 0.0);
    }
  }
  // where a slot's values begin in a layer of the ring
  std::size_t ring_offset(int slot) const {
    return layer_stride(grid_) * static_cast<std::size_t>(slot - kGridSlots) + layer_padding(grid_);
  }

  const GridLayout& grid_;
  double* grid_arrays_;
  const double* zeros_;
  double* ring_;
  double* held_;  // the layer each place of the ring holds (-1: none yet)
};

// The scratch vector: the grid's slots, a layer of zeros (every slot), then a ring per thread.
class GridScratch {
 public:
  GridScratch(const GridLayout& grid, int rings, std::vector<double>& scratch) : grid_(grid) {
    const std::size_t layer = LayerArrays::layer_stride(grid) * kLayerSlots;
    const std::size_t rings_and_zeros = 1 + static_cast<std::size_t>(rings) * kRingPlaces;
    held_offset_ = LayerArrays::grid_stride(grid) * kGridSlots + layer * rings_and_zeros;
    const std::size_t size = held_offset_ + static_cast<std::size_t>(rings) * kHeldStride;
    if (scratch.size() != size) {
      scratch.assign(size, 0.0);  // the paddings and the points outside the body stay as set here
      std::fill(scratch.begin() + static_cast<std::ptrdiff_t>(held_offset_), scratch.end(), -1.0);
      base_ = scratch.data();
      for (int axis = 0; axis < 3; ++axis) {
        double* position = arrays(0).out(kPosition + axis, 0);
        for (int p = 0; p < grid.num_points; ++p) position[p] = grid.rest_points(axis, p);
      }
    }
    base_ = scratch.data();
  }
  /// The arrays of the thread that uses ring `ring`.
  LayerArrays arrays(int ring) const {
    double* zeros = base_ + LayerArrays::grid_stride(grid_) * kGridSlots;
    const std::size_t ring_size = LayerArrays::layer_stride(grid_) * kRingPlaces * kLayerSlots;
    double* first_ring = zeros + LayerArrays::layer_stride(grid_) * kLayerSlots;
    return LayerArrays(grid_, base_, zeros, first_ring + ring_size * static_cast<std::size_t>(ring),
                       base_ + held_offset_ + static_cast<std::size_t>(ring) * kHeldStride);
  }

 private:
  const GridLayout& grid_;
  double* base_ = nullptr;
  std::size_t held_offset_ = 0;  // where each ring's held layers are kept, after the rings
  // 128 bytes apart, so that no two rings' share a cache line (unaligned as they are): every
  // pass's out() reads its thread's, and no thread writes a line another reads
  static constexpr std::size_t kHeldStride = 16;
  static_assert(kHeldStride >= kRingPlaces);
};

}  // namespace cubespring
