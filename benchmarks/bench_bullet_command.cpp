// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// cubespring bench-bullet: one clamped beam under gravity built three ways and run side by side
// (Bullet-plugin issue): as a cubespring body (explicit with its stable sub-steps, and implicit),
// as Bullet's classic btSoftBody on the same nodes and springs (position-based links, kLST = 1,
// at several iteration counts) and as Bullet's deformable FEM (btDeformableMultiBodyDynamicsWorld,
// corotated linear elasticity on 6 tetrahedra per cell). For each: wall time per simulated second,
// the tip deflection it settles to and that deflection's error against finite elements.
// Bullet's soft-body arrays (btAlignedObjectArray of btReducedVector and tetra scratches) set off
// GCC's may-be-uninitialized analysis inside Bullet's own inline code, wherever it is used.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

// Bullet's headers come through the imported target's include directory, which CMake passes as a
// system directory (-isystem): the project's warnings do not fire inside them.
#include <BulletSoftBody/btDeformableBodySolver.h>
#include <BulletSoftBody/btDeformableGravityForce.h>
#include <BulletSoftBody/btDeformableLinearElasticityForce.h>
#include <BulletSoftBody/btDeformableMultiBodyConstraintSolver.h>
#include <BulletSoftBody/btDeformableMultiBodyDynamicsWorld.h>
#include <BulletSoftBody/btSoftBody.h>
#include <BulletSoftBody/btSoftBodyHelpers.h>
#include <BulletSoftBody/btSoftBodyRigidBodyCollisionConfiguration.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>
#include <btBulletDynamicsCommon.h>
#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "arguments.h"
#include "bench_support.h"
#include "commands.h"
#include "cubespring/constraints.h"
#include "cubespring/integrator.h"
#include "cubespring/validation/experiments.h"
#include "json_output.h"

namespace cubespring::app {
namespace {

using Clock = std::chrono::steady_clock;

constexpr double kCellSize = 0.01;  // [m], the 1 cm cells
constexpr double kGravity = 9.81;   // [m/s^2], along -z
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Finite-element references (README, "Against finite elements (CalculiX)"): linear C3D20R tip
// deflections of the 0.16 x 0.04 x 0.04 m beam at E = 1 MPa, nu = 0.3, rho = 1000 kg/m^3.
constexpr double kFeTip16x4x4AtHalfCell = -6.2759e-3;     // [m] 32x8x8 elements (h/2 of the 16x4x4 lattice)
constexpr double kFeTip16x4x4AtQuarterCell = -6.2820e-3;  // [m] 64x16x16 elements (h/4), converged to 0.1%

struct BenchBulletOptions {
  std::string sizes = "16,4,4;32,8,8";
  double seconds = 3.0;                   // simulated per case [s]
  double dt = 1e-3;                       // frame [s]
  double damping = 10.0;                  // mass-proportional (Rayleigh alpha) damping for every engine [1/s]
  std::vector<int> iterations{1, 8, 32};  // btSoftBody position iterations
  std::vector<std::string> models{"baudet2007", "exact-bending"};
  std::vector<int> threads{1, 2};  // force-pass threads of the explicit cubespring rows
  double drift_window = 0.5;       // the tip's change over the last this many seconds shows settling [s]
  double max_case_seconds = 60.0;  // wall-time cap per case [s]
  bool json = false;
};

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

btScalar bt(double value) { return static_cast<btScalar>(value); }
btVector3 bt(const Eigen::Vector3d& v) { return btVector3(bt(v.x()), bt(v.y()), bt(v.z())); }

std::string size_name(const Eigen::Vector3i& n) {
  std::ostringstream name;
  name << n.x() << "x" << n.y() << "x" << n.z();
  return name.str();
}

// The FE tip deflection [m] for a beam of 4k x k x k cells of 1 cm (NaN for other shapes) and how
// it was obtained. Linear elasticity under self-weight: a beam scaled by s sags s^2 as much.
std::pair<double, std::string> fe_reference(const Eigen::Vector3i& n) {
  const int k = n.y();
  if (n.z() != k || n.x() != 4 * k) return {kNaN, "no FE reference for this shape"};
  if (k == 4) return {kFeTip16x4x4AtHalfCell, "CalculiX C3D20R, 32x8x8 elements (h/2), README"};
  const double scale = k / 4.0;
  std::ostringstream how;
  how << "CalculiX C3D20R on the 0.16 m beam at 64x16x16 elements (README, -6.2820 mm) x (" << k
      << "/4)^2 (linear elasticity under self-weight scales as length^2)";
  return {scale * scale * kFeTip16x4x4AtQuarterCell, how.str()};
}

struct Row {
  std::string size;
  std::string engine;
  std::string setting;
  double wall_per_sim = kNaN;  // [s] wall per simulated second
  double cpu_per_sim = kNaN;   // [s] process CPU time per simulated second
  double tip = kNaN;           // [m] mean z displacement of the free end's nodes at the end
  double drift = kNaN;         // [m] tip at the end minus tip drift_window earlier
  double simulated = 0.0;      // [s] simulated
  double reference = kNaN;     // [m] FE tip
  double base_wall = kNaN;     // [s] the size's cubespring explicit (first model) wall per sim s
  double static_tip = kNaN;    // [m] cubespring rows: the same lattice's static equilibrium (Newton)
  int threads = 1;             // cubespring rows: force-pass threads (Bullet runs on one)
  std::string status = "ok";   // ok | diverged ... | capped ...
  bool diverged = false;
  bool capped = false;
  double error() const { return tip / reference - 1.0; }
  /// Ran to the end and its tip moved by under 0.1% over the last drift_window.
  bool settled() const { return !diverged && !capped && std::abs(drift) < 1e-3 * std::abs(tip); }
};

// Steps frames of dt until seconds have been simulated, the case diverges or the wall-time cap is
// reached, and fills the row's time, tip, drift and status. step_frame advances one frame and
// returns "" or what went wrong; tip gives the current tip deflection [m].
void run_frames(const BenchBulletOptions& o, double length, const std::function<std::string()>& step_frame,
                const std::function<double()>& tip, Row& row) {
  const long frames = std::lround(o.seconds / o.dt);
  const long drift_frame = frames - std::lround(o.drift_window / o.dt);
  double earlier = kNaN;
  long done = 0;
  double wall = 0.0;
  const auto start = Clock::now();
  const std::clock_t cpu_start = std::clock();
  for (long f = 1; f <= frames; ++f) {
    const std::string error = step_frame();
    const double t = tip();
    wall = seconds_since(start);
    done = f;
    if (!error.empty() || !std::isfinite(t) || std::abs(t) > length) {
      std::ostringstream status;
      status << "diverged at t = " << static_cast<double>(f) * o.dt << " s: "
             << (error.empty() ? "tip " + std::to_string(t) + " m (beyond the beam's length or not finite)" : error);
      row.status = status.str();
      row.diverged = true;
      break;
    }
    row.tip = t;
    if (f == drift_frame) earlier = t;
    if (wall > o.max_case_seconds && f < frames) {
      std::ostringstream status;
      status << "capped at t = " << static_cast<double>(f) * o.dt << " s (" << std::fixed << std::setprecision(1)
             << wall << " s wall): time extrapolated, tip not settled";
      row.status = status.str();
      row.capped = true;
      break;
    }
  }
  row.simulated = static_cast<double>(done) * o.dt;
  row.wall_per_sim = row.simulated > 0 ? wall / row.simulated : kNaN;
  const double cpu = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  row.cpu_per_sim = row.simulated > 0 ? cpu / row.simulated : kNaN;
  if (!row.diverged && !row.capped && std::isfinite(earlier)) row.drift = row.tip - earlier;
  if (row.diverged) row.tip = kNaN;
}

struct Beam {
  Eigen::Vector3i counts;
  Material material;
  Model model;             // the paper's model: its nodes, masses and springs are shared by every engine
  std::vector<int> fixed;  // nodes of face x = 0
  std::vector<int> tip;    // nodes of face x = L
  double length = 0;
};

// The material: E = 1 MPa, nu = 0.3, rho = 1000 kg/m^3, with the run's mass damping.
Material beam_material(double damping) {
  Material material;
  material.young_modulus = 1e6;
  material.poisson_ratio = 0.3;
  material.density = 1000.0;
  material.mass_damping = damping;
  return material;
}

Beam make_beam(const Eigen::Vector3i& counts, const BenchBulletOptions& o) {
  Beam beam;
  beam.counts = counts;
  beam.material = beam_material(o.damping);
  Result<Model> model = build_model(box_lattice(counts, Eigen::Vector3d::Constant(kCellSize), beam.material));
  if (!model) throw std::runtime_error(model.message());
  beam.model = std::move(model).value();
  beam.length = counts.x() * kCellSize;
  const double tolerance = 1e-9;
  beam.fixed = beam.model.nodes_in_box({-tolerance, -1e9, -1e9}, {tolerance, 1e9, 1e9});
  beam.tip = beam.model.nodes_in_box({beam.length - tolerance, -1e9, -1e9}, {beam.length + tolerance, 1e9, 1e9});
  return beam;
}

// ---- cubespring ----------------------------------------------------------------------------

Row run_cubespring(const Beam& beam, CellModel cell_model, bool implicit, int threads, const BenchBulletOptions& o) {
  LatticeDesc desc = box_lattice(beam.counts, Eigen::Vector3d::Constant(kCellSize), beam.material);
  desc.model = cell_model;
  Result<Model> built = build_model(desc);
  if (!built) throw std::runtime_error(built.message());
  const Model& model = built.value();
  Constraints clamp(model);
  if (Status s = clamp.fix_nodes(model, beam.fixed); !s) throw std::runtime_error(s.message());
  Loads loads;
  loads.gravity = {0.0, 0.0, -kGravity};
  State state = rest_state(model);
  Stepper stepper(model);

  Row row;
  row.engine = implicit ? "cubespring implicit" : "cubespring explicit";
  StepSettings settings;
  settings.threads = threads;
  settings.adapt_threads = false;  // the row takes the threads it names
  row.threads = threads;
  int sub_steps = 1;
  long solver_iterations = 0, steps = 0;
  std::ostringstream setting;
  setting << cell_model_name(cell_model) << ", ";
  if (implicit) {
    settings.integrator = Integrator::kImplicitEuler;
    settings.time_step = o.dt;
    settings.solver_tolerance = 1e-6;
  } else {
    settings.integrator = Integrator::kSymplecticEuler;
    sub_steps = std::max(1, static_cast<int>(std::ceil(o.dt / max_stable_time_step(model) - 1e-9)));
    settings.time_step = o.dt / sub_steps;
    setting << "symplectic Euler, " << sub_steps << " x " << 1e3 * settings.time_step << " ms";
    if (threads > 1) setting << ", " << threads << " threads";
  }
  const auto step_frame = [&]() -> std::string {
    for (int i = 0; i < sub_steps; ++i) {
      const StepReport report = stepper.step(model, clamp, loads, settings, state);
      if (!report.ok()) return std::string(step_status_name(report.status)) + ": " + report.message;
      solver_iterations += report.solver_iterations;
      ++steps;
    }
    return "";
  };
  const auto tip = [&] {
    double sum = 0;
    for (const int n : beam.tip) sum += state.positions(2, n) - model.rest_positions(2, n);
    return sum / static_cast<double>(beam.tip.size());
  };
  run_frames(o, beam.length, step_frame, tip, row);
  if (implicit) {
    setting << "implicit Euler 1 step/frame, CG 1e-6 ("
            << std::lround(static_cast<double>(solver_iterations) / static_cast<double>(std::max(1L, steps)))
            << " it/step)";
  }
  row.setting = setting.str();
  return row;
}

// Static equilibrium of the same lattice (Newton), the value a settled dynamic run must reach.
double cubespring_static_tip(const Beam& beam, CellModel cell_model) {
  ExperimentSettings settings;
  settings.material = beam.material;
  settings.material.mass_damping = 0.0;
  settings.model = cell_model;
  settings.cells = beam.counts;
  settings.cell_size = Eigen::Vector3d::Constant(kCellSize);
  settings.gravity = kGravity;
  Result<ExperimentResult> result = run_experiment(Experiment::kCantilever, settings);
  if (!result || !result->tip_deflection) return kNaN;
  return *result->tip_deflection;
}

// ---- Bullet ----------------------------------------------------------------------------------

// A btSoftBody on the lattice's nodes with its lumped masses, the clamped nodes at mass 0 (Bullet's
// way of pinning a node), kept awake (a sleeping body would stop moving and look settled).
std::unique_ptr<btSoftBody> make_soft_body(btSoftBodyWorldInfo& info, const Beam& beam) {
  const Model& model = beam.model;
  std::vector<btVector3> positions(static_cast<std::size_t>(model.num_nodes()));
  std::vector<btScalar> masses(positions.size());
  for (int n = 0; n < model.num_nodes(); ++n) {
    positions[static_cast<std::size_t>(n)] = bt(Eigen::Vector3d(model.rest_positions.col(n)));
    masses[static_cast<std::size_t>(n)] = bt(model.mass[n]);
  }
  auto body = std::make_unique<btSoftBody>(&info, model.num_nodes(), positions.data(), masses.data());
  for (const int n : beam.fixed) body->setMass(n, 0);
  body->m_sleepingThreshold = 0;
  return body;
}

double bullet_tip(const btSoftBody& body, const Beam& beam) {
  double sum = 0;
  for (const int n : beam.tip) {
    sum += static_cast<double>(body.m_nodes[n].m_x.z()) - beam.model.rest_positions(2, n);
  }
  return sum / static_cast<double>(beam.tip.size());
}

// Classic btSoftBody: the lattice's springs (12 edges and 4 body diagonals per cell, shared edges
// once) as links of kLST = 1, solved by position projection; its damping kDP scales the velocity
// by (1 - kDP) each step, which is mass damping of alpha = kDP / dt.
Row run_soft_body(const Beam& beam, int iterations, const BenchBulletOptions& o) {
  const btVector3 gravity(0, 0, bt(-kGravity));
  btSoftBodyRigidBodyCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher(&configuration);
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btSoftRigidDynamicsWorld world(&dispatcher, &broadphase, &solver, &configuration);
  world.setGravity(gravity);
  world.getWorldInfo().m_gravity = gravity;

  std::unique_ptr<btSoftBody> body = make_soft_body(world.getWorldInfo(), beam);
  for (const auto& spring : beam.model.spring_nodes) body->appendLink(spring[0], spring[1]);
  body->m_materials[0]->m_kLST = 1;
  body->m_cfg.piterations = iterations;
  body->m_cfg.kDP = bt(o.damping * o.dt);
  world.addSoftBody(body.get());
  body->forceActivationState(DISABLE_DEACTIVATION);

  Row row;
  row.engine = "btSoftBody";
  std::ostringstream setting;
  setting << "kLST = 1, piterations " << iterations << ", kDP " << o.damping * o.dt;
  row.setting = setting.str();
  const auto step_frame = [&]() -> std::string {
    world.stepSimulation(bt(o.dt), 0);
    return "";
  };
  run_frames(
      o, beam.length, step_frame, [&] { return bullet_tip(*body, beam); }, row);
  world.removeSoftBody(body.get());
  return row;
}

// The 6 tetrahedra of the Kuhn (Freudenthal) split of a cell along its diagonal from corner 0 to
// corner 7: one per order of the axes, along the path 0 -> e_a -> e_a + e_b -> 7. Every cell is cut
// the same way, so the faces of neighbouring cells are split along the same diagonal.
std::vector<std::array<int, 4>> kuhn_tetrahedra() {
  std::vector<std::array<int, 4>> tetrahedra;
  std::array<int, 3> axes{0, 1, 2};
  do {
    const int first = 1 << axes[0];
    const int second = first | (1 << axes[1]);
    tetrahedra.push_back({0, first, second, 7});
  } while (std::next_permutation(axes.begin(), axes.end()));
  return tetrahedra;
}

// Bullet's deformable FEM: btDeformableMultiBodyDynamicsWorld with btDeformableBodySolver, the
// body as 6 tetrahedra per cell, btDeformableLinearElasticityForce (Bullet's corotated linear
// elasticity) from E and nu with the same mass damping, btDeformableGravityForce, and the solver
// settings of Bullet's volumetric demos (implicit, no line search, projection for the pinned nodes).
Row run_deformable(const Beam& beam, const BenchBulletOptions& o) {
  const btVector3 gravity(0, 0, bt(-kGravity));
  btSoftBodyRigidBodyCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher(&configuration);
  btDbvtBroadphase broadphase;
  btDeformableBodySolver body_solver;
  btDeformableMultiBodyConstraintSolver constraint_solver;
  constraint_solver.setDeformableSolver(&body_solver);
  btDeformableMultiBodyDynamicsWorld world(&dispatcher, &broadphase, &constraint_solver, &configuration, &body_solver);
  world.setGravity(gravity);
  world.getWorldInfo().m_gravity = gravity;

  std::unique_ptr<btSoftBody> body = make_soft_body(world.getWorldInfo(), beam);
  const std::vector<std::array<int, 4>> split = kuhn_tetrahedra();
  for (const auto& cell : beam.model.cell_nodes) {
    for (const auto& tet : split) {
      std::array<int, 4> nodes{cell[tet[0]], cell[tet[1]], cell[tet[2]], cell[tet[3]]};
      // odd orders of the axes give a left-handed corner order: swap two corners for a positive volume
      const Eigen::Vector3d a = beam.model.rest_positions.col(nodes[1]) - beam.model.rest_positions.col(nodes[0]);
      const Eigen::Vector3d b = beam.model.rest_positions.col(nodes[2]) - beam.model.rest_positions.col(nodes[0]);
      const Eigen::Vector3d c = beam.model.rest_positions.col(nodes[3]) - beam.model.rest_positions.col(nodes[0]);
      if (a.dot(b.cross(c)) < 0) std::swap(nodes[1], nodes[2]);
      body->appendTetra(nodes[0], nodes[1], nodes[2], nodes[3]);
    }
  }
  body->initializeDmInverse();
  // the scratch of an undeformed tetrahedron (Bullet's default one leaves its matrices unset)
  btSoftBody::TetraScratch rest;
  rest.m_F.setIdentity();
  rest.m_trace = 3;
  rest.m_J = 1;
  rest.m_cofF.setIdentity();
  rest.m_corotation.setIdentity();
  body->m_tetraScratches.resize(body->m_tetras.size(), rest);
  body->m_tetraScratchesTn.resize(body->m_tetras.size(), rest);
  btSoftBodyHelpers::generateBoundaryFaces(body.get());
  world.addSoftBody(body.get());
  body->forceActivationState(DISABLE_DEACTIVATION);

  const double mu = shear_modulus(beam.material);
  const double lambda = lame_lambda(beam.material);
  btDeformableGravityForce gravity_force(gravity);
  btDeformableLinearElasticityForce elasticity(bt(mu), bt(lambda), bt(o.damping), 0);
  world.addForce(body.get(), &gravity_force);
  world.addForce(body.get(), &elasticity);
  world.setImplicit(true);
  world.setLineSearch(false);
  world.setUseProjection(true);

  Row row;
  row.engine = "Bullet deformable FEM";
  std::ostringstream setting;
  setting << body->m_tetras.size() << " tets (6/cell), corotated linear, implicit, 1 step/frame";
  row.setting = setting.str();
  const auto step_frame = [&]() -> std::string {
    world.stepSimulation(bt(o.dt), 0);
    return "";
  };
  run_frames(
      o, beam.length, step_frame, [&] { return bullet_tip(*body, beam); }, row);
  world.removeForce(body.get(), &elasticity);
  world.removeForce(body.get(), &gravity_force);
  world.removeSoftBody(body.get());
  return row;
}

// ---- the command -----------------------------------------------------------------------------

void check_options(const BenchBulletOptions& o) {
  const auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (!positive(o.seconds))
    throw std::runtime_error("--seconds " + std::to_string(o.seconds) + " must be a number > 0");
  if (!positive(o.dt) || o.dt > o.seconds) {
    throw std::runtime_error("--dt " + std::to_string(o.dt) + " must be a number > 0 and <= --seconds");
  }
  if (!std::isfinite(o.damping) || o.damping < 0.0 || o.damping * o.dt >= 1.0) {
    throw std::runtime_error("--damping " + std::to_string(o.damping) + " must be >= 0 and below 1 / dt");
  }
  if (!positive(o.max_case_seconds)) {
    throw std::runtime_error("--max-case-seconds " + std::to_string(o.max_case_seconds) + " must be a number > 0");
  }
  for (const int i : o.iterations) {
    if (i < 1) throw std::runtime_error("--iterations " + std::to_string(i) + ": each count must be >= 1");
  }
  if (o.models.empty()) throw std::runtime_error("--models: expected at least one cell model");
  if (o.threads.empty()) throw std::runtime_error("--threads: expected at least one thread count");
  for (const int t : o.threads) {
    if (t < 1) throw std::runtime_error("--threads " + std::to_string(t) + ": each count must be >= 1");
  }
}

struct SizeSummary {
  std::string size;
  double reference = kNaN;
  std::string reference_source;
  std::vector<std::pair<std::string, double>> static_tips;  // cubespring static tip per cell model
};

std::string format_number(const char* format, double value) {
  if (!std::isfinite(value)) return "-";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

void print_table(const std::vector<Row>& rows, const std::vector<SizeSummary>& sizes, const BenchBulletOptions& o) {
  const Material material = beam_material(o.damping);
  const std::string processor = cpu_name();
  std::printf("machine: %s, %u hardware threads; Bullet %d (%s precision)\n",
              processor.empty() ? "unknown CPU" : processor.c_str(), std::thread::hardware_concurrency(),
              btGetVersion(), sizeof(btScalar) == 8 ? "double" : "single");
  std::printf(
      "beam of 1 cm cells, E = 1 MPa, nu = 0.3, rho = 1000 kg/m^3, face x = 0 clamped, g = 9.81 m/s^2 along -z;\n"
      "%g s simulated in frames of %g ms from rest, mass damping alpha = %g 1/s in every engine\n",
      o.seconds, 1e3 * o.dt, o.damping);
  std::printf("%-7s %-21s %13s %12s %13s %9s %9s %8s  %s\n", "size", "engine", "wall_s/sim_s", "cpu_s/sim_s", "tip_m",
              "err_FE_%", "drift_%", "x_expl", "case / notes");
  for (const Row& r : rows) {
    const std::string wall = format_number("%.4g", r.wall_per_sim);
    const std::string cpu = format_number("%.4g", r.cpu_per_sim);
    std::string tip = r.diverged ? "diverged" : format_number("%.6f", r.tip);
    std::string error = r.diverged ? "-" : format_number("%+.1f", 100.0 * r.error());
    if (r.capped) {
      tip += "*";
      error += "*";
    }
    const std::string drift = format_number("%.3f", 100.0 * std::abs(r.drift / r.tip));
    const std::string ratio = format_number("%.3g", r.wall_per_sim / r.base_wall);
    std::printf("%-7s %-21s %13s %12s %13s %9s %9s %8s  %s%s\n", r.size.c_str(), r.engine.c_str(), wall.c_str(),
                cpu.c_str(), tip.c_str(), error.c_str(), drift.c_str(), ratio.c_str(), r.setting.c_str(),
                r.status == "ok" ? "" : ("; " + r.status).c_str());
  }
  std::printf(
      "wall_s/sim_s: wall seconds per simulated second, stepping only (set-up excluded), measured over the whole\n"
      "run, or, for a case capped at %g s of wall time (*), over the part simulated (an extrapolation to the\n"
      "full run; its tip is where it had got to, not where it settles). cpu_s/sim_s: the same in process\n"
      "CPU time, which other jobs on a shared machine do not inflate. tip_m: mean z displacement of the\n"
      "nodes of face x = L at the end. err_FE_%%: tip / FE reference - 1 (negative: too stiff). drift_%%: the\n"
      "tip's change over the last %g s relative to the tip (how settled it is). x_expl: wall time over the\n"
      "same size's cubespring explicit %s row. Every engine has the lattice's nodes and lumped masses\n"
      "(rho h^3 / 8 per cell corner), so the loads are the same, and the clamped nodes fixed (cubespring:\n"
      "Constraints::fix_nodes; Bullet: mass 0). Damping: cubespring Material::mass_damping = alpha;\n"
      "btSoftBody kDP = alpha dt (velocities scaled by 1 - kDP each step); FEM damping_alpha = alpha,\n"
      "damping_beta = 0; no stiffness damping anywhere. cubespring: double precision, 1 thread unless its case\n"
      "says more (Bullet runs on one); explicit\n"
      "sub-steps: the fewest of equal length within max_stable_time_step. Bullet: stepSimulation(dt, 0),\n"
      "one internal step per frame; btSoftBody links = the lattice's springs (edges and body diagonals);\n"
      "FEM: btDeformableBodySolver as in Bullet's volumetric demos (setImplicit(true), no line search,\n"
      "setUseProjection(true), its default CG), btDeformableLinearElasticityForce(mu = %.0f Pa,\n"
      "lambda = %.0f Pa), btDeformableGravityForce, each cell split along its 0-7 diagonal into 6 tets.\n"
      "The FE references are linear; every run here is at full gravity (geometrically nonlinear).\n",
      o.max_case_seconds, o.drift_window, o.models.front().c_str(), shear_modulus(material), lame_lambda(material));
  for (const SizeSummary& s : sizes) {
    std::printf("%s: FE reference %s m (%s); cubespring static (Newton):", s.size.c_str(),
                format_number("%.6f", s.reference).c_str(), s.reference_source.c_str());
    for (const auto& [model, tip] : s.static_tips) {
      std::printf(" %s %s m (%s%%)", model.c_str(), format_number("%.6f", tip).c_str(),
                  format_number("%+.1f", 100.0 * (tip / s.reference - 1.0)).c_str());
    }
    std::printf("\n");
  }
  // a settled run away from the static equilibrium found by Newton from rest: another equilibrium
  for (const Row& r : rows) {
    if (!r.settled() || !std::isfinite(r.static_tip)) continue;
    const double off = r.tip / r.static_tip - 1.0;
    if (std::abs(off) < 0.01) continue;
    std::printf(
        "note: %s %s (%s) settles %+.1f%% away from the static equilibrium Newton finds from rest (%.6f m):\n"
        "  the dynamics reached another equilibrium of the same lattice\n",
        r.size.c_str(), r.engine.c_str(), r.setting.substr(0, r.setting.find(',')).c_str(), 100.0 * off, r.static_tip);
  }
  // the target: cubespring at least 50x faster than Bullet's deformable FEM, at better accuracy
  for (const SizeSummary& s : sizes) {
    const Row* fem = nullptr;
    for (const Row& r : rows) {
      if (r.size == s.size && r.engine == "Bullet deformable FEM") fem = &r;
    }
    if (fem == nullptr || fem->diverged) continue;
    for (const Row& r : rows) {
      if (r.size != s.size || r.engine.rfind("cubespring", 0) != 0 || r.diverged) continue;
      const double speedup = fem->wall_per_sim / r.wall_per_sim;
      const std::string threads =
          r.threads > 1 ? ", " + std::to_string(r.threads) + " threads against the FEM's one" : "";
      std::printf("target %s, %s (%s%s): %.3gx faster than the FEM in wall time (%.3gx in CPU time)%s", s.size.c_str(),
                  r.engine.c_str(), r.setting.substr(0, r.setting.find(',')).c_str(), threads.c_str(), speedup,
                  fem->cpu_per_sim / r.cpu_per_sim, fem->capped || r.capped ? " (time extrapolated)" : "");
      if (!fem->settled() || !r.settled()) {
        std::printf(", accuracy not compared (%s not settled): speed %s\n", r.settled() ? "FEM" : "cubespring",
                    speedup >= 50.0 ? "met" : "NOT met");
        continue;
      }
      const bool better = std::abs(r.error()) < std::abs(fem->error());
      std::printf(", |error| %.1f%% vs %.1f%%: %s\n", 100.0 * std::abs(r.error()), 100.0 * std::abs(fem->error()),
                  speedup >= 50.0 && better ? "met" : "NOT met");
    }
  }
}

int run_bench_bullet(const BenchBulletOptions& o) {
  std::vector<Row> rows;
  std::vector<SizeSummary> summaries;
  try {
    check_options(o);
    std::vector<CellModel> cell_models;
    for (const std::string& name : o.models) {
      Result<CellModel> model = parse_cell_model(name);
      if (!model) throw std::runtime_error("--models: " + model.message());
      cell_models.push_back(model.value());
    }
    for (const Eigen::Vector3i& counts : parse_size_list(o.sizes)) {
      const Beam beam = make_beam(counts, o);
      SizeSummary summary;
      summary.size = size_name(counts);
      std::tie(summary.reference, summary.reference_source) = fe_reference(counts);
      const auto add = [&](Row row) {
        row.size = summary.size;
        row.reference = summary.reference;
        if (!o.json) {
          std::fprintf(stderr, "%s %s (%s): %s s wall per simulated s, tip %s m%s\n", row.size.c_str(),
                       row.engine.c_str(), row.setting.c_str(), format_number("%.4g", row.wall_per_sim).c_str(),
                       format_number("%.6f", row.tip).c_str(), row.status == "ok" ? "" : ("; " + row.status).c_str());
        }
        rows.push_back(std::move(row));
      };
      const std::size_t first = rows.size();
      for (const CellModel model : cell_models) {
        const double static_tip = cubespring_static_tip(beam, model);
        summary.static_tips.emplace_back(cell_model_name(model), static_tip);
        for (const int threads : o.threads) {
          Row row = run_cubespring(beam, model, false, threads, o);
          row.static_tip = static_tip;
          add(std::move(row));
        }
        Row row = run_cubespring(beam, model, true, 1, o);
        row.static_tip = static_tip;
        add(std::move(row));
      }
      for (const int iterations : o.iterations) add(run_soft_body(beam, iterations, o));
      add(run_deformable(beam, o));
      for (std::size_t i = first; i < rows.size(); ++i) rows[i].base_wall = rows[first].wall_per_sim;
      summaries.push_back(summary);
    }
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  }

  if (o.json) {
    const auto number = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); };
    nlohmann::json out = nlohmann::json::array();
    for (const Row& r : rows) {
      out.push_back({{"size", r.size},
                     {"engine", r.engine},
                     {"case", r.setting},
                     {"wall_s_per_sim_s", number(r.wall_per_sim)},
                     {"cpu_s_per_sim_s", number(r.cpu_per_sim)},
                     {"tip_deflection_m", number(r.tip)},
                     {"fe_reference_m", number(r.reference)},
                     {"error_vs_fe", number(r.error())},
                     {"drift_m", number(r.drift)},
                     {"cubespring_static_tip_m", number(r.static_tip)},
                     {"ratio_to_cubespring_explicit", number(r.wall_per_sim / r.base_wall)},
                     {"simulated_s", r.simulated},
                     {"damping_alpha_per_s", o.damping},
                     {"threads", r.threads},
                     {"status", r.status}});
    }
    std::cout << json_text(out) << "\n";
    return 0;
  }
  print_table(rows, summaries, o);
  return 0;
}

}  // namespace

Command add_bench_bullet_command(CLI::App& app) {
  auto options = std::make_shared<BenchBulletOptions>();
  CLI::App* cmd = app.add_subcommand("bench-bullet",
                                     "Run one clamped beam as a cubespring body, a classic Bullet btSoftBody and "
                                     "Bullet's deformable FEM, side by side");
  cmd->add_option("--sizes", options->sizes, "beams of 1 cm cells as NX,NY,NZ separated by ';'")->capture_default_str();
  cmd->add_option("--seconds", options->seconds, "simulated time per case [s]")->capture_default_str();
  cmd->add_option("--dt", options->dt, "frame time step [s]")->capture_default_str();
  cmd->add_option("--damping", options->damping, "mass damping alpha of every engine [1/s]")->capture_default_str();
  cmd->add_option("--iterations", options->iterations, "btSoftBody position iterations, separated by ','")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--models", options->models, "cubespring cell models, separated by ','")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--threads", options->threads, "force-pass threads of the explicit cubespring rows, separated by ','")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--max-case-seconds", options->max_case_seconds,
                  "stop a case after this much wall time and extrapolate its time [s]")
      ->capture_default_str();
  cmd->add_flag("--json", options->json, "print a JSON array instead of the table");
  return [options] { return run_bench_bullet(*options); };
}

}  // namespace cubespring::app
