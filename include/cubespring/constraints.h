// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "cubespring/model.h"
#include "cubespring/result.h"

/// Units are SI throughout the API: metres, kilograms, seconds, newtons, pascals.
namespace cubespring {

/// Nodes whose position is driven rather than simulated: fixed at rest, or moved to a prescribed
/// position that the caller may change between steps (a kinematic tool or clamp). Integrators move
/// a driven node to its target during the step and give it the velocity that gets it there.
/// A node may be driven along some axes only (a frictionless support or platen: its normal
/// component driven, the others free); the calls without an axis drive all three.
class Constraints {
 public:
  Constraints() = default;
  explicit Constraints(const Model& model);

  /// Fixes nodes at their rest position. Errors name an out-of-range index.
  Status fix_nodes(const Model& model, const std::vector<int>& nodes);
  /// Fixes every node whose rest position lies in [lower, upper] [m]; errors if none does.
  Status fix_box(const Model& model, const Eigen::Vector3d& lower, const Eigen::Vector3d& upper);
  /// Drives a node to a position [m] or to rest plus a displacement [m].
  Status prescribe_position(int node, const Eigen::Vector3d& position);
  Status prescribe_displacement(const Model& model, int node, const Eigen::Vector3d& displacement);
  /// Drives every node whose rest position lies in [lower, upper] [m] to rest plus a displacement
  /// [m] (a clamp that moves); errors if no node lies in the box.
  Status prescribe_box_displacement(const Model& model, const Eigen::Vector3d& lower, const Eigen::Vector3d& upper,
                                    const Eigen::Vector3d& displacement);
  /// Drives one component (axis 0, 1, 2: x, y, z) of every node whose rest position lies in
  /// [lower, upper] [m] to its rest value plus `displacement` [m], leaving the other components as
  /// they were (free, or driven by another call): a frictionless support (displacement 0) or
  /// platen. Errors name an axis out of range, a displacement that is not finite or an empty box.
  Status prescribe_box_axis_displacement(const Model& model, const Eigen::Vector3d& lower, const Eigen::Vector3d& upper,
                                         int axis, double displacement);
  /// Drives component `axis` of one node to `coordinate` [m] (the others as they were).
  Status prescribe_axis_position(int node, int axis, double coordinate);
  /// The same constraints on the body after its nodes were renumbered (cells removed,
  /// cell_removal.h): node n becomes node new_node[n] of `num_new_nodes`, or is dropped where
  /// that is -1. Errors name a map of the wrong size or an index out of range.
  Result<Constraints> renumbered(const std::vector<int>& new_node, int num_new_nodes) const;
  /// The same constraints on a body whose node n was node source_node[n] of this one (nodes
  /// duplicated where faces were split, face_split.h): each node driven as its source was.
  /// Errors name a source out of range.
  Result<Constraints> gathered(const std::vector<int>& source_node) const;
  /// Makes a node free again.
  Status release(int node);

  /// Whether any component of the node is driven.
  bool is_driven(int node) const { return driven_[node] != 0; }
  /// The node's driven components: bit a set when component a is driven (kAllAxes: all three).
  std::uint8_t driven_axes(int node) const { return driven_[node]; }
  static constexpr std::uint8_t kAllAxes = 7;
  /// Where the node is driven to [m] (its driven components; the others mean nothing).
  const Eigen::Vector3d target(int node) const { return target_.col(node); }
  int num_driven() const;
  bool empty() const { return num_driven() == 0; }
  int num_nodes() const { return static_cast<int>(driven_.size()); }
  /// One flag per node, non-zero when driven: its driven_axes() (num_nodes() of them).
  const std::uint8_t* driven_flags() const { return driven_.data(); }

 private:
  Status check_index(int node) const;
  std::vector<std::uint8_t> driven_;
  Eigen::Matrix3Xd target_;
};

}  // namespace cubespring
