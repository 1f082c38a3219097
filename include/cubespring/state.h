// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#pragma once

#include <cstdint>
#include <string>

#include <Eigen/Core>

#include "cubespring/model.h"
#include "cubespring/result.h"

/// Units are SI throughout the API: metres, kilograms, seconds, newtons, pascals.
namespace cubespring {

/// The time-varying part of a body: a plain value that can be copied, compared, hashed and saved.
struct State {
  Eigen::Matrix3Xd positions;   ///< (3 x num_nodes) [m]
  Eigen::Matrix3Xd velocities;  ///< (3 x num_nodes) [m/s]
  double time = 0.0;            ///< [s]

  /// Same size and the same bits in every array (bit-identical replay).
  bool operator==(const State& other) const;
  bool operator!=(const State& other) const { return !(*this == other); }
};

/// The body at rest: positions at rest, velocities zero, time zero.
State rest_state(const Model& model);

/// Displacements from rest (3 x num_nodes) [m].
Eigen::Matrix3Xd displacements(const Model& model, const State& state);

/// A 64-bit FNV-1a hash of every byte of the state, to compare runs.
std::uint64_t state_hash(const State& state);

/// Saves the state bit for bit (binary, little-endian doubles as in memory) and loads it back.
/// load_state checks the header and that the node count matches the model; it refuses a file of
/// the first format (saved before nodes were numbered along a body's long axis) for a body that is
/// not numbered z-major (Model::major_axis), whose nodes that file holds in another order.
Status save_state(const State& state, const std::string& path);
Result<State> load_state(const Model& model, const std::string& path);

}  // namespace cubespring
