// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "forces/input_checks.h"

#include <sstream>
#include <stdexcept>
#include <string>

namespace cubespring {

std::string node_columns_error(const Model& model, const Eigen::Matrix3Xd& values, const char* name,
                               bool may_be_empty) {
  if (values.cols() == model.num_nodes() || (may_be_empty && values.size() == 0)) return {};
  std::ostringstream message;
  message << name << " has " << values.cols() << " columns; the body has " << model.num_nodes() << " nodes"
          << (may_be_empty ? " (or leave it empty)" : "");
  return message.str();
}

void require_node_columns(const Model& model, const Eigen::Matrix3Xd& values, const char* name, bool may_be_empty) {
  const std::string error = node_columns_error(model, values, name, may_be_empty);
  if (!error.empty()) throw std::invalid_argument(error);
}

std::string law_constants_error(const Model& model) {
  if (model.cell_law != CellLaw::kNeoHookean || model.law_constants.size() == model.materials.size()) return "";
  return "the model's cell law is neo-hookean but it has " + std::to_string(model.law_constants.size()) +
         " sets of the law's constants for " + std::to_string(model.materials.size()) +
         " materials: set LatticeDesc::law and build the model again";
}

void require_law_constants(const Model& model, const char* caller) {
  const std::string error = law_constants_error(model);
  if (!error.empty()) throw std::invalid_argument(std::string(caller) + ": " + error);
}

std::string state_and_loads_error(const Model& model, const State& state, const Loads& loads) {
  if (std::string error = law_constants_error(model); !error.empty()) return error;
  if (model.inertial_mass.size() != 0 && model.inertial_mass.size() != model.num_nodes()) {
    return "model.inertial_mass has " + std::to_string(model.inertial_mass.size()) + " entries; the body has " +
           std::to_string(model.num_nodes()) + " nodes (or leave it empty)";
  }
  for (const std::string& error : {node_columns_error(model, state.positions, "state.positions"),
                                   node_columns_error(model, state.velocities, "state.velocities"),
                                   node_columns_error(model, loads.nodal_forces, "loads.nodal_forces", true)}) {
    if (!error.empty()) return error;
  }
  return gravity_error(loads);
}

std::string gravity_error(const Loads& loads) {
  if (loads.gravity.allFinite()) return {};
  std::ostringstream message;
  message << "loads.gravity = (" << loads.gravity.transpose() << ") m/s^2 is not finite";
  return message.str();
}

Status check_state_and_loads(const Model& model, const State& state, const Loads& loads) {
  const std::string error = state_and_loads_error(model, state, loads);
  return error.empty() ? Status() : Status::error(error);
}

std::string constraints_error(const Model& model, const Constraints& constraints) {
  if (constraints.num_nodes() == 0 || constraints.num_nodes() == model.num_nodes()) return {};
  return "the constraints are for a body of " + std::to_string(constraints.num_nodes()) + " nodes; this one has " +
         std::to_string(model.num_nodes());
}

}  // namespace cubespring
