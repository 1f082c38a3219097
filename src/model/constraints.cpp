// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "cubespring/constraints.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace cubespring {
namespace {

// The nodes whose rest position lies in [lower, upper], or an error naming the box if none does.
Result<std::vector<int>> nodes_in(const Model& model, const Eigen::Vector3d& lower, const Eigen::Vector3d& upper) {
  std::vector<int> nodes = model.nodes_in_box(lower, upper);
  if (nodes.empty()) {
    std::ostringstream message;
    message << "no node lies in the box (" << lower.transpose() << ") - (" << upper.transpose() << ") m";
    return Status::error(message.str());
  }
  return nodes;
}

}  // namespace

Constraints::Constraints(const Model& model) : driven_(model.num_nodes(), 0), target_(model.rest_positions) {}

Status Constraints::check_index(int node) const {
  if (node < 0 || node >= num_nodes()) {
    return Status::error("node " + std::to_string(node) + " is out of range: the body has " +
                         std::to_string(num_nodes()) + " nodes");
  }
  return {};
}

Status Constraints::fix_nodes(const Model& model, const std::vector<int>& nodes) {
  for (int node : nodes) {
    if (Status status = check_index(node); !status) return status;
  }
  for (int node : nodes) {
    driven_[node] = kAllAxes;
    target_.col(node) = model.rest_positions.col(node);
  }
  return {};
}

Status Constraints::fix_box(const Model& model, const Eigen::Vector3d& lower, const Eigen::Vector3d& upper) {
  Result<std::vector<int>> found = nodes_in(model, lower, upper);
  if (!found) return found.status();
  return fix_nodes(model, found.value());
}

Status Constraints::prescribe_position(int node, const Eigen::Vector3d& position) {
  if (Status status = check_index(node); !status) return status;
  if (!position.allFinite()) return Status::error("node " + std::to_string(node) + ": target position is not finite");
  driven_[node] = kAllAxes;
  target_.col(node) = position;
  return {};
}

Status Constraints::prescribe_axis_position(int node, int axis, double coordinate) {
  if (Status status = check_index(node); !status) return status;
  if (axis < 0 || axis > 2) return Status::error("axis " + std::to_string(axis) + " is out of range: 0, 1 or 2");
  if (!std::isfinite(coordinate)) {
    return Status::error("node " + std::to_string(node) + ": target coordinate is not finite");
  }
  driven_[node] |= static_cast<std::uint8_t>(1u << axis);
  target_(axis, node) = coordinate;
  return {};
}

Status Constraints::prescribe_box_axis_displacement(const Model& model, const Eigen::Vector3d& lower,
                                                    const Eigen::Vector3d& upper, int axis, double displacement) {
  if (axis < 0 || axis > 2) return Status::error("axis " + std::to_string(axis) + " is out of range: 0, 1 or 2");
  if (!std::isfinite(displacement)) {
    return Status::error("displacement " + std::to_string(displacement) + " m is not finite");
  }
  Result<std::vector<int>> found = nodes_in(model, lower, upper);
  if (!found) return found.status();
  const std::vector<int>& nodes = found.value();
  for (int node : nodes) {
    if (Status status = prescribe_axis_position(node, axis, model.rest_positions(axis, node) + displacement); !status) {
      return status;
    }
  }
  return {};
}

Status Constraints::prescribe_displacement(const Model& model, int node, const Eigen::Vector3d& displacement) {
  if (Status status = check_index(node); !status) return status;
  return prescribe_position(node, model.rest_positions.col(node) + displacement);
}

Status Constraints::prescribe_box_displacement(const Model& model, const Eigen::Vector3d& lower,
                                               const Eigen::Vector3d& upper, const Eigen::Vector3d& displacement) {
  Result<std::vector<int>> found = nodes_in(model, lower, upper);
  if (!found) return found.status();
  const std::vector<int>& nodes = found.value();
  for (int node : nodes) {
    if (Status status = prescribe_displacement(model, node, displacement); !status) return status;
  }
  return {};
}

Status Constraints::release(int node) {
  if (Status status = check_index(node); !status) return status;
  driven_[node] = 0;
  return {};
}

Result<Constraints> Constraints::renumbered(const std::vector<int>& new_node, int num_new_nodes) const {
  if (new_node.size() != driven_.size()) {
    return Status::error("the node map has " + std::to_string(new_node.size()) + " entries for " +
                         std::to_string(driven_.size()) + " constrained nodes");
  }
  Constraints carried;
  carried.driven_.assign(static_cast<std::size_t>(std::max(num_new_nodes, 0)), 0);
  carried.target_.setZero(3, std::max(num_new_nodes, 0));
  for (std::size_t n = 0; n < new_node.size(); ++n) {
    const int to = new_node[n];
    if (to == -1) continue;
    if (to < 0 || to >= num_new_nodes) {
      return Status::error("the node map sends node " + std::to_string(n) + " to " + std::to_string(to) +
                           ", outside the new body's " + std::to_string(num_new_nodes) + " nodes");
    }
    carried.driven_[static_cast<std::size_t>(to)] = driven_[n];
    carried.target_.col(to) = target_.col(static_cast<Eigen::Index>(n));
  }
  return carried;
}

Result<Constraints> Constraints::gathered(const std::vector<int>& source_node) const {
  Constraints carried;
  carried.driven_.assign(source_node.size(), 0);
  carried.target_.setZero(3, static_cast<Eigen::Index>(source_node.size()));
  for (std::size_t n = 0; n < source_node.size(); ++n) {
    const int from = source_node[n];
    if (from < 0 || from >= num_nodes()) {
      return Status::error("node " + std::to_string(n) + " comes from node " + std::to_string(from) + ", outside the " +
                           std::to_string(num_nodes()) + " constrained nodes");
    }
    carried.driven_[n] = driven_[static_cast<std::size_t>(from)];
    carried.target_.col(static_cast<Eigen::Index>(n)) = target_.col(from);
  }
  return carried;
}

int Constraints::num_driven() const {
  return static_cast<int>(driven_.size() - std::count(driven_.begin(), driven_.end(), std::uint8_t{0}));
}

}  // namespace cubespring
