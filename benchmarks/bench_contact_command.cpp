// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// cubespring bench-contact: the contact issue's cases in one run, through the Bullet plugin. Probes
// (kinematic capsules) pressed 1 cm into soft tissue resting on the ground and dragged 4 cm, at
// each radius, speed and Bullet step; 3 cm boxes of each mass dropped 5 mm onto the block. Tissue:
// 5 kPa, nu = 0.45, density 1060, mass damping 40/s, exact-bending cells, the neo-Hookean law,
// friction 0.3. Printed per case: how deep the surface reached into the probe, whether its force
// ever fell below half the step before while pressing, the drag's mean force and its roughness
// (RMS of the force less its 20 ms moving average, over the mean), the wall time per simulated
// second; per drop, whether the box came to rest carried by the tissue.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <btBulletDynamicsCommon.h>
#include <nlohmann/json.hpp>

#include "bench_support.h"
#include "commands.h"
#include "cubespring/bullet/world.h"
#include "cubespring/forces.h"
#include "cubespring/mesh/load_mesh.h"
#include "cubespring/voxelize.h"
#include "json_output.h"
#include "number_checks.h"

namespace cubespring::app {
namespace {

struct BenchContactOptions {
  std::string mesh;            // an organ besides the block; empty: the block alone
  double longest_side = 0.15;  // [m] of the organ
  std::string cells_across = "20";
  std::string radii = "0.001,0.002,0.005";
  std::string speeds = "0.01,0.02,0.1";
  std::string steps = "0.001,0.0166667";
  std::string drops = "0.02,0.1,0.2";
  bool json = false;
};

constexpr double kPressDepth = 0.01;       // [m]
constexpr double kDragLength = 0.04;       // [m]
constexpr double kSmoothingWindow = 0.02;  // [s], the moving average the roughness is measured against

// "a,b,c" as positive finite numbers; throws naming the flag and the part at fault.
std::vector<double> parse_numbers(const std::string& text, const std::string& flag) {
  return parse_number_list(
      text, flag, [](double value) { return value > 0.0 && std::isfinite(value); }, "a positive number");
}

// the scenes' default tissue (nu 0.45, 1060 kg/m^3, 40/s) at the 5 kPa
Material tissue() { return soft_tissue(5e3); }

// A Bullet world with one soft body on the ground (the plane z = 0), owning what it makes.
class Bench {
 public:
  explicit Bench(const bullet::SoftBodySettings& settings)
      : dispatcher_(&configuration_), world_(&dispatcher_, &broadphase_, &solver_, &configuration_) {
    world_.setGravity(btVector3(0, 0, btScalar(-9.81)));
    add_rigid(new btStaticPlaneShape(btVector3(0, 0, 1), 0), 0.0, btTransform::getIdentity(), false);
    Result<std::unique_ptr<bullet::SoftBody>> made = bullet::SoftBody::create(settings);
    if (!made) throw std::runtime_error(made.message());
    soft_ = std::move(made).value();
    world_.addSoftBody(soft_.get());
  }
  ~Bench() {
    for (auto& body : rigid_) world_.removeRigidBody(body.get());
    world_.removeSoftBody(soft_.get());
  }
  btRigidBody* add_rigid(btCollisionShape* shape, double mass, const btTransform& place, bool kinematic) {
    shapes_.emplace_back(shape);
    btVector3 inertia(0, 0, 0);
    if (mass > 0) shape->calculateLocalInertia(btScalar(mass), inertia);
    btRigidBody::btRigidBodyConstructionInfo info(btScalar(mass), nullptr, shape, inertia);
    info.m_startWorldTransform = place;
    rigid_.push_back(std::make_unique<btRigidBody>(info));
    btRigidBody* body = rigid_.back().get();
    if (kinematic) body->setCollisionFlags(body->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
    body->setActivationState(DISABLE_DEACTIVATION);
    world_.addRigidBody(body);
    return body;
  }
  // Steps for `seconds` at `step`; false (and the body's message) if it stopped.
  bool run(double seconds, double step) {
    const int steps = std::max(1, static_cast<int>(std::lround(seconds / step)));
    for (int i = 0; i < steps && error().empty(); ++i) world_.stepSimulation(btScalar(step), 1, btScalar(step));
    return error().empty();
  }
  std::string error() const { return world_.getSoftBodyError(); }
  bullet::World& world() { return world_; }
  const bullet::SoftBody& soft() const { return *soft_; }

 private:
  btDefaultCollisionConfiguration configuration_;
  btCollisionDispatcher dispatcher_;
  btDbvtBroadphase broadphase_;
  btSequentialImpulseConstraintSolver solver_;
  bullet::World world_;
  std::vector<std::unique_ptr<btCollisionShape>> shapes_;
  std::vector<std::unique_ptr<btRigidBody>> rigid_;
  std::unique_ptr<bullet::SoftBody> soft_;
};

struct Body {
  std::string name;
  bullet::SoftBodySettings settings;
  double settle = 1.0;  // [s] before a probe comes
};

// The 10 x 10 x 5 cm block, `across` cells along its 10 cm sides.
Body block(int across) {
  const double h = 0.1 / across;
  const int tall = std::max(1, static_cast<int>(std::lround(0.05 / h)));
  Body body{"block 10x10x5 cm, " + std::to_string(across) + " across", {}, 1.0};
  body.settings.lattice = box_lattice({across, across, tall}, Eigen::Vector3d::Constant(h), tissue());
  body.settings.lattice.origin = Eigen::Vector3d(-0.05, -0.05, 0.0);
  body.settings.lattice.model = CellModel::kExactBending;
  body.settings.contact.friction = 0.3;
  return body;
}

// The organ in `path` scaled to `longest` [m], lowest point on the ground, `across` cells along
// its longest side, its mesh the visual surface; it settles 4 s (an organ as its file stands it
// may topple first).
Body organ(const std::string& path, double longest, int across) {
  Result<TriangleMesh> unscaled = load_mesh(path);
  if (!unscaled) throw std::runtime_error(unscaled.message());
  const Eigen::Vector3d extent = unscaled->vertices.rowwise().maxCoeff() - unscaled->vertices.rowwise().minCoeff();
  LoadOptions options;
  options.scale = longest / extent.maxCoeff();
  Result<TriangleMesh> mesh = load_mesh(path, options);
  if (!mesh) throw std::runtime_error(mesh.message());
  mesh->vertices.row(2).array() -= mesh->vertices.row(2).minCoeff();
  VoxelizeOptions voxelize_options;
  voxelize_options.cells_across = across;
  Result<Voxelization> voxels = voxelize(*mesh, voxelize_options);
  if (!voxels) throw std::runtime_error(voxels.message());
  Body body{std::filesystem::path(path).filename().string() + ", " + std::to_string(across) + " across", {}, 4.0};
  body.settings.lattice = lattice_from_voxels(
      *voxels, std::vector<Material>(std::max<std::size_t>(1, mesh->parts.size()), tissue()), CellModel::kExactBending);
  body.settings.visual_mesh = *mesh;
  body.settings.contact.friction = 0.3;
  return body;
}

struct ProbeCase {
  std::string body;
  double radius = 0, speed = 0, step = 0;
  std::string failure;    // empty when it ran
  double deepest = 0;     // [m]
  int drops = 0;          // steps whose force fell below half the step before's, while pressing
  double drag_force = 0;  // mean [N]
  double roughness = 0;   // RMS of the force less its moving average, over the mean force
  double wall_per_simulated = 0;
};

// A probe of `radius` pressed and dragged over the body's top, 2 cm before its centre.
ProbeCase probe(const Body& body, double radius, double speed, double step) {
  ProbeCase result;
  result.body = body.name;
  result.radius = radius;
  result.speed = speed;
  result.step = step;
  Bench bench(body.settings);
  if (!bench.run(body.settle, 1.0 / 60)) {
    result.failure = "while settling: " + bench.error();
    return result;
  }
  const Eigen::Matrix3Xd& surface = bench.soft().surface_vertices();
  const Eigen::Vector3d centre = 0.5 * (surface.rowwise().minCoeff() + surface.rowwise().maxCoeff());
  const double high = surface.row(2).maxCoeff() + 0.1;
  const std::optional<bullet::SoftBody::RayHit> hit = bench.soft().ray_test(
      Eigen::Vector3d(centre.x() - 0.02, centre.y(), high), Eigen::Vector3d(centre.x() - 0.02, centre.y(), -0.1));
  if (!hit) {
    result.failure = "no surface under the probe";
    return result;
  }
  const double top = high - hit->fraction * (high + 0.1);
  const double length = 0.1;
  const double press = kPressDepth / speed;
  const auto tip_centre = [&](double t) {
    const double depth = std::min(t / press, 1.0) * kPressDepth;
    const double along = std::clamp((t - press) * speed, 0.0, kDragLength);
    return Eigen::Vector3d(centre.x() - 0.02 + along, centre.y() + 0.0013, top + radius - depth);
  };
  const auto place = [&](double t) {
    const Eigen::Vector3d c = tip_centre(t);
    return btTransform(btQuaternion::getIdentity(),
                       btVector3(btScalar(c.x()), btScalar(c.y()), btScalar(c.z() + 0.5 * length - radius)));
  };
  btRigidBody* tool =
      bench.add_rigid(new btCapsuleShapeZ(btScalar(radius), btScalar(length - 2 * radius)), 0.0, place(0.0), true);
  const int steps = static_cast<int>(std::lround((press + kDragLength / speed) / step));
  std::vector<double> drag;
  double previous = 0.0;
  const auto start = std::chrono::steady_clock::now();
  for (int n = 1; n <= steps; ++n) {
    tool->setWorldTransform(place(n * step));
    bench.world().stepSimulation(btScalar(step), 1, btScalar(step));
    if (!bench.error().empty()) {
      result.failure = bench.error();
      return result;
    }
    const bullet::ContactWrench wrench = bench.world().getContactWrench(tool);
    const double force = wrench.force.norm();
    result.deepest = std::max(result.deepest, wrench.penetration);
    if (n * step > 0.3 * press && n * step <= press && force < 0.5 * previous) ++result.drops;
    if (n * step > press) drag.push_back(force);
    previous = force;
  }
  result.wall_per_simulated =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / (steps * step);
  if (!drag.empty()) {
    double sum = 0.0;
    for (const double f : drag) sum += f;
    result.drag_force = sum / static_cast<double>(drag.size());
    const int half = std::max(1, static_cast<int>(std::lround(0.5 * kSmoothingWindow / step)));
    double squares = 0.0;
    for (std::size_t i = 0; i < drag.size(); ++i) {
      const std::size_t from = i >= static_cast<std::size_t>(half) ? i - static_cast<std::size_t>(half) : 0;
      const std::size_t to = std::min(drag.size(), i + static_cast<std::size_t>(half) + 1);
      double mean = 0.0;
      for (std::size_t j = from; j < to; ++j) mean += drag[j];
      mean /= static_cast<double>(to - from);
      squares += (drag[i] - mean) * (drag[i] - mean);
    }
    result.roughness =
        result.drag_force > 0 ? std::sqrt(squares / static_cast<double>(drag.size())) / result.drag_force : 0;
  }
  return result;
}

struct DropCase {
  std::string body;
  double mass = 0;
  std::string failure;
  double speed = 0;    // over the last 0.5 s [m/s]
  double carried = 0;  // the tissue's force on it over its weight
  double sunk = 0;     // below the block's top [m]
};

// A 3 cm box of `mass` dropped 5 mm onto the block's centre, 3 s at 1/60 s.
DropCase drop(const Body& body, double mass) {
  DropCase result;
  result.body = body.name;
  result.mass = mass;
  Bench bench(body.settings);
  const double half = 0.015;
  const double top = bench.soft().surface_vertices().row(2).maxCoeff();
  btRigidBody* box =
      bench.add_rigid(new btBoxShape(btVector3(btScalar(half), btScalar(half), btScalar(half))), mass,
                      btTransform(btQuaternion::getIdentity(), btVector3(0, 0, btScalar(top + half + 0.005))), false);
  if (!bench.run(2.5, 1.0 / 60)) {
    result.failure = bench.error();
    return result;
  }
  const btVector3 before = box->getCenterOfMassPosition();
  if (!bench.run(0.5, 1.0 / 60)) {
    result.failure = bench.error();
    return result;
  }
  result.speed = double((box->getCenterOfMassPosition() - before).length()) / 0.5;
  result.carried = bench.world().getContactWrench(box).force.z() / (mass * 9.81);
  result.sunk = top - (double(box->getCenterOfMassPosition().z()) - half);
  return result;
}

int run(const BenchContactOptions& o) {
  std::vector<double> across, radii, speeds, steps, masses;
  try {
    for (const double n : parse_numbers(o.cells_across, "--cells-across")) {
      if (n != std::floor(n) || n > 200) {
        throw std::runtime_error("--cells-across: " + std::to_string(n) + " is not a whole number up to 200");
      }
      across.push_back(n);
    }
    radii = parse_numbers(o.radii, "--radii");
    speeds = parse_numbers(o.speeds, "--speeds");
    steps = parse_numbers(o.steps, "--steps");
    masses = parse_numbers(o.drops, "--drops");
  } catch (const std::exception& bad) {
    std::cerr << "error: " << bad.what() << "\n";
    return 2;
  }
  std::vector<ProbeCase> probes;
  std::vector<DropCase> drops;
  try {
    for (const double n : across) {
      std::vector<Body> bodies{block(static_cast<int>(n))};
      if (!o.mesh.empty()) bodies.push_back(organ(o.mesh, o.longest_side, static_cast<int>(n)));
      for (const Body& body : bodies) {
        for (const double r : radii) {
          for (const double v : speeds) {
            for (const double dt : steps) probes.push_back(probe(body, r, v, dt));
          }
        }
      }
      for (const double m : masses) drops.push_back(drop(bodies.front(), m));
    }
  } catch (const std::exception& failed) {
    std::cerr << "error: " << failed.what() << "\n";
    return 1;
  }
  if (o.json) {
    nlohmann::json out;
    out["machine"] = cpu_name();
    out["probes"] = nlohmann::json::array();
    for (const ProbeCase& p : probes) {
      out["probes"].push_back({{"body", p.body},
                               {"radius_m", p.radius},
                               {"speed_m_per_s", p.speed},
                               {"step_s", p.step},
                               {"failure", p.failure},
                               {"deepest_m", p.deepest},
                               {"allowed_m", std::max(0.5e-3, 0.1 * p.radius)},
                               {"force_drops", p.drops},
                               {"drag_force_N", p.drag_force},
                               {"roughness", p.roughness},
                               {"wall_per_simulated", p.wall_per_simulated}});
    }
    out["drops"] = nlohmann::json::array();
    for (const DropCase& d : drops) {
      out["drops"].push_back({{"body", d.body},
                              {"mass_kg", d.mass},
                              {"failure", d.failure},
                              {"speed_m_per_s", d.speed},
                              {"carried_over_weight", d.carried},
                              {"sunk_m", d.sunk}});
    }
    std::cout << json_text(out) << "\n";
    return 0;
  }
  std::printf("probes pressed %.0f mm and dragged %.0f mm; %s\n", 1e3 * kPressDepth, 1e3 * kDragLength,
              cpu_name().c_str());
  std::printf("%-34s %6s %6s %7s %10s %8s %6s %8s %7s %7s\n", "body", "r mm", "cm/s", "step ms", "deepest mm",
              "allowed", "drops", "drag N", "rough %", "wall/s");
  for (const ProbeCase& p : probes) {
    std::printf("%-34s %6.1f %6.1f %7.2f ", p.body.c_str(), 1e3 * p.radius, 1e2 * p.speed, 1e3 * p.step);
    if (!p.failure.empty()) {
      std::printf("unstable: %s\n", p.failure.c_str());
      continue;
    }
    std::printf("%10.3f %8.2f %6d %8.3f %7.1f %7.2f\n", 1e3 * p.deepest, 1e3 * std::max(0.5e-3, 0.1 * p.radius),
                p.drops, p.drag_force, 1e2 * p.roughness, p.wall_per_simulated);
  }
  std::printf("\n3 cm boxes dropped 5 mm onto the block, 3 s at 1/60 s\n%-34s %7s %14s %12s %8s\n", "body", "mass g",
              "speed mm/s", "carried/w", "sunk mm");
  for (const DropCase& d : drops) {
    std::printf("%-34s %7.0f ", d.body.c_str(), 1e3 * d.mass);
    if (!d.failure.empty()) {
      std::printf("unstable: %s\n", d.failure.c_str());
      continue;
    }
    std::printf("%14.4f %12.4f %8.1f\n", 1e3 * d.speed, d.carried, 1e3 * d.sunk);
  }
  return 0;
}

}  // namespace

Command add_bench_contact_command(CLI::App& app) {
  auto options = std::make_shared<BenchContactOptions>();
  CLI::App* cmd = app.add_subcommand("bench-contact",
                                     "Probes pressed and dragged over soft tissue, and instruments "
                                     "dropped on it, through the Bullet plugin: penetration, force, "
                                     "rest");
  cmd->add_option("--mesh", options->mesh,
                  "an organ mesh to probe besides the block (OBJ, STL, PLY, OFF, glTF or COLLADA)");
  cmd->add_option("--longest-side", options->longest_side, "the organ's longest side once scaled [m]")
      ->check(finite_positive_number())
      ->capture_default_str();
  cmd->add_option("--cells-across", options->cells_across,
                  "cells along the block's 10 cm side and the organ's longest, "
                  "a,b,...")
      ->capture_default_str();
  cmd->add_option("--radii", options->radii, "probe radii [m], a,b,...")->capture_default_str();
  cmd->add_option("--speeds", options->speeds, "probe speeds [m/s], a,b,...")->capture_default_str();
  cmd->add_option("--steps", options->steps, "Bullet steps [s], a,b,...")->capture_default_str();
  cmd->add_option("--drops", options->drops, "masses of the dropped boxes [kg], a,b,...")->capture_default_str();
  cmd->add_flag("--json", options->json, "print one JSON object instead of the tables");
  return [options] { return run(*options); };
}

}  // namespace cubespring::app
