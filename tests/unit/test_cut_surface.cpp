// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// A closed surface cut by removed cells stays closed and consistently oriented, keeps what lies
// outside them as it was, and encloses the solid less the removed cells' share of it.
#include <algorithm>
#include <array>
#include <map>
#include <random>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "closed_surface.h"
#include "cubespring/cut_surface.h"
#include "cubespring/shapes.h"

namespace cubespring {
namespace {

double volume(const TriangleMesh& mesh) {
  double six = 0.0;
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    six += mesh.vertices.col(mesh.triangles(0, t))
               .dot(mesh.vertices.col(mesh.triangles(1, t)).cross(mesh.vertices.col(mesh.triangles(2, t))));
  }
  return six / 6.0;
}

// The overlap of two boxes [m^3].
double overlap(const Eigen::Vector3d& lo_a, const Eigen::Vector3d& hi_a, const Eigen::Vector3d& lo_b,
               const Eigen::Vector3d& hi_b) {
  const Eigen::Vector3d size = (hi_a.cwiseMin(hi_b) - lo_a.cwiseMax(lo_b)).cwiseMax(0.0);
  return size.prod();
}

// A box whose faces cross the cells, cut by random cells in and around it: the volume it keeps
// is its own less each removed cell's overlap with it (exact for a box), and it stays closed.
TEST(CutSurface, ABoxLosesExactlyTheRemovedCellsShare) {
  const Eigen::Vector3d lo(0.0013, -0.0021, 0.0007), hi(0.0371, 0.0189, 0.0283);
  const TriangleMesh box = box_mesh(lo, hi);
  const Eigen::Vector3d origin(0, -0.005, 0), h = Eigen::Vector3d::Constant(0.005);
  std::mt19937 rng(7);
  for (int trial = 0; trial < 40; ++trial) {
    std::vector<Eigen::Vector3i> removed;
    std::uniform_int_distribution<int> x(0, 7), y(0, 5), z(0, 5);
    const int count = 1 + trial % 12;
    for (int i = 0; i < count; ++i) removed.emplace_back(x(rng), y(rng), z(rng));
    std::sort(removed.begin(), removed.end(), [](const Eigen::Vector3i& a, const Eigen::Vector3i& b) {
      return std::tie(a.x(), a.y(), a.z()) < std::tie(b.x(), b.y(), b.z());
    });
    removed.erase(std::unique(removed.begin(), removed.end()), removed.end());
    double expected = (hi - lo).prod();
    for (const Eigen::Vector3i& cell : removed) {
      const Eigen::Vector3d cell_lo = origin + cell.cast<double>().cwiseProduct(h);
      expected -= overlap(lo, hi, cell_lo, cell_lo + h);
    }
    const CutSurface cut = cut_surface(box, origin, h, removed);
    ASSERT_TRUE(test::closed_and_oriented(cut.mesh.triangles)) << "trial " << trial;
    EXPECT_NEAR(volume(cut.mesh), expected, 1e-5 * (hi - lo).prod()) << "trial " << trial;  // planes moved 1e-6 cell
    if (expected < (hi - lo).prod() - 1e-12) {
      EXPECT_GT(cut.cap_triangles, 0);
    }
  }
}

// A sphere (its triangles smaller than the cells) cut by a random stroke of cells and by random
// cells: closed and oriented after each, its vertices outside the removed cells where they were.
TEST(CutSurface, ASphereCutAnywhereStaysClosed) {
  const TriangleMesh sphere = sphere_mesh(0.03, 4);
  const Eigen::Vector3d origin = Eigen::Vector3d::Constant(-0.04), h = Eigen::Vector3d::Constant(0.006);
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> cell(4, 10);
  for (int trial = 0; trial < 30; ++trial) {
    std::vector<Eigen::Vector3i> removed;
    const Eigen::Vector3i start(cell(rng), cell(rng), cell(rng));
    for (int k = 0; k < 1 + trial % 8; ++k) removed.push_back(start + Eigen::Vector3i(k, 0, k / 2));
    const CutSurface cut = cut_surface(sphere, origin, h, removed);
    ASSERT_TRUE(test::closed_and_oriented(cut.mesh.triangles)) << "trial " << trial;
    EXPECT_LE(volume(cut.mesh), volume(sphere) * (1 + 1e-12));  // some strokes leave the sphere
    EXPECT_GT(volume(cut.mesh), volume(sphere) - static_cast<double>(removed.size()) * h.prod() * (1 + 1e-5));
    for (int v = 0; v < cut.mesh.num_vertices(); ++v) {
      const int source = cut.vertex_source[static_cast<std::size_t>(v)];
      if (source >= 0) {
        EXPECT_EQ(cut.mesh.vertices.col(v), sphere.vertices.col(source));
      }
    }
  }
  // nothing removed: the same surface
  const CutSurface none = cut_surface(sphere, origin, h, {});
  EXPECT_EQ(none.mesh.vertices, sphere.vertices);
  EXPECT_EQ(none.mesh.triangles, sphere.triangles);
  EXPECT_EQ(none.cap_triangles, 0);
}

// A body cut again and again: each cut from the surface it started with, by every cell removed so
// far (as the Bullet plugin does): closed and oriented after each, its volume falling as cells go,
// and a point two cuts both make (the same key) in the same place.
TEST(CutSurface, CutsThatGrowStayClosedAndKeepTheirPoints) {
  const TriangleMesh sphere = sphere_mesh(0.03, 3);
  const Eigen::Vector3d origin = Eigen::Vector3d::Constant(-0.04), h = Eigen::Vector3d::Constant(0.007);
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> cell(3, 8);
  std::vector<Eigen::Vector3i> removed;
  CutSurface last = cut_surface(sphere, origin, h, removed);
  for (int cut = 0; cut < 40; ++cut) {
    removed.emplace_back(cell(rng), cell(rng), cell(rng));
    const CutSurface next = cut_surface(sphere, origin, h, removed);
    ASSERT_TRUE(test::closed_and_oriented(next.mesh.triangles)) << "cut " << cut;
    EXPECT_LE(volume(next.mesh), volume(last.mesh) * (1 + 1e-9)) << "cut " << cut;
    std::map<std::array<long long, 4>, int> before;
    for (int v = 0; v < last.mesh.num_vertices(); ++v) before[last.vertex_keys[static_cast<std::size_t>(v)]] = v;
    int shared = 0;
    for (int v = 0; v < next.mesh.num_vertices(); ++v) {
      const auto found = before.find(next.vertex_keys[static_cast<std::size_t>(v)]);
      if (found == before.end()) continue;
      ++shared;
      EXPECT_LT((next.mesh.vertices.col(v) - last.mesh.vertices.col(found->second)).norm(), 1e-15) << "cut " << cut;
    }
    EXPECT_GT(shared, sphere.num_vertices() / 2);
    last = next;
  }
}

// A box on the grid's own planes (a lattice's outside), cut through its middle by a slab: two
// closed boxes, each its half's volume.
TEST(CutSurface, ASlabThroughABoxOnTheGridLeavesTwoClosedHalves) {
  const Eigen::Vector3d h = Eigen::Vector3d::Constant(0.01);
  const TriangleMesh box = box_mesh({0, 0, 0}, {0.05, 0.02, 0.02});
  std::vector<Eigen::Vector3i> slab;
  for (int j = 0; j < 2; ++j) {
    for (int k = 0; k < 2; ++k) slab.emplace_back(2, j, k);
  }
  const CutSurface cut = cut_surface(box, Eigen::Vector3d::Zero(), h, slab);
  EXPECT_TRUE(test::closed_and_oriented(cut.mesh.triangles));
  EXPECT_NEAR(volume(cut.mesh), 0.04 * 0.02 * 0.02, 1e-6 * 0.05 * 0.02 * 0.02);
}

}  // namespace
}  // namespace cubespring
