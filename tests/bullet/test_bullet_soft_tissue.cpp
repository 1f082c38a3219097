// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// A soft organ resting on the ground before any tool touches it (issues 24 and 25): a 12 cm cube
// of 5 or 10 kPa tissue (nu = 0.45, density 1060, mass damping 40/s, exact-bending cells of 8 mm,
// the plugin's default neo-Hookean law) with a visual surface twice as fine as its cells, on a
// static plane, for 3 s at Bullet's 1/60 s steps. It must settle: no blow-up, no crushed cell,
// its volume kept, the ground carrying its weight. (Label slow: seconds in a release build.)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "bullet_scene.h"

namespace cubespring {
namespace {

// The surface of the box [-a, a]^2 x [0, 2a], each face cut into n x n squares of two triangles,
// counter-clockwise seen from outside, with the vertices on its edges shared.
TriangleMesh box_surface(double a, int n) {
  const int side = n + 1;
  std::vector<int> index(static_cast<std::size_t>(side * side * side), -1);
  std::vector<Eigen::Vector3d> vertices;
  const auto vertex = [&](const Eigen::Vector3i& g) {
    int& i = index[static_cast<std::size_t>((g.z() * side + g.y()) * side + g.x())];
    if (i < 0) {
      i = static_cast<int>(vertices.size());
      vertices.push_back(Eigen::Vector3d(-a, -a, 0) + (2 * a / n) * g.cast<double>());
    }
    return i;
  };
  std::vector<Eigen::Vector3i> triangles;
  for (int d = 0; d < 3; ++d) {
    const int u = (d + 1) % 3;
    const int v = (d + 2) % 3;  // e_u x e_v = e_d
    for (int high = 0; high < 2; ++high) {
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
          const auto corner = [&](int di, int dj) {
            Eigen::Vector3i g;
            g[d] = high * n;
            g[u] = i + di;
            g[v] = j + dj;
            return vertex(g);
          };
          const int p00 = corner(0, 0), p10 = corner(1, 0), p11 = corner(1, 1), p01 = corner(0, 1);
          if (high) {
            triangles.push_back({p00, p10, p11});
            triangles.push_back({p00, p11, p01});
          } else {
            triangles.push_back({p00, p11, p10});
            triangles.push_back({p00, p01, p11});
          }
        }
      }
    }
  }
  TriangleMesh mesh;
  mesh.vertices.resize(3, static_cast<Eigen::Index>(vertices.size()));
  for (std::size_t i = 0; i < vertices.size(); ++i) mesh.vertices.col(static_cast<Eigen::Index>(i)) = vertices[i];
  mesh.triangles.resize(3, static_cast<Eigen::Index>(triangles.size()));
  for (std::size_t i = 0; i < triangles.size(); ++i) mesh.triangles.col(static_cast<Eigen::Index>(i)) = triangles[i];
  return mesh;
}

// A cube of tissue (nu = 0.45, density 1060, mass damping 40/s) of `cells` exact-bending cells of
// 8 mm across, base at z = 0, its visual surface the cube's faces cut into `squares` x `squares`.
bullet::SoftBodySettings tissue_cube(double young_modulus, int cells, int squares) {
  Material tissue;
  tissue.young_modulus = young_modulus;
  tissue.poisson_ratio = 0.45;
  tissue.density = 1060;
  tissue.mass_damping = 40;
  const double h = 0.008;
  bullet::SoftBodySettings settings = test::block(Eigen::Vector3i::Constant(cells), h, tissue);
  settings.lattice.model = CellModel::kExactBending;
  settings.visual_mesh = box_surface(0.5 * cells * h, squares);
  return settings;
}

TEST(SoftTissue, BoxSurfaceIsClosedAndOutward) {
  const TriangleMesh mesh = box_surface(0.06, 6);
  EXPECT_EQ(mesh.num_vertices(), 6 * 6 * 6 + 2);  // (n+1)^3 - (n-1)^3
  double volume = 0.0;                            // the divergence theorem: outward triangles give the box's volume
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    const Eigen::Vector3d a = mesh.vertices.col(mesh.triangles(0, t));
    const Eigen::Vector3d b = mesh.vertices.col(mesh.triangles(1, t));
    const Eigen::Vector3d c = mesh.vertices.col(mesh.triangles(2, t));
    volume += a.dot(b.cross(c)) / 6.0;
  }
  EXPECT_NEAR(volume, 0.12 * 0.12 * 0.12, 1e-12);
}

TEST(SoftTissue, CubeOnTheGroundSettlesKeepingItsVolume) {
  for (double young_modulus : {5e3, 1e4}) {
    test::BulletScene scene;
    btRigidBody* floor = scene.add_floor();
    bullet::SoftBody* soft = scene.add_soft(tissue_cube(young_modulus, 15, 30));
    ASSERT_NE(soft, nullptr);
    ASSERT_EQ(soft->model().cell_law, CellLaw::kNeoHookean) << "the plugin's default";
    scene.run(3.0);
    ASSERT_TRUE(scene.world().getSoftBodyError().empty()) << scene.world().getSoftBodyError();
    const Model& model = soft->model();
    double volume = 0.0, least = 1e300;
    for (int c = 0; c < model.num_cells(); ++c) {
      const double j = cell_signed_volume(model, soft->state().positions, c) / model.rest_cell_volume();
      volume += j;
      least = std::min(least, j);
    }
    volume /= model.num_cells();
    const double rms_speed = std::sqrt(2.0 * kinetic_energy(model, soft->state()) / model.total_mass());
    const double weight = model.total_mass() * 9.81;
    const double ground = -scene.world().getContactWrench(floor).force.z();
    const double top = soft->state().positions(2, model.node_at({7, 7, 15}));
    std::printf(
        "E = %g Pa: top centre %.2f mm (rest 120), volume %.4f of rest, least cell J %.3f, rms speed %.2e m/s, "
        "ground %.4f N for a weight of %.4f N\n",
        young_modulus, 1e3 * top, volume, least, rms_speed, ground, weight);
    EXPECT_GT(least, 0.5);
    EXPECT_NEAR(volume, 1.0, 0.03);
    EXPECT_LT(rms_speed, 1e-3) << "at rest (4e-3 m/s when a contact pass took the mean of its points' corrections)";
    EXPECT_NEAR(ground, weight, 0.01 * weight);
    EXPECT_GT(top, 0.1) << "it stands: the sag of a uniaxial column, rho g H^2 / (2 E), is 15 mm at 5 kPa";
  }
}

TEST(SoftTissue, CubeWithACoarseSurfaceRestsOnTheGround) {
  // the cube's visual surface is its 8 corners and 12 triangles, 15 cells a side: contact on the
  // surface's vertices alone left the cells between the corners to sink through the ground, and it
  // blew up at t = 0.24 s; the contact surface splits the edges to 1.5 cells at most
  test::BulletScene scene;
  btRigidBody* floor = scene.add_floor();
  bullet::SoftBodySettings settings = tissue_cube(5e3, 15, 1);
  ASSERT_EQ(settings.visual_mesh->num_vertices(), 8);
  bullet::SoftBody* soft = scene.add_soft(settings);
  ASSERT_NE(soft, nullptr);
  scene.run(3.0);
  ASSERT_TRUE(scene.world().getSoftBodyError().empty()) << scene.world().getSoftBodyError();
  const Model& model = soft->model();
  double lowest_node = 1e300;
  for (int n = 0; n < model.num_nodes(); ++n) lowest_node = std::min(lowest_node, soft->state().positions(2, n));
  double lowest_vertex = 1e300;
  for (int v = 0; v < soft->surface_vertices().cols(); ++v)
    lowest_vertex = std::min(lowest_vertex, soft->surface_vertices()(2, v));
  const double rms_speed = std::sqrt(2.0 * kinetic_energy(model, soft->state()) / model.total_mass());
  const double weight = model.total_mass() * 9.81;
  const double ground = -scene.world().getContactWrench(floor).force.z();
  std::printf(
      "8-vertex surface: %d contact vertices, lowest node %.3f mm, lowest contact vertex %.4f mm, rms speed %.2e m/s, "
      "ground %.4f N for a weight of %.4f N\n",
      static_cast<int>(soft->surface_vertices().cols()), 1e3 * lowest_node, 1e3 * lowest_vertex, rms_speed, ground,
      weight);
  EXPECT_GT(lowest_node, -0.1 * 0.008) << "no cell sinks through the ground (3.3 mm with contact points every 2 cells)";
  EXPECT_GT(lowest_vertex, -1e-5);
  EXPECT_LT(rms_speed, 1e-3);
  EXPECT_NEAR(ground, weight, 0.01 * weight);
}

// Where a ray from `from` along `direction` first meets the body's surface [m], if within `length`.
double surface_distance_along(const bullet::SoftBody& soft, const Eigen::Vector3d& from,
                              const Eigen::Vector3d& direction, double length) {
  const std::optional<bullet::SoftBody::RayHit> hit = soft.ray_test(from, from + length * direction.normalized());
  return hit ? hit->fraction * length : std::numeric_limits<double>::infinity();
}

// A 5 mm probe (a kinematic capsule of 2.5 mm radius) pressed 1 cm into a 9.6 cm cube of 5 kPa
// tissue, base bonded, and dragged 4 cm across it at 2 cm/s, friction 0.3, at Bullet's 1/60 s
// steps. The surface's triangles (8 mm squares cut in two) are wider than the probe, so its
// vertices alone could not hold it: until round tools met the whole surface it slipped between
// them and under the surface, and its force fell to nothing. The tissue's surface must stay
// outside the probe, within 0.5 mm (the contact issue's target), seen by rays cast from the
// probe's core (the plugin's picking, not its contact code), and the force must never fall
// below half its value a step before.
TEST(SoftTissue, AProbeThinnerThanTheSurfaceTrianglesNeverSlipsInside) {
  test::BulletScene scene;
  btRigidBody* floor = scene.add_floor();
  bullet::SoftBodySettings settings = tissue_cube(5e3, 12, 12);
  settings.contact.friction = 0.3;
  bullet::SoftBody* soft = scene.add_soft(settings);
  ASSERT_NE(soft, nullptr);
  ASSERT_TRUE(soft->anchor_box(floor, Eigen::Vector3d(-1, -1, -1e-6), Eigen::Vector3d(1, 1, 1e-6)).ok());
  scene.run(0.5);  // settles under its own weight first
  ASSERT_TRUE(scene.world().getSoftBodyError().empty()) << scene.world().getSoftBodyError();

  const double radius = 0.0025, length = 0.1;
  const double top = soft->state().positions(2, soft->model().node_at({6, 6, 12}));
  // the tip's centre (a radius above the tip) over time: press, hold, drag; off the grid's lines
  const auto tip_centre = [&](double t) {
    const double depth = std::min(t / 0.5, 1.0) * 0.01;
    const double along = std::clamp((t - 0.75) * 0.02, 0.0, 0.04);
    return Eigen::Vector3d(-0.02 + along, 0.0013, top + radius - depth);
  };
  // it starts where it touches: the world meets rigid bodies that start a step near the tissue
  const Eigen::Vector3d start = tip_centre(0.0);
  btRigidBody* probe =
      scene.add_rigid(new btCapsuleShapeZ(static_cast<btScalar>(radius), static_cast<btScalar>(length - 2 * radius)),
                      0.0, test::at(start.x(), start.y(), start.z() + 0.5 * length - radius), true);
  const double step = 1.0 / 60.0;
  const double allowed = std::max(0.5e-3, 0.1 * radius);
  std::vector<Eigen::Vector3d> directions;
  for (int i = -1; i <= 1; ++i) {
    for (int j = -1; j <= 1; ++j) {
      for (int k = -1; k <= 1; ++k) {
        if (i != 0 || j != 0 || k != 0) directions.push_back(Eigen::Vector3d(i, j, k).normalized());
      }
    }
  }
  double deepest = 0.0, deepest_reported = 0.0, previous_force = 0.0, least_drag_force = 1e300;
  int drops = 0;
  for (int n = 1; n <= static_cast<int>(std::lround(2.75 / step)); ++n) {
    const double t = n * step;
    const Eigen::Vector3d centre = tip_centre(t);
    probe->setWorldTransform(test::at(centre.x(), centre.y(), centre.z() + 0.5 * length - radius));
    scene.world().stepSimulation(static_cast<btScalar>(step), 1, static_cast<btScalar>(step));
    ASSERT_TRUE(scene.world().getSoftBodyError().empty()) << "t = " << t << ": " << scene.world().getSoftBodyError();
    // the surface's distance from the core, at the tip's centre and 1 cm up the shaft
    for (const Eigen::Vector3d& d : directions) {
      deepest = std::max(deepest, radius - surface_distance_along(*soft, centre, d, 2 * radius));
      if (d.z() == 0.0) {
        deepest = std::max(deepest,
                           radius - surface_distance_along(*soft, centre + Eigen::Vector3d(0, 0, 0.01), d, 2 * radius));
      }
    }
    const bullet::ContactWrench wrench = scene.world().getContactWrench(probe);
    deepest_reported = std::max(deepest_reported, wrench.penetration);
    const double force = wrench.force.norm();
    if (t > 0.3 && force < 0.5 * previous_force) ++drops;
    if (t > 0.75) least_drag_force = std::min(least_drag_force, force);
    previous_force = force;
  }
  std::printf(
      "probe: the surface reaches %.3f mm into it at most (the plugin reports %.3f mm); %d steps lost half "
      "the force; the drag's least force %.3f N, last %.3f N\n",
      1e3 * deepest, 1e3 * deepest_reported, drops, least_drag_force, previous_force);
  EXPECT_LT(deepest, allowed);
  EXPECT_LT(deepest_reported, allowed);
  EXPECT_NEAR(deepest_reported, deepest, 0.2e-3) << "the reported penetration is the one the rays see";
  EXPECT_EQ(drops, 0);
  EXPECT_GT(least_drag_force, 0.1) << "pressed 1 cm into 5 kPa tissue, the probe always feels it";
}

}  // namespace
}  // namespace cubespring
