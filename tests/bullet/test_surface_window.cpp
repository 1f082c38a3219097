// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The contact surface's window (plugins/bullet/src/surface_window.h): while it holds, no vertex or
// triangle left out of it has come within reach of a rigid body's box, against brute force over
// random motions of the nodes and the boxes (each body's own part of it too); and a vertex's
// normal as vertex_normals() gives it.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "cubespring/embedding.h"
#include "surface_topology.h"
#include "surface_window.h"

namespace cubespring::bullet {
namespace {

// A wavy sheet of n x n vertices over [0, size]^2, two triangles a square, counter-clockwise from
// above. Each vertex hangs from two nodes: w times one plus (1 - w) times the next, w = 1.5 for
// some (extrapolated, as a visual vertex outside its cell is), so a vertex moves up to
// `spread` = 2 times as far as its nodes.
struct Sheet {
  Eigen::Matrix3Xd nodes;
  std::vector<Eigen::Vector2i> hang;  // per vertex: its two nodes
  std::vector<double> weight;         // of the first
  Eigen::Matrix3Xi triangles;
  double spread = 0.0;

  Eigen::Matrix3Xd vertices() const {
    Eigen::Matrix3Xd v(3, static_cast<Eigen::Index>(hang.size()));
    for (std::size_t i = 0; i < hang.size(); ++i) {
      v.col(static_cast<Eigen::Index>(i)) =
          weight[i] * nodes.col(hang[i][0]) + (1.0 - weight[i]) * nodes.col(hang[i][1]);
    }
    return v;
  }
};

Sheet wavy_sheet(int n, double size) {
  Sheet sheet;
  const int vertices = n * n;
  sheet.nodes.resize(3, vertices + 1);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const double x = size * i / (n - 1), y = size * j / (n - 1);
      sheet.nodes.col(j * n + i) = Eigen::Vector3d(x, y, 0.01 * std::sin(40.0 * x) * std::cos(30.0 * y));
    }
  }
  sheet.nodes.col(vertices) = sheet.nodes.col(0);
  for (int v = 0; v < vertices; ++v) {
    // extrapolated vertices hang from themselves and the next node: at w = 1.5 they sit half a
    // step beyond
    sheet.hang.emplace_back(v, v + 1);
    sheet.weight.push_back(v % 7 == 0 ? 1.5 : 1.0);
  }
  sheet.spread = 2.0;  // |1.5| + |-0.5|
  sheet.triangles.resize(3, 2 * (n - 1) * (n - 1));
  int t = 0;
  for (int j = 0; j + 1 < n; ++j) {
    for (int i = 0; i + 1 < n; ++i) {
      const int a = j * n + i, b = a + 1, c = a + n, d = c + 1;
      sheet.triangles.col(t++) = Eigen::Vector3i(a, b, d);
      sheet.triangles.col(t++) = Eigen::Vector3i(a, d, c);
    }
  }
  return sheet;
}

Eigen::AlignedBox3d grown(const ContactBox& box) {
  const Eigen::Vector3d by = Eigen::Vector3d::Constant(box.reach);
  return {box.box.min() - by, box.box.max() + by};
}

// Brute force: what the window must hold for the contact tests to see what a loop over the whole
// surface would: every vertex within reach of a box with the triangles around it (its normal),
// every triangle within reach with the triangles around its corners (their pseudonormals), each
// with its corners.
::testing::AssertionResult window_covers(const SurfaceWindow& window, const Eigen::Matrix3Xd& vertices,
                                         const Eigen::Matrix3Xi& triangles, const SurfaceTopology& topology,
                                         const std::vector<ContactBox>& boxes) {
  std::vector<char> vertex_in(static_cast<std::size_t>(vertices.cols()), 0);
  std::vector<char> triangle_in(static_cast<std::size_t>(triangles.cols()), 0);
  for (const int v : window.vertices()) vertex_in[static_cast<std::size_t>(v)] = 1;
  for (const int t : window.triangles()) triangle_in[static_cast<std::size_t>(t)] = 1;
  const auto triangle_complete = [&](int t) {
    return triangle_in[static_cast<std::size_t>(t)] && vertex_in[static_cast<std::size_t>(triangles(0, t))] &&
           vertex_in[static_cast<std::size_t>(triangles(1, t))] && vertex_in[static_cast<std::size_t>(triangles(2, t))];
  };
  for (const ContactBox& box : boxes) {
    const Eigen::AlignedBox3d reach = grown(box);
    for (Eigen::Index v = 0; v < vertices.cols(); ++v) {
      if (!reach.contains(vertices.col(v))) continue;
      if (!vertex_in[static_cast<std::size_t>(v)])
        return ::testing::AssertionFailure() << "vertex " << v << " left out";
      for (int k = topology.vertex_offset[static_cast<std::size_t>(v)];
           k < topology.vertex_offset[static_cast<std::size_t>(v) + 1]; ++k) {
        const int t = topology.vertex_triangle[static_cast<std::size_t>(k)];
        if (!triangle_complete(t)) return ::testing::AssertionFailure() << "triangle " << t << " around vertex " << v;
      }
    }
    for (Eigen::Index t = 0; t < triangles.cols(); ++t) {
      Eigen::AlignedBox3d bounds(vertices.col(triangles(0, t)));
      bounds.extend(vertices.col(triangles(1, t))).extend(vertices.col(triangles(2, t)));
      if (!reach.intersects(bounds)) continue;
      if (!triangle_complete(static_cast<int>(t)))
        return ::testing::AssertionFailure() << "triangle " << t << " left out";
      // a corner's pseudonormal reads the triangles around it
      for (int corner = 0; corner < 3; ++corner) {
        const int v = triangles(corner, t);
        for (int k = topology.vertex_offset[static_cast<std::size_t>(v)];
             k < topology.vertex_offset[static_cast<std::size_t>(v) + 1]; ++k) {
          const int around = topology.vertex_triangle[static_cast<std::size_t>(k)];
          if (!triangle_complete(around)) {
            return ::testing::AssertionFailure() << "triangle " << around << " around corner " << v << " of " << t;
          }
        }
      }
    }
  }
  return ::testing::AssertionSuccess();
}

TEST(SurfaceWindow, WhileItHoldsNothingLeftOutHasComeWithinReach) {
  const Sheet sheet = wavy_sheet(30, 0.1);
  const SurfaceTopology topology = surface_topology(sheet.vertices(), sheet.triangles);
  const double margin = 0.004;
  SurfaceWindow window(margin, sheet.spread);
  // a probe's box over the middle and a table's just under the sheet
  const ContactBox probe{
      &sheet, Eigen::AlignedBox3d(Eigen::Vector3d(0.045, 0.045, 0.0), Eigen::Vector3d(0.05, 0.05, 0.05)), 0.003};
  const ContactBox table{&topology, Eigen::AlignedBox3d(Eigen::Vector3d(-1, -1, -0.2), Eigen::Vector3d(1, 1, -0.012)),
                         0.0};
  const std::vector<ContactBox> chosen_boxes{probe, table};
  window.choose(sheet.nodes, sheet.vertices(), sheet.triangles, topology, chosen_boxes);
  ASSERT_TRUE(window.holds(chosen_boxes));
  ASSERT_TRUE(window_covers(window, sheet.vertices(), sheet.triangles, topology, chosen_boxes));
  // each body's part is what a window of its box alone takes, and the window is their union
  std::vector<int> all_vertices, all_triangles;
  for (const ContactBox& box : chosen_boxes) {
    SurfaceWindow alone(margin, sheet.spread);
    alone.choose(sheet.nodes, sheet.vertices(), sheet.triangles, topology, {box});
    EXPECT_EQ(window.vertices_near(box.object), alone.vertices());
    EXPECT_EQ(window.triangles_near(box.object), alone.triangles());
    all_vertices.insert(all_vertices.end(), alone.vertices().begin(), alone.vertices().end());
    all_triangles.insert(all_triangles.end(), alone.triangles().begin(), alone.triangles().end());
  }
  for (std::vector<int>* list : {&all_vertices, &all_triangles}) {
    std::sort(list->begin(), list->end());
    list->erase(std::unique(list->begin(), list->end()), list->end());
  }
  EXPECT_EQ(window.vertices(), all_vertices);
  EXPECT_EQ(window.triangles(), all_triangles);
  EXPECT_LT(window.vertices_near(&sheet).size(), window.vertices().size() / 2);  // the probe's part is small
  EXPECT_TRUE(window.vertices_near(&margin).empty());                            // a body with no box
  EXPECT_TRUE(window.bounds_near(&margin).isEmpty());
  // with nothing moved, a part's bounds are its vertices' own, and they stand where they were
  EXPECT_EQ(window.vertex_travel(), 0.0);
  for (const ContactBox& box : chosen_boxes) {
    Eigen::AlignedBox3d exact;
    for (const int v : window.vertices_near(box.object)) {
      exact.extend(sheet.vertices().col(v));
      ASSERT_EQ(window.chosen_position(v), sheet.vertices().col(v));
    }
    EXPECT_TRUE(window.bounds_near(box.object).isApprox(exact));
  }
  {
    // chosen again for fewer boxes, in another order: no part is left from the first choice
    SurfaceWindow again = window;
    again.choose(sheet.nodes, sheet.vertices(), sheet.triangles, topology, {table});
    SurfaceWindow alone(margin, sheet.spread);
    alone.choose(sheet.nodes, sheet.vertices(), sheet.triangles, topology, {table});
    EXPECT_TRUE(again.vertices_near(&sheet).empty());
    EXPECT_TRUE(again.triangles_near(&sheet).empty());
    EXPECT_EQ(again.vertices_near(&topology), alone.vertices());
    EXPECT_EQ(again.vertices(), alone.vertices());
    again.choose(sheet.nodes, sheet.vertices(), sheet.triangles, topology, {table, probe});
    EXPECT_EQ(again.vertices(), window.vertices());
    EXPECT_EQ(again.vertices_near(&sheet), window.vertices_near(&sheet));
  }
  // a part of the surface, not all of it
  EXPECT_LT(window.vertices().size(), 900u / 2);
  EXPECT_GT(window.vertices().size(), 20u);

  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int held = 0, let_go = 0;
  for (int trial = 0; trial < 400; ++trial) {
    // the nodes and the probe move by up to twice the margin, in a random mix
    const double node_scale = margin * (trial % 20) / 10.0;
    const double box_scale = margin * (trial % 11) / 10.0;
    Sheet moved = sheet;
    for (Eigen::Index n = 0; n < moved.nodes.cols(); ++n) {
      moved.nodes.col(n) += node_scale / std::sqrt(3.0) * Eigen::Vector3d(unit(random), unit(random), unit(random));
    }
    ContactBox probe_now = probe;
    probe_now.box.translate(box_scale / std::sqrt(3.0) * Eigen::Vector3d(unit(random), unit(random), unit(random)));
    const std::vector<ContactBox> boxes{probe_now, table};
    SurfaceWindow copy = window;
    copy.note_moved(moved.nodes);
    if (!copy.holds(boxes)) {
      ++let_go;
      continue;
    }
    ++held;
    ASSERT_TRUE(window_covers(copy, moved.vertices(), moved.triangles, topology, boxes)) << "trial " << trial;
    // a test that skips a vertex because it was too far at the choice to have come within reach
    // since, and one that uses a part's bounds without reading its vertices, miss none
    const Eigen::Matrix3Xd now = moved.vertices();
    for (const int v : copy.vertices()) {
      ASSERT_LE((now.col(v) - copy.chosen_position(v)).norm(), copy.vertex_travel() * (1.0 + 1e-12))
          << "trial " << trial << ", vertex " << v;
    }
    for (const ContactBox& box : boxes) {
      const Eigen::AlignedBox3d bounds = copy.bounds_near(box.object);
      for (const int v : copy.vertices_near(box.object)) {
        ASSERT_TRUE(bounds.contains(now.col(v))) << "trial " << trial << ", vertex " << v;
      }
    }
    // what a test against one body reads, its part (the choice of its box alone, above), covers
    // that body's reach as well
    for (std::size_t b = 0; b < boxes.size(); ++b) {
      SurfaceWindow part(margin, sheet.spread);
      part.choose(sheet.nodes, sheet.vertices(), sheet.triangles, topology, {chosen_boxes[b]});
      ASSERT_EQ(copy.vertices_near(boxes[b].object), part.vertices());
      ASSERT_EQ(copy.triangles_near(boxes[b].object), part.triangles());
      ASSERT_TRUE(window_covers(part, moved.vertices(), moved.triangles, topology, {boxes[b]}))
          << "trial " << trial << ", box " << b;
    }
  }
  // both verdicts were reached: the test saw windows that hold and windows that had to be chosen again
  EXPECT_GT(held, 50);
  EXPECT_GT(let_go, 50);
}

TEST(SurfaceWindow, ANodeMovedByTheMarginOrABoxOfAnotherBodyEndsIt) {
  const Sheet sheet = wavy_sheet(10, 0.1);
  const SurfaceTopology topology = surface_topology(sheet.vertices(), sheet.triangles);
  SurfaceWindow window(0.004, 1.0);
  EXPECT_FALSE(window.holds({}));  // nothing chosen yet
  const ContactBox probe{&sheet,
                         Eigen::AlignedBox3d(Eigen::Vector3d(0.04, 0.04, 0.0), Eigen::Vector3d(0.05, 0.05, 0.05)), 0.0};
  window.choose(sheet.nodes, sheet.vertices(), sheet.triangles, topology, {probe});
  Eigen::Matrix3Xd nodes = sheet.nodes;
  nodes(2, 5) += 0.0039;
  window.note_moved(nodes, {5});
  EXPECT_TRUE(window.holds({probe}));
  nodes(2, 5) += 0.0002;  // 4.1 mm in all
  window.note_moved(nodes, {5});
  EXPECT_FALSE(window.holds({probe}));

  window.choose(sheet.nodes, sheet.vertices(), sheet.triangles, topology, {probe});
  const ContactBox other{&topology, probe.box, 0.0};
  EXPECT_FALSE(window.holds({probe, other}));  // a body the choice did not see
  EXPECT_TRUE(window.holds({}));               // a body that left: fewer boxes, nothing new within reach
  ContactBox farther = probe;
  farther.reach = 0.005;  // reaching farther than its choice counts as the box growing
  EXPECT_FALSE(window.holds({farther}));
  ContactBox round = probe;
  round.read_whole = true;  // the same body now read whole (its shape swapped for a round one)
  EXPECT_FALSE(window.holds({round}));
}

TEST(SurfaceTopology, OneVertexNormalIsVertexNormalsBitForBit) {
  Sheet sheet = wavy_sheet(12, 0.1);
  std::mt19937 random(3);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (Eigen::Index n = 0; n < sheet.nodes.cols(); ++n)
    sheet.nodes.col(n) += 0.003 * Eigen::Vector3d(unit(random), unit(random), unit(random));
  const Eigen::Matrix3Xd vertices = sheet.vertices();
  const SurfaceTopology topology = surface_topology(vertices, sheet.triangles);
  Eigen::Matrix3Xd all;
  vertex_normals(vertices, sheet.triangles, all);
  for (Eigen::Index v = 0; v < vertices.cols(); ++v) {
    const Eigen::Vector3d one = vertex_normal(topology, vertices, sheet.triangles, static_cast<int>(v));
    for (int axis = 0; axis < 3; ++axis) ASSERT_EQ(one[axis], all(axis, v)) << "vertex " << v;  // the same bits
  }
}

}  // namespace
}  // namespace cubespring::bullet
