// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// cubespring bench: time per step of each integrator on blocks and a voxelized sphere, beside a
// bare spring-force pass over the same springs (the floor a full step is compared with).
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <functional>
#include <iostream>
#include <limits>
#include <memory>
#include <sstream>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "arguments.h"
#include "bench_support.h"
#include "commands.h"
#include "cubespring/constraints.h"
#include "cubespring/integrator.h"
#include "cubespring/stable_time_step.h"
#include "grid_spring_floor.h"
#include "json_output.h"
#include "number_checks.h"
#include "step_timing.h"

namespace cubespring::app {
namespace {

struct BenchOptions {
  std::string sizes = "16,4,4;32,8,8;64,16,16;32,32,32;64,64,64";
  int sphere_cells_across = 32;
  double min_seconds = 0.3;  // per measurement
  bool implicit = true;
  int implicit_max_cells = 40000;  // implicit steps are timed up to this many cells
  bool json = false;
  int busy = 0;  // threads spinning beside the bench: a loaded machine
};

// Threads that spin until destroyed: another program's load on the machine (--busy).
class BusyThreads {
 public:
  explicit BusyThreads(int count) {
    for (int i = 0; i < count; ++i) {
      threads_.emplace_back([this] {
        while (!stop_.load(std::memory_order_relaxed)) {
        }
      });
    }
  }
  ~BusyThreads() {
    stop_.store(true);
    for (std::thread& thread : threads_) thread.join();
  }
  BusyThreads(const BusyThreads&) = delete;
  BusyThreads& operator=(const BusyThreads&) = delete;

 private:
  std::atomic<bool> stop_{false};
  std::vector<std::thread> threads_;
};

// The floor: one pass of linear spring forces, f = k (l - l0) d / l, over the springs grouped by
// their first node (whose sum stays in a register), scattered to the second node.
void bare_spring_pass(const Model& model, const Eigen::Matrix3Xd& x, Eigen::Matrix3Xd& forces) {
  forces.setZero();
  for (int i = 0; i < model.num_nodes(); ++i) {
    const Eigen::Vector3d xi = x.col(i);
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (int s = model.node_first_spring[i]; s < model.node_first_spring[i + 1]; ++s) {
      const int j = model.spring_nodes[s][1];
      const Eigen::Vector3d d = x.col(j) - xi;
      const double length = d.norm();
      const Eigen::Vector3d f = (model.spring_stiffness[s] * (length - model.spring_rest_length[s]) / length) * d;
      sum += f;
      forces.col(j) -= f;
    }
    forces.col(i) += sum;
  }
}

struct Row {
  std::string name;
  int cells = 0, nodes = 0, springs = 0;
  double bare = 0, grid_bare = 0, symplectic1 = 0, symplectic2 = 0, verlet1 = 0, verlet2 = 0;
  double symplectic_adaptive = 0;                // 2 threads allowed, the step taking 1 while 1 is faster
  double implicit_step = 0, implicit_step2 = 0;  // 1 and 2 threads
  double two_bodies = 0;      // two copies of the body's 1-thread symplectic step at once, on 2 threads
  double exact_bending1 = 0;  // the exact-bending model's symplectic step, 1 thread
  // the same with the neo-Hookean law, on the passes build_model chose and on the spring lists
  double neo_hookean1 = 0, neo_hookean_lists1 = 0;
  bool neo_hookean_on_grid = false;
  int implicit_iterations = 0;
  // the implicit step with each preconditioner (the default, automatic, chooses one of them), 1 thread
  double jacobi_step = 0, multigrid_step = 0;
  int jacobi_iterations = 0, multigrid_iterations = 0;
  // the implicit step (automatic preconditioner, 1 thread) of exact-bending cells with the springs
  // law and with the neo-Hookean law (the scenes' default, whose cells' stiffness is projected)
  double exact_bending_implicit_step = 0, neo_hookean_implicit_step = 0;
};

// The positions of a box's nodes in the floor's order (x fastest, then y, then z), whatever
// order the model numbers them in (Model::major_axis).
Eigen::Matrix3Xd in_box_order(const Model& model, const Eigen::Vector3i& cells, const Eigen::Matrix3Xd& positions) {
  Eigen::Vector3i first = model.node_grid_index.front();
  for (const Eigen::Vector3i& index : model.node_grid_index) first = first.cwiseMin(index);
  Eigen::Matrix3Xd ordered(3, model.num_nodes());
  for (int n = 0; n < model.num_nodes(); ++n) {
    const Eigen::Vector3i i = model.node_grid_index[n] - first;
    ordered.col(i.x() + (cells.x() + 1) * (i.y() + (cells.y() + 1) * i.z())) = positions.col(n);
  }
  return ordered;
}

// `box`: the body's cell counts when it is a box (for the floor with implicit connectivity).
Row bench_body(const std::string& name, LatticeDesc desc, const BenchOptions& o, const Eigen::Vector3i* box = nullptr) {
  Result<Model> built = build_model(desc);
  if (!built) throw std::runtime_error(built.message());
  const Model& model = built.value();
  Row row;
  row.name = name;
  row.cells = model.num_cells();
  row.nodes = model.num_nodes();
  row.springs = model.num_springs();

  // clamped at its lowest x, under gravity, slightly disturbed so that every term works
  Constraints clamp(model);
  const double x_min = model.rest_positions.row(0).minCoeff();
  (void)clamp.fix_box(model, {-1e9, -1e9, -1e9}, {x_min + 1e-9, 1e9, 1e9});
  Loads loads;
  loads.gravity = {0, 0, -9.81};
  State start = rest_state(model);
  start.positions.array() += 1e-5 * Eigen::Matrix3Xd::Random(3, model.num_nodes()).array();

  // the same lattice with the exact-bending model, for the cost ratio of the two models
  desc.model = CellModel::kExactBending;
  Result<Model> exact = build_model(desc);
  if (!exact) throw std::runtime_error(exact.message());
  // and with the neo-Hookean law (the scenes' default), on its grid passes and on the lists
  desc.law = CellLaw::kNeoHookean;
  Result<Model> neo_hookean = build_model(desc);
  if (!neo_hookean) throw std::runtime_error(neo_hookean.message());
  row.neo_hookean_on_grid = uses_grid_passes(neo_hookean.value());
  constexpr double kSpringLists = std::numeric_limits<double>::quiet_NaN();  // a fill no body reaches

  Eigen::Matrix3Xd forces(3, model.num_nodes());
  // half the stable step, found once per model (it assembles the stiffness)
  const double dt = 0.5 * max_stable_time_step(model);
  const double exact_dt = 0.5 * max_stable_time_step(exact.value());
  const double neo_hookean_dt = 0.5 * max_stable_time_step(neo_hookean.value());
  ExplicitStepper symplectic1(model, clamp, loads, start, Integrator::kSymplecticEuler, 1, dt);
  ExplicitStepper symplectic2(model, clamp, loads, start, Integrator::kSymplecticEuler, 2, dt);
  ExplicitStepper symplectic_adaptive(model, clamp, loads, start, Integrator::kSymplecticEuler, 2, dt);
  symplectic_adaptive.adapting();
  ExplicitStepper verlet1(model, clamp, loads, start, Integrator::kVelocityVerlet, 1, dt);
  ExplicitStepper verlet2(model, clamp, loads, start, Integrator::kVelocityVerlet, 2, dt);
  ExplicitStepper exact1(exact.value(), clamp, loads, start, Integrator::kSymplecticEuler, 1, exact_dt);
  ExplicitStepper neo_hookean1(neo_hookean.value(), clamp, loads, start, Integrator::kSymplecticEuler, 1,
                               neo_hookean_dt);
  ExplicitStepper neo_hookean_lists1(neo_hookean.value(), clamp, loads, start, Integrator::kSymplecticEuler, 1,
                                     neo_hookean_dt, kSpringLists);
  ExplicitStepper first_body(model, clamp, loads, start, Integrator::kSymplecticEuler, 1, dt);
  ExplicitStepper second_body(model, clamp, loads, start, Integrator::kSymplecticEuler, 1, dt);
  const TwoAtOnce two_bodies(std::ref(first_body), std::ref(second_body));
  std::vector<std::function<void()>> columns{[&] { bare_spring_pass(model, start.positions, forces); },
                                             std::ref(symplectic1),
                                             std::ref(symplectic2),
                                             std::ref(verlet1),
                                             std::ref(exact1),
                                             std::ref(two_bodies),
                                             std::ref(verlet2),
                                             std::ref(neo_hookean1),
                                             std::ref(neo_hookean_lists1),
                                             std::ref(symplectic_adaptive)};
  std::unique_ptr<GridSpringFloor> floor;
  if (box != nullptr) {
    const Result<CellCalibration> springs = calibrate_cell(CellModel::kBaudet2007, desc.materials[0], desc.cell_size);
    if (!springs) throw std::runtime_error(springs.message());
    floor = std::make_unique<GridSpringFloor>(*box, desc.cell_size.x(), in_box_order(model, *box, start.positions),
                                              springs.value().edge_stiffness.x(), springs.value().diagonal_stiffness);
    columns.push_back(std::ref(*floor));
  }
  const std::vector<double> times = interleaved_best_times(o.min_seconds, columns);
  row.bare = times[0];
  row.symplectic1 = times[1];
  row.symplectic2 = times[2];
  row.verlet1 = times[3];
  row.exact_bending1 = times[4];
  row.two_bodies = times[5];
  row.verlet2 = times[6];
  row.neo_hookean1 = times[7];
  row.neo_hookean_lists1 = times[8];
  row.symplectic_adaptive = times[9];
  if (floor) {
    if (floor->springs() != model.num_springs() || !std::isfinite(floor->checksum())) {
      throw std::runtime_error("the grid floor of " + name + " visited " + std::to_string(floor->springs()) +
                               " springs, the model has " + std::to_string(model.num_springs()));
    }
    row.grid_bare = times[10];
  }

  if (o.implicit && model.num_cells() <= o.implicit_max_cells) {
    // steps from the same start on 1 and 2 threads, interleaved (each stepper takes as many steps
    // as its batches need: CG it is the 1-thread stepper's)
    StepSettings settings;
    settings.integrator = Integrator::kImplicitEuler;
    settings.time_step = 1e-3;
    settings.solver_tolerance = 1e-6;
    State state1 = start, state2 = start, state_jacobi = start, state_multigrid = start;
    State state_exact = start, state_neo_hookean = start;
    Stepper stepper1(model), stepper2(model), stepper_jacobi(model), stepper_multigrid(model);
    Stepper stepper_exact(exact.value()), stepper_neo_hookean(neo_hookean.value());
    StepSettings settings2 = settings;
    settings2.threads = 2;
    settings2.adapt_threads = false;  // the column measures 2 threads
    StepSettings settings_jacobi = settings;
    settings_jacobi.preconditioner = SolverPreconditioner::kJacobi;
    StepSettings settings_multigrid = settings;
    settings_multigrid.preconditioner = SolverPreconditioner::kMultigrid;
    long iterations = 0, steps = 0, iterations_jacobi = 0, steps_jacobi = 0, iterations_multigrid = 0,
         steps_multigrid = 0;
    const std::vector<double> implicit_times = interleaved_best_times(
        o.min_seconds,
        {[&] {
           const StepReport report = stepper1.step(model, clamp, loads, settings, state1);
           iterations += report.solver_iterations;
           ++steps;
         },
         [&] { (void)stepper2.step(model, clamp, loads, settings2, state2); },
         [&] {
           const StepReport report = stepper_jacobi.step(model, clamp, loads, settings_jacobi, state_jacobi);
           iterations_jacobi += report.solver_iterations;
           ++steps_jacobi;
         },
         [&] {
           const StepReport report = stepper_multigrid.step(model, clamp, loads, settings_multigrid, state_multigrid);
           iterations_multigrid += report.solver_iterations;
           ++steps_multigrid;
         },
         [&] { (void)stepper_exact.step(exact.value(), clamp, loads, settings, state_exact); },
         [&] { (void)stepper_neo_hookean.step(neo_hookean.value(), clamp, loads, settings, state_neo_hookean); }});
    row.implicit_step = implicit_times[0];
    row.implicit_step2 = implicit_times[1];
    row.implicit_iterations = static_cast<int>(iterations / std::max(1L, steps));
    row.jacobi_step = implicit_times[2];
    row.jacobi_iterations = static_cast<int>(iterations_jacobi / std::max(1L, steps_jacobi));
    row.multigrid_step = implicit_times[3];
    row.multigrid_iterations = static_cast<int>(iterations_multigrid / std::max(1L, steps_multigrid));
    row.exact_bending_implicit_step = implicit_times[4];
    row.neo_hookean_implicit_step = implicit_times[5];
  }
  return row;
}

int run_bench(const BenchOptions& o) {
  Material material;  // E = 1 MPa, nu = 0.3, rho = 1000
  std::vector<Row> rows;
  const BusyThreads busy(o.busy);
  try {
    for (const Eigen::Vector3i& n : parse_size_list(o.sizes)) {
      std::ostringstream name;
      name << n.x() << "x" << n.y() << "x" << n.z();
      rows.push_back(bench_body(name.str(), box_lattice(n, Eigen::Vector3d::Constant(0.01), material), o, &n));
      if (!o.json) std::fprintf(stderr, "benched %s\n", name.str().c_str());
    }
    if (o.sphere_cells_across > 0) {
      rows.push_back(bench_body("sphere " + std::to_string(o.sphere_cells_across),
                                ball_lattice(o.sphere_cells_across, 0.01, material), o));
    }
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  }

  if (o.json) {
    nlohmann::json out = nlohmann::json::array();
    for (const Row& r : rows) {
      out.push_back(
          {{"body", r.name},
           {"cells", r.cells},
           {"nodes", r.nodes},
           {"springs", r.springs},
           {"bare_spring_pass_ms", 1e3 * r.bare},
           {"grid_bare_spring_pass_ms", r.grid_bare > 0 ? nlohmann::json(1e3 * r.grid_bare) : nlohmann::json()},
           {"symplectic_euler_ms", {{"1", 1e3 * r.symplectic1}, {"2", 1e3 * r.symplectic2}}},
           {"symplectic_euler_adaptive_threads_ms", {{"2", 1e3 * r.symplectic_adaptive}}},
           {"busy_threads", o.busy},
           {"two_bodies_at_once_ms", 1e3 * r.two_bodies},
           {"two_thread_ceiling", 2.0 * r.symplectic1 / r.two_bodies},
           {"velocity_verlet_ms", {{"1", 1e3 * r.verlet1}, {"2", 1e3 * r.verlet2}}},
           {"exact_bending_symplectic_euler_ms", {{"1", 1e3 * r.exact_bending1}}},
           {"neo_hookean_symplectic_euler_ms", {{"1", 1e3 * r.neo_hookean1}}},
           {"neo_hookean_on_grid", r.neo_hookean_on_grid},
           {"neo_hookean_spring_lists_symplectic_euler_ms", {{"1", 1e3 * r.neo_hookean_lists1}}},
           {"neo_hookean_over_exact_bending", r.neo_hookean1 / r.exact_bending1},
           {"implicit_euler_ms", r.implicit_step > 0 ? nlohmann::json(1e3 * r.implicit_step) : nlohmann::json()},
           {"implicit_euler_threads_ms",
            r.implicit_step > 0 ? nlohmann::json{{"1", 1e3 * r.implicit_step}, {"2", 1e3 * r.implicit_step2}}
                                : nlohmann::json()},
           {"implicit_cg_iterations", r.implicit_iterations},
           {"implicit_wall_per_simulated_second_s",
            r.implicit_step > 0 ? nlohmann::json(1e3 * r.implicit_step) : nlohmann::json()},
           {"implicit_preconditioner", solver_preconditioner_name(StepSettings{}.preconditioner)},
           {"implicit_jacobi_ms", r.jacobi_step > 0 ? nlohmann::json(1e3 * r.jacobi_step) : nlohmann::json()},
           {"implicit_jacobi_cg_iterations", r.jacobi_iterations},
           {"implicit_multigrid_ms", r.multigrid_step > 0 ? nlohmann::json(1e3 * r.multigrid_step) : nlohmann::json()},
           {"implicit_multigrid_cg_iterations", r.multigrid_iterations},
           {"exact_bending_implicit_euler_ms",
            r.exact_bending_implicit_step > 0 ? nlohmann::json(1e3 * r.exact_bending_implicit_step) : nlohmann::json()},
           {"neo_hookean_implicit_euler_ms",
            r.neo_hookean_implicit_step > 0 ? nlohmann::json(1e3 * r.neo_hookean_implicit_step) : nlohmann::json()}});
    }
    std::cout << json_text(out) << "\n";
    return 0;
  }
  std::printf(
      "E = 1 MPa, nu = 0.3, 1 cm cells, clamped, gravity; times per step in ms (best of %d interleaved batches of\n"
      ">= %.2f s each, the explicit columns together and the implicit ones together)\n",
      kBatches, o.min_seconds / kBatches);
  std::printf(
      "%-12s %8s %9s %9s | %9s %9s %9s %9s %7s %7s %9s %9s | %9s %9s %9s %9s %9s %7s | %9s %7s %9s | %9s %7s | %10s "
      "%5s %10s %10s %10s %5s %10s %5s %10s %10s\n",
      "body", "cells", "nodes", "springs", "bare", "grid bare", "symp 1t", "symp 2t", "2t gain", "ceiling", "full/bare",
      "full/grid", "Gspring/s", "grid G/s", "verlet 1t", "verlet 2t", "exact 1t", "exact/pap", "nh 1t", "nh/exact",
      "nh lists", "auto 2t", "auto/1t", "implicit", "CG it", "s/sim s", "impl 2t", "jacobi", "J it", "multigrid",
      "MG it", "exact impl", "nh impl");
  for (const Row& r : rows) {
    char grid_bare[16] = "-", over_grid[16] = "-", grid_rate[16] = "-";
    if (r.grid_bare > 0) {
      std::snprintf(grid_bare, sizeof grid_bare, "%.4f", 1e3 * r.grid_bare);
      std::snprintf(over_grid, sizeof over_grid, "%.2f", r.symplectic1 / r.grid_bare);
      std::snprintf(grid_rate, sizeof grid_rate, "%.3f", 1e-9 * r.springs / r.grid_bare);
    }
    std::printf(
        "%-12s %8d %9d %9d | %9.4f %9s %9.4f %9.4f %7.2f %7.2f %9.2f %9s | %9.3f %9s %9.4f %9.4f %9.4f %7.2f |"
        " %9.4f %7.2f %9.4f | %9.4f %7.2f |",
        r.name.c_str(), r.cells, r.nodes, r.springs, 1e3 * r.bare, grid_bare, 1e3 * r.symplectic1, 1e3 * r.symplectic2,
        r.symplectic1 / r.symplectic2, 2.0 * r.symplectic1 / r.two_bodies, r.symplectic1 / r.bare, over_grid,
        1e-9 * r.springs / r.bare, grid_rate, 1e3 * r.verlet1, 1e3 * r.verlet2, 1e3 * r.exact_bending1,
        r.exact_bending1 / r.symplectic1, 1e3 * r.neo_hookean1, r.neo_hookean1 / r.exact_bending1,
        1e3 * r.neo_hookean_lists1, 1e3 * r.symplectic_adaptive, r.symplectic_adaptive / r.symplectic1);
    if (r.implicit_step > 0) {
      std::printf(" %10.3f %5d %10.2f %10.3f %10.3f %5d %10.3f %5d %10.3f %10.3f\n", 1e3 * r.implicit_step,
                  r.implicit_iterations, r.implicit_step / 1e-3, 1e3 * r.implicit_step2, 1e3 * r.jacobi_step,
                  r.jacobi_iterations, 1e3 * r.multigrid_step, r.multigrid_iterations,
                  1e3 * r.exact_bending_implicit_step, 1e3 * r.neo_hookean_implicit_step);
    } else {
      std::printf(" %10s %5s %10s %10s %10s %5s %10s %5s %10s %10s\n", "-", "-", "-", "-", "-", "-", "-", "-", "-",
                  "-");
    }
  }
  std::printf(
      "bare: one linear spring-force pass over the spring lists; grid bare: the same with implicit lattice\n"
      "connectivity (boxes only: springs at fixed index offsets, plain loops), the issue's floor; symp: full\n"
      "symplectic Euler step (springs, correction, inversion check, damping, integration); 2t gain: symp 1t over\n"
      "symp 2t; ceiling: what two cores give two copies of the body stepped at once on one thread each (2 x\n"
      "symp 1t over their time): the gain a 2-thread split would have with no cost of its own (a split can beat\n"
      "it a little, as each half's arrays fit the caches better); full/bare, full/grid:\n"
      "1-thread step over each floor; Gspring/s, grid G/s: springs per second of each floor;\n"
      "exact 1t: the same step with the exact-bending model, exact/pap its cost over the paper's model;\n"
      "nh 1t: exact-bending cells with the neo-Hookean law (the scenes' default), nh/exact its cost over exact 1t;\n"
      "nh lists: the same on the spring lists (where the grid passes do not take the body, as nh 1t);\n"
      "implicit: dt = 1 ms, CG to 1e-6 (CG it: products with the matrix per step), 1 thread; s/sim s: wall\n"
      "seconds per simulated second; verlet 2t, impl 2t: the same steps on 2 threads. The implicit step's CG\n"
      "preconditioner is chosen by the step (automatic: Jacobi until two solves take over 80 iterations, then\n"
      "the multigrid); jacobi, J it and multigrid, MG it: the same step with each, 1 thread; exact impl, nh impl:\n"
      "the implicit step (automatic, 1 thread) of exact-bending cells with the springs and the neo-Hookean law.\n"
      "auto 2t: the symplectic step allowed 2 threads as users step (StepSettings::adapt_threads: it takes 1\n"
      "while 1 is measured faster), auto/1t its time over symp 1t; the other columns take the threads they\n"
      "name. With --busy N, N threads spin beside the bench throughout (a loaded machine).\n");
  if (o.busy > 0) std::printf("%d threads were spinning beside the bench.\n", o.busy);
  return 0;
}

}  // namespace

Command add_bench_command(CLI::App& app) {
  auto options = std::make_shared<BenchOptions>();
  CLI::App* cmd = app.add_subcommand("bench", "Time each integrator per step on blocks and a voxelized sphere");
  cmd->add_option("--sizes", options->sizes, "blocks as NX,NY,NZ separated by ';'")->capture_default_str();
  cmd->add_option("--sphere", options->sphere_cells_across, "cells across the voxelized sphere (0: none)")
      ->capture_default_str();
  cmd->add_option("--min-seconds", options->min_seconds,
                  "time each measurement at least this long [s], in 5 interleaved batches")
      ->check(finite_positive_number())
      ->capture_default_str();
  cmd->add_option("--implicit-max-cells", options->implicit_max_cells, "time implicit steps up to this many cells")
      ->capture_default_str();
  cmd->add_option("--busy", options->busy, "threads spinning beside the bench throughout (a loaded machine)")
      ->check(CLI::Range(0, 64))
      ->capture_default_str();
  cmd->add_flag("--json", options->json, "print a JSON array instead of the table");
  return [options] { return run_bench(*options); };
}

}  // namespace cubespring::app
