// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "cubespring/state.h"

#include <cstring>
#include <fstream>

namespace cubespring {
namespace {

constexpr char kMagic[8] = {'C', 'U', 'B', 'E', 'S', 'T', 'A', '2'};
// Files of the first format came from builds that numbered every body's nodes z-major: they hold
// the nodes in this build's order only for a body that is still z-major (Model::major_axis).
constexpr char kZMajorMagic[8] = {'C', 'U', 'B', 'E', 'S', 'T', 'A', '1'};

bool same_bits(const Eigen::Matrix3Xd& a, const Eigen::Matrix3Xd& b) {
  // an empty matrix's data() is null, which memcmp may not be given even for 0 bytes
  return a.cols() == b.cols() &&
         (a.size() == 0 || std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0);
}

void hash_bytes(std::uint64_t& hash, const void* data, std::size_t size) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i) {
    hash ^= bytes[i];
    hash *= 1099511628211ULL;
  }
}

}  // namespace

bool State::operator==(const State& other) const {
  return std::memcmp(&time, &other.time, sizeof(double)) == 0 && same_bits(positions, other.positions) &&
         same_bits(velocities, other.velocities);
}

State rest_state(const Model& model) {
  State state;
  state.positions = model.rest_positions;
  state.velocities = Eigen::Matrix3Xd::Zero(3, model.num_nodes());
  return state;
}

Eigen::Matrix3Xd displacements(const Model& model, const State& state) {
  return state.positions - model.rest_positions;
}

std::uint64_t state_hash(const State& state) {
  std::uint64_t hash = 14695981039346656037ULL;
  hash_bytes(hash, &state.time, sizeof(double));
  hash_bytes(hash, state.positions.data(), sizeof(double) * state.positions.size());
  hash_bytes(hash, state.velocities.data(), sizeof(double) * state.velocities.size());
  return hash;
}

Status save_state(const State& state, const std::string& path) {
  std::ofstream out(path, std::ios::binary);
  if (!out) return Status::error(path + ": cannot open the file for writing");
  const std::int64_t num_nodes = state.positions.cols();
  out.write(kMagic, sizeof(kMagic));
  out.write(reinterpret_cast<const char*>(&num_nodes), sizeof(num_nodes));
  out.write(reinterpret_cast<const char*>(&state.time), sizeof(double));
  out.write(reinterpret_cast<const char*>(state.positions.data()), sizeof(double) * state.positions.size());
  out.write(reinterpret_cast<const char*>(state.velocities.data()), sizeof(double) * state.velocities.size());
  if (!out) return Status::error(path + ": writing the state failed");
  return {};
}

Result<State> load_state(const Model& model, const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Status::error(path + ": cannot open the file for reading");
  char magic[sizeof(kMagic)] = {};
  std::int64_t num_nodes = 0;
  in.read(magic, sizeof(magic));
  in.read(reinterpret_cast<char*>(&num_nodes), sizeof(num_nodes));
  const bool z_major_file = in && std::memcmp(magic, kZMajorMagic, sizeof(kZMajorMagic)) == 0;
  if (!in || (std::memcmp(magic, kMagic, sizeof(kMagic)) != 0 && !z_major_file)) {
    return Status::error(path + ": not a cubespring state file (bad header)");
  }
  if (z_major_file && model.major_axis != 2) {
    return Status::error(path + ": the state was saved by an earlier version, which numbered the nodes z-major; " +
                         "this body's nodes are numbered along " + "xyz"[model.major_axis] +
                         " now (Model::major_axis), so the file's nodes would land on the wrong ones");
  }
  if (num_nodes != model.num_nodes()) {
    return Status::error(path + ": the state has " + std::to_string(num_nodes) + " nodes, the model has " +
                         std::to_string(model.num_nodes()));
  }
  State state;
  state.positions.resize(3, num_nodes);
  state.velocities.resize(3, num_nodes);
  in.read(reinterpret_cast<char*>(&state.time), sizeof(double));
  in.read(reinterpret_cast<char*>(state.positions.data()), sizeof(double) * state.positions.size());
  in.read(reinterpret_cast<char*>(state.velocities.data()), sizeof(double) * state.velocities.size());
  if (!in) return Status::error(path + ": the file ends before the state does (truncated)");
  return state;
}

}  // namespace cubespring
