// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "forces/force_engine.h"

#include <cmath>

namespace cubespring {
namespace {

bool same_fill(double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); }

}  // namespace

const ForceEngine& engine_blocks(const Model& model, ForceWorkspace& ws) {
  if (ws.engine && ws.engine->made_for(model)) return *ws.engine;
  auto engine = std::make_shared<ForceEngine>();
  engine->model_revision = model.revision;
  engine->num_nodes = model.num_nodes();
  engine->num_springs = model.num_springs();
  engine->num_cells = model.num_cells();
  engine->blocks = split_force_blocks(model);
  ws.engine = engine;
  return *engine;
}

const ForceEngine& engine_with_grid(const Model& model, double min_grid_fill, ForceWorkspace& ws) {
  const ForceEngine& current = engine_blocks(model, ws);
  if (current.grid_decided && same_fill(current.min_grid_fill, min_grid_fill)) return current;
  auto engine = std::make_shared<ForceEngine>(current);
  engine->grid_decided = true;
  engine->min_grid_fill = min_grid_fill;
  engine->grid = build_grid_layout(model, min_grid_fill);
  ws.engine = engine;
  return *engine;
}

bool uses_grid_passes(const Model& model, const ForceOptions& options) {
  return build_grid_layout(model, options.min_grid_fill) != nullptr;
}

}  // namespace cubespring
