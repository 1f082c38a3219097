// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// cubespring bench-layout: the same bodies stepped on the spring lists and on the grid passes,
// by how much of their bounding box they fill, for the fill above which build_model() takes the
// grid (kDefaultMinGridFill, docs/data-layout.md).
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench_support.h"
#include "commands.h"
#include "cubespring/model.h"
#include "cubespring/stable_time_step.h"
#include "json_output.h"
#include "number_checks.h"
#include "step_timing.h"

namespace cubespring::app {
namespace {

struct LayoutOptions {
  int cells_across = 40;
  std::string fills = "0.25,0.30,0.35,0.40,0.45,0.52";
  double min_seconds = 0.3;
  bool json = false;
};

struct LayoutRow {
  double fill = 0;  // of the cells' bounding box
  int cells = 0;
  CellModel model = CellModel::kBaudet2007;
  bool inclusion = false;
  double lists[2] = {0, 0}, grid[2] = {0, 0};  // [s] per step, 1 and 2 threads
  bool default_grid = false;                   // what the default min_grid_fill picks
};

// A solid ball fills about pi / 6 of its box: the most a ball can.
const double kSolidBallFill = std::acos(-1.0) / 6.0;

std::vector<double> parse_fills(const std::string& text) {
  return parse_number_list(
      text, "--fills", [](double fill) { return fill > 0.0 && fill <= kSolidBallFill; },
      "a fraction in (0, 0.52] (a solid ball fills 0.52 of its box)");
}

double box_fill(const Model& model) {
  Eigen::Vector3i lower = model.cell_grid_index[0], upper = lower;
  for (const Eigen::Vector3i& cell : model.cell_grid_index) {
    lower = lower.cwiseMin(cell);
    upper = upper.cwiseMax(cell);
  }
  return model.num_cells() / (upper - lower + Eigen::Vector3i::Ones()).cast<double>().prod();
}

// A hollow ball of about `fill` of its box, in one material or with a stiff third (E x 10: the
// grid then streams per-point coefficients).
LatticeDesc hollow_ball(int across, double fill, bool inclusion) {
  const double hollow = std::cbrt(1.0 - fill / kSolidBallFill);
  LatticeDesc desc = ball_lattice(across, 0.01, Material{}, hollow);
  if (inclusion) {
    Material stiff;
    stiff.young_modulus *= 10.0;
    desc.materials.push_back(stiff);
    for (const Eigen::Vector3i& cell : desc.cells) desc.cell_material.push_back(3 * cell.x() < across ? 1 : 0);
  }
  return desc;
}

LayoutRow bench_layouts(LatticeDesc desc, CellModel cell_model, bool inclusion, double min_seconds) {
  desc.model = cell_model;
  Result<Model> built = build_model(desc);
  if (!built) throw std::runtime_error(built.message());
  LayoutRow row;
  row.fill = box_fill(built.value());
  row.cells = built.value().num_cells();
  row.model = cell_model;
  row.inclusion = inclusion;
  row.default_grid = uses_grid_passes(built.value());
  const Model& model = built.value();  // stepped on either layout, as the fill asked for says
  constexpr double kSpringLists = std::numeric_limits<double>::quiet_NaN();  // a fill no body reaches
  constexpr double kGridAlways = 0.0;
  if (!uses_grid_passes(model, ForceOptions{true, 1, kGridAlways})) {
    throw std::runtime_error("the grid passes cannot take the ball");
  }

  Constraints clamp(model);
  const double x_min = model.rest_positions.row(0).minCoeff();
  (void)clamp.fix_box(model, {-1e9, -1e9, -1e9}, {x_min + 0.02, 1e9, 1e9});
  Loads loads;
  loads.gravity = {0, 0, -9.81};
  const State start = rest_state(model);
  const double dt = 0.5 * max_stable_time_step(model);
  ExplicitStepper lists1(model, clamp, loads, start, Integrator::kSymplecticEuler, 1, dt, kSpringLists);
  ExplicitStepper grid1(model, clamp, loads, start, Integrator::kSymplecticEuler, 1, dt, kGridAlways);
  ExplicitStepper lists2(model, clamp, loads, start, Integrator::kSymplecticEuler, 2, dt, kSpringLists);
  ExplicitStepper grid2(model, clamp, loads, start, Integrator::kSymplecticEuler, 2, dt, kGridAlways);
  const std::vector<double> times =
      interleaved_best_times(min_seconds, {std::ref(lists1), std::ref(grid1), std::ref(lists2), std::ref(grid2)});
  row.lists[0] = times[0];
  row.grid[0] = times[1];
  row.lists[1] = times[2];
  row.grid[1] = times[3];
  return row;
}

const char* materials_name(bool inclusion) { return inclusion ? "inclusion" : "one"; }

int run_bench_layout(const LayoutOptions& o) {
  std::vector<LayoutRow> rows;
  try {
    if (o.cells_across < 4 || o.cells_across > 256) {
      throw std::runtime_error("--cells-across: " + std::to_string(o.cells_across) + " is outside 4..256");
    }
    for (const double fill : parse_fills(o.fills)) {
      for (const CellModel cell_model : {CellModel::kBaudet2007, CellModel::kExactBending}) {
        for (const bool inclusion : {false, true}) {
          rows.push_back(
              bench_layouts(hollow_ball(o.cells_across, fill, inclusion), cell_model, inclusion, o.min_seconds));
        }
      }
      if (!o.json) std::fprintf(stderr, "benched fill %.2f\n", fill);
    }
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  }
  if (o.json) {
    nlohmann::json out = nlohmann::json::array();
    for (const LayoutRow& r : rows) {
      out.push_back({{"fill", r.fill},
                     {"cells", r.cells},
                     {"model", cell_model_name(r.model)},
                     {"materials", materials_name(r.inclusion)},
                     {"lists_ms", {{"1", 1e3 * r.lists[0]}, {"2", 1e3 * r.lists[1]}}},
                     {"grid_ms", {{"1", 1e3 * r.grid[0]}, {"2", 1e3 * r.grid[1]}}},
                     {"default_layout", r.default_grid ? "grid" : "lists"}});
    }
    std::cout << json_text(out) << "\n";
    return 0;
  }
  std::printf(
      "Hollow balls of %d cells across (1 cm cells, E = 1 MPa, nu = 0.3, clamped, gravity): symplectic Euler\n"
      "step in ms on the spring lists and on the grid passes (best of %d interleaved batches of >= %.2f s)\n",
      o.cells_across, kBatches, o.min_seconds / kBatches);
  std::printf("%6s %7s %-14s %-9s | %9s %9s %10s | %9s %9s %10s | %s\n", "fill", "cells", "model", "materials",
              "lists 1t", "grid 1t", "lists/grid", "lists 2t", "grid 2t", "lists/grid", "default");
  for (const LayoutRow& r : rows) {
    std::printf("%6.3f %7d %-14s %-9s | %9.4f %9.4f %10.2f | %9.4f %9.4f %10.2f | %s\n", r.fill, r.cells,
                cell_model_name(r.model), materials_name(r.inclusion), 1e3 * r.lists[0], 1e3 * r.grid[0],
                r.lists[0] / r.grid[0], 1e3 * r.lists[1], 1e3 * r.grid[1], r.lists[1] / r.grid[1],
                r.default_grid ? "grid" : "lists");
  }
  std::printf(
      "fill: cells over the cells of their bounding box; lists/grid > 1: the grid is faster; default: the\n"
      "layout the default ForceOptions::min_grid_fill picks (the grid from a fill of %.2f,\n"
      "kDefaultMinGridFill); inclusion: the ball's lowest third in x 10 times stiffer.\n",
      kDefaultMinGridFill);
  return 0;
}

}  // namespace

Command add_bench_layout_command(CLI::App& app) {
  auto options = std::make_shared<LayoutOptions>();
  CLI::App* cmd = app.add_subcommand("bench-layout", "Time steps on the spring lists and on the grid passes by fill");
  cmd->add_option("--cells-across", options->cells_across, "cells across the hollow balls")->capture_default_str();
  cmd->add_option("--fills", options->fills, "fractions of their box the balls fill, separated by ','")
      ->capture_default_str();
  cmd->add_option("--min-seconds", options->min_seconds, "time each measurement at least this long [s]")
      ->check(finite_positive_number())
      ->capture_default_str();
  cmd->add_flag("--json", options->json, "print a JSON array instead of the table");
  return [options] { return run_bench_layout(*options); };
}

}  // namespace cubespring::app
