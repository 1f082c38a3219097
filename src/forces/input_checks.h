// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Checks that the arrays a caller hands the engine fit the body, before anything reads them: a
// state, a load or constraints of another body would read and write past the arrays' ends.
#pragma once

#include <string>

#include <Eigen/Core>

#include "cubespring/constraints.h"
#include "cubespring/forces.h"
#include "cubespring/model.h"
#include "cubespring/state.h"

namespace cubespring {

/// "" when `values` holds one column per node of the model (or, with may_be_empty, none);
/// else what is wrong, naming `name` and both counts.
std::string node_columns_error(const Model& model, const Eigen::Matrix3Xd& values, const char* name,
                               bool may_be_empty = false);

/// Throws std::invalid_argument with node_columns_error()'s message unless it is "" (for the
/// functions that return their result, not a Status).
void require_node_columns(const Model& model, const Eigen::Matrix3Xd& values, const char* name,
                          bool may_be_empty = false);

/// "" unless the model's cells take the neo-Hookean law without one set of its constants per
/// material (Model::cell_law set after build_model(), which makes them); else what is wrong.
std::string law_constants_error(const Model& model);
/// Throws std::invalid_argument with law_constants_error()'s message, prefixed by `caller`.
void require_law_constants(const Model& model, const char* caller);

/// "" when the state and the loads fit the model and the gravity is finite (and the model's
/// law has its constants); else what is wrong.
std::string state_and_loads_error(const Model& model, const State& state, const Loads& loads);

/// "" when loads.gravity is finite; else what it is.
std::string gravity_error(const Loads& loads);

/// "" when the constraints are empty (Constraints()) or were made for a body of this many
/// nodes; else what is wrong.
std::string constraints_error(const Model& model, const Constraints& constraints);

}  // namespace cubespring
