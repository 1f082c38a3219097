// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Voxelizing: volumes of closed primitives against their own enclosed volume, symmetry, the same
// cells for damaged copies, parts, connectivity, counts against build_model, and bad input.
#include <algorithm>
#include <cmath>
#include <set>
#include <tuple>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "cubespring/model.h"
#include "cubespring/shapes.h"
#include "cubespring/surface_repair.h"
#include "cubespring/voxelize.h"
#include "mesh_edits.h"

namespace cubespring {
namespace {

using CellSet = std::set<std::tuple<int, int, int>>;

// Cells in world grid units (grid index plus the origin's index), comparable across grids.
CellSet world_cells(const Voxelization& v) {
  const Eigen::Vector3i offset = (v.origin.array() / v.cell_size.array()).round().cast<int>();
  CellSet cells;
  for (const Eigen::Vector3i& c : v.cells) {
    const Eigen::Vector3i w = c + offset;
    cells.emplace(w.x(), w.y(), w.z());
  }
  return cells;
}

Voxelization voxelize_ok(const TriangleMesh& mesh, const VoxelizeOptions& options) {
  Result<Voxelization> v = voxelize(mesh, options);
  EXPECT_TRUE(v.ok()) << v.message();
  return v.ok() ? std::move(v).value() : Voxelization{};
}

VoxelizeOptions across(int cells) {
  VoxelizeOptions options;
  options.cells_across = cells;
  return options;
}

VoxelizeOptions cell_size(double h) {
  VoxelizeOptions options;
  options.cell_size = Eigen::Vector3d::Constant(h);
  return options;
}

double closed_volume(const TriangleMesh& mesh) { return signed_volume(mesh, 0, mesh.num_triangles()); }

// A unit cube turned off the grid's axes (an axis-aligned one is exact or off by whole layers),
// its faces split so that 1% of its triangles is a few of them.
TriangleMesh rotated_cube() {
  TriangleMesh cube = test::subdivide(box_mesh(Eigen::Vector3d::Constant(-0.5), Eigen::Vector3d::Constant(0.5)), 3);
  const Eigen::Matrix3d turn =
      (Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()))
          .toRotationMatrix();
  cube.vertices = (turn * cube.vertices).colwise() + Eigen::Vector3d(0.011, 0.023, -0.017);
  return cube;
}

struct Primitive {
  const char* name;
  TriangleMesh mesh;
};

std::vector<Primitive> primitives() {
  return {
      {"sphere", sphere_mesh(1.0, 4)},
      {"torus", torus_mesh(1.0, 0.4, 64, 32, Eigen::Vector3d(0.013, -0.021, 0.007))},
      {"cube", rotated_cube()},
      // 0.4 thick at 20 cells across 2.0: a shell 4 cells thick
      {"hollow shell", hollow_mesh(sphere_mesh(1.0, 4), sphere_mesh(0.6, 4))},
  };
}

TEST(Voxelize, VolumeOfClosedPrimitivesWithinThreePercentAtTwentyCellsAcross) {
  for (const Primitive& p : primitives()) {
    const Voxelization v = voxelize_ok(p.mesh, across(20));
    EXPECT_NEAR(v.mesh_volume, std::abs(closed_volume(p.mesh)), 1e-12) << p.name;
    EXPECT_LT(std::abs(v.relative_volume_difference()), 0.03)
        << p.name << ": voxel " << v.voxel_volume << " mesh " << v.mesh_volume;
    EXPECT_TRUE(v.surface.clean()) << p.name;
    EXPECT_EQ(v.undecided_cells, 0) << p.name;
    EXPECT_EQ(v.connectivity.islands, 0) << p.name;
  }
}

TEST(Voxelize, HollowShellKeepsItsCavity) {
  const Voxelization v = voxelize_ok(hollow_mesh(sphere_mesh(1.0, 4), sphere_mesh(0.6, 4)), across(20));
  const CellSet cells = world_cells(v);
  EXPECT_EQ(cells.count({0, 0, 0}), 0u);  // centre of the cavity
  EXPECT_EQ(cells.count({7, 0, 0}), 1u);  // centre 0.75 from the middle: in the wall
  const double shell = 4.0 / 3.0 * M_PI * (1.0 - 0.216);
  EXPECT_NEAR(v.voxel_volume, shell, 0.05 * shell);
}

TEST(Voxelize, SphereOnAGridNodeIsSymmetricUnderTheGridSymmetries) {
  const Voxelization v = voxelize_ok(sphere_mesh(1.0, 4), across(20));
  const CellSet cells = world_cells(v);
  ASSERT_FALSE(cells.empty());
  // cell i of the world grid spans [i, i+1): its mirror about the node 0 is -1 - i
  std::array<int, 3> permutation{0, 1, 2};
  int symmetries = 0;
  do {
    for (int mirror = 0; mirror < 8; ++mirror) {
      ++symmetries;
      for (const auto& [i, j, k] : cells) {
        std::array<int, 3> c{i, j, k};
        std::array<int, 3> image{};
        for (int axis = 0; axis < 3; ++axis) {
          const int value = c[static_cast<std::size_t>(permutation[static_cast<std::size_t>(axis)])];
          image[static_cast<std::size_t>(axis)] = ((mirror >> axis) & 1) ? -1 - value : value;
        }
        ASSERT_EQ(cells.count({image[0], image[1], image[2]}), 1u)
            << "mirror " << mirror << " permutation " << permutation[0] << permutation[1] << permutation[2];
      }
    }
  } while (std::next_permutation(permutation.begin(), permutation.end()));
  EXPECT_EQ(symmetries, 48);
}

TEST(Voxelize, FlippedAndDuplicatedTrianglesGiveTheSameCells) {
  for (const Primitive& p : primitives()) {
    const CellSet reference = world_cells(voxelize_ok(p.mesh, across(20)));
    const Voxelization all_flipped = voxelize_ok(test::flip_triangles(p.mesh, 1.0), across(20));
    EXPECT_EQ(world_cells(all_flipped), reference) << p.name << " all flipped";
    EXPECT_EQ(all_flipped.surface.flipped_triangles, p.mesh.num_triangles()) << p.name;
    const Voxelization some_flipped = voxelize_ok(test::flip_triangles(p.mesh, 0.1), across(20));
    EXPECT_EQ(world_cells(some_flipped), reference) << p.name << " 10% flipped";
    EXPECT_GT(some_flipped.surface.flipped_triangles, p.mesh.num_triangles() / 20) << p.name;
    EXPECT_LT(some_flipped.surface.flipped_triangles, p.mesh.num_triangles() / 5) << p.name;
    const Voxelization doubled = voxelize_ok(test::duplicate_triangles(p.mesh), across(20));
    EXPECT_EQ(world_cells(doubled), reference) << p.name << " duplicated";
    EXPECT_EQ(doubled.surface.duplicate_triangles, p.mesh.num_triangles()) << p.name;
  }
}

TEST(Voxelize, OnePercentOfTrianglesMissingChangesAtMostHalfAPercentOfCells) {
  for (const Primitive& p : primitives()) {
    const CellSet reference = world_cells(voxelize_ok(p.mesh, across(20)));
    const TriangleMesh holed = test::remove_triangles(p.mesh, 0.01);
    const Result<Voxelization> v = voxelize(holed, across(20));
    ASSERT_TRUE(v.ok()) << p.name << ": " << v.message();
    EXPECT_GT(v->surface.open_edges, 0) << p.name;
    EXPECT_FALSE(v->warnings.empty()) << p.name;
    const CellSet cells = world_cells(*v);
    std::vector<std::tuple<int, int, int>> different;
    std::set_symmetric_difference(cells.begin(), cells.end(), reference.begin(), reference.end(),
                                  std::back_inserter(different));
    EXPECT_LE(static_cast<double>(different.size()), 0.005 * static_cast<double>(reference.size()))
        << p.name << ": " << different.size() << " of " << reference.size() << " cells differ";
  }
}

TEST(Voxelize, VerticesRepeatedPerTriangleAreJoinedFirst) {
  // a triangle soup as STL files and simulators' own arrays give it
  const TriangleMesh sphere = sphere_mesh(1.0, 3);
  TriangleMesh soup;
  soup.vertices.resize(3, 3 * sphere.num_triangles());
  soup.triangles.resize(3, sphere.num_triangles());
  for (int t = 0; t < sphere.num_triangles(); ++t) {
    for (int c = 0; c < 3; ++c) {
      soup.vertices.col(3 * t + c) = sphere.vertices.col(sphere.triangles(c, t));
      soup.triangles(c, t) = 3 * t + c;
    }
  }
  const Voxelization v = voxelize_ok(test::flip_triangles(soup, 0.1), across(20));
  EXPECT_EQ(v.surface.open_edges, 0);
  EXPECT_EQ(world_cells(v), world_cells(voxelize_ok(sphere, across(20))));
}

TEST(Voxelize, CountsMatchTheBuiltModel) {
  // a 3 x 4 x 5 block of 0.1 m cells, faces between cell centres
  const Voxelization v =
      voxelize_ok(box_mesh(Eigen::Vector3d(0.02, 0.03, 0.01), Eigen::Vector3d(0.29, 0.38, 0.48)), cell_size(0.1));
  ASSERT_EQ(v.cells.size(), 60u);
  const Result<Model> model = build_model(lattice_from_voxels(v, {Material{}}));
  ASSERT_TRUE(model.ok()) << model.message();
  EXPECT_EQ(v.nodes, model->num_nodes());
  EXPECT_EQ(v.springs, model->num_springs());
  EXPECT_EQ(v.nodes, 4 * 5 * 6);
  EXPECT_GT(v.memory_estimate_bytes, 0u);
}

TEST(Voxelize, CoveredFractionRuleTakesCellsOverTheThreshold) {
  // [0, 0.23]^3 with 0.1 m cells: cells 0 and 1 fully in, cell 2 covered 30% along each axis,
  // which 4 samples per axis see as 1/4
  const TriangleMesh box = box_mesh(Eigen::Vector3d(0.001, 0.001, 0.001), Eigen::Vector3d(0.23, 0.23, 0.23));
  EXPECT_EQ(voxelize_ok(box, cell_size(0.1)).cells.size(), 8u);
  VoxelizeOptions options = cell_size(0.1);
  options.rule = CellRule::kCoveredFraction;
  options.samples_per_axis = 4;
  options.min_covered_fraction = 0.25;
  EXPECT_EQ(voxelize_ok(box, options).cells.size(), 8u + 3u * 4u);  // faces in, edges (1/16) out
  options.min_covered_fraction = 0.5;
  EXPECT_EQ(voxelize_ok(box, options).cells.size(), 8u);
}

TEST(Voxelize, InnerPartWinsAndIsNotCountedTwiceInTheVolume) {
  TriangleMesh organ = sphere_mesh(1.0, 4);
  organ.parts[0].name = "organ";
  TriangleMesh tumour = sphere_mesh(0.35, 3, Eigen::Vector3d(0.3, 0.0, 0.0));
  tumour.parts[0].name = "tumour";
  const Voxelization v = voxelize_ok(combine_meshes(organ, tumour), across(20));
  ASSERT_EQ(v.parts.size(), 2u);
  EXPECT_EQ(v.parts[0].name, "organ");
  EXPECT_EQ(v.parts[1].name, "tumour");
  EXPECT_GT(v.parts[1].cells, 0);
  // every cell inside the tumour's own voxelization is a tumour cell here
  EXPECT_NEAR(v.parts[1].cells * v.cell_size.prod(), v.parts[1].voxel_volume, 1e-12);
  EXPECT_EQ(v.parts[0].cells + v.parts[1].cells, static_cast<int>(v.cells.size()));
  EXPECT_NEAR(v.mesh_volume, closed_volume(organ), 1e-12);
  const Eigen::Vector3d centre = v.origin + v.cell_size.cwiseProduct(Eigen::Vector3d::Constant(0.5));
  for (std::size_t c = 0; c < v.cells.size(); ++c) {
    const Eigen::Vector3d x = centre + v.cells[c].cast<double>().cwiseProduct(v.cell_size);
    const double distance = (x - Eigen::Vector3d(0.3, 0, 0)).norm();
    if (distance < 0.3) {
      EXPECT_EQ(v.cell_part[c], 1);
    } else if (distance > 0.4) {
      EXPECT_EQ(v.cell_part[c], 0);
    }
  }
}

TEST(Voxelize, OverlappingPartsGiveTheOverlapToTheSmallerPart) {
  const TriangleMesh big = sphere_mesh(1.0, 4);
  const TriangleMesh small = sphere_mesh(0.5, 4, Eigen::Vector3d(0.9, 0.0, 0.0));
  const Voxelization v = voxelize_ok(combine_meshes(big, small), cell_size(0.1));
  const Voxelization alone = voxelize_ok(big, cell_size(0.1));
  EXPECT_GT(v.cells.size(), alone.cells.size());  // the union sticks out
  EXPECT_NEAR(v.parts[1].cells * v.cell_size.prod(), v.parts[1].voxel_volume, 1e-12);
  // the mesh volume counts both: neither lies inside the other
  EXPECT_NEAR(v.mesh_volume, closed_volume(big) + closed_volume(small), 1e-12);
}

TEST(Voxelize, PartsSharingEdgesAreOneSolid) {
  // a box whose faces are split between two parts (a tool split by material): neither part
  // encloses anything alone
  TriangleMesh box = test::subdivide(box_mesh(Eigen::Vector3d(0.01, 0.02, 0.03), Eigen::Vector3d(0.47, 0.38, 0.29)), 1);
  box.parts = {MeshPart{"handle", "steel", 0, 20}, MeshPart{"grip", "rubber", 20, 28}};
  const Voxelization v = voxelize_ok(box, cell_size(0.1));
  EXPECT_EQ(v.surface.open_edges, 0);
  EXPECT_EQ(v.cells.size(), 5u * 4u * 3u);
  EXPECT_EQ(v.parts[0].merged_into, -1);
  EXPECT_EQ(v.parts[1].merged_into, 0);
  EXPECT_EQ(v.parts[0].cells, 60);
  EXPECT_EQ(v.parts[1].cells, 0);
  EXPECT_NEAR(v.mesh_volume, 0.46 * 0.36 * 0.26, 1e-12);
}

TEST(Voxelize, ReportsHingesBallJointsAndIslands) {
  const TriangleMesh a = box_mesh(Eigen::Vector3d(0.01, 0.01, 0.01), Eigen::Vector3d(0.19, 0.19, 0.19));
  const auto with = [&](const Eigen::Vector3d& lower, const Eigen::Vector3d& upper) {
    return combine_meshes(a, box_mesh(lower, upper));
  };
  // a second 2x2x2 block sharing an edge line (2 cell pairs), a corner (1 pair), nothing
  const Voxelization hinge = voxelize_ok(with({0.21, 0.21, 0.01}, {0.39, 0.39, 0.19}), cell_size(0.1));
  EXPECT_EQ(hinge.connectivity.edge_only_contacts, 2);
  EXPECT_EQ(hinge.connectivity.corner_only_contacts, 0);
  EXPECT_EQ(hinge.connectivity.islands, 1);  // an edge is not a face: two face-connected pieces
  const Voxelization ball = voxelize_ok(with({0.21, 0.21, 0.21}, {0.39, 0.39, 0.39}), cell_size(0.1));
  EXPECT_EQ(ball.connectivity.corner_only_contacts, 1);
  EXPECT_EQ(ball.connectivity.edge_only_contacts, 0);
  const TriangleMesh apart = with({0.51, 0.01, 0.01}, {0.59, 0.09, 0.09});  // one cell, apart
  const Voxelization island = voxelize_ok(apart, cell_size(0.1));
  EXPECT_EQ(island.connectivity.islands, 1);
  EXPECT_EQ(island.connectivity.island_cells, 1);
  EXPECT_EQ(island.cells.size(), 9u);
  VoxelizeOptions drop = cell_size(0.1);
  drop.drop_islands = true;
  const Voxelization dropped = voxelize_ok(apart, drop);
  EXPECT_EQ(dropped.cells.size(), 8u);
  EXPECT_EQ(dropped.connectivity.dropped_cells, 1);
  EXPECT_EQ(dropped.parts[1].cells, 0);
}

TEST(Voxelize, RefusesBadInputWithTheValueAtFault) {
  const TriangleMesh sphere = sphere_mesh(1.0, 3);
  const auto error = [](const TriangleMesh& mesh, const VoxelizeOptions& options) {
    const Result<Voxelization> v = voxelize(mesh, options);
    EXPECT_FALSE(v.ok());
    return v.message();
  };
  EXPECT_NE(error(sphere, cell_size(0.0)).find("cell size"), std::string::npos);
  EXPECT_NE(error(sphere, cell_size(-0.1)).find("-0.1"), std::string::npos);
  EXPECT_NE(error(sphere, across(-3)).find("-3"), std::string::npos);
  EXPECT_NE(error(TriangleMesh{}, across(10)).find("no triangles"), std::string::npos);
  // a flat square seen from both sides: closed, but no volume
  TriangleMesh flat = box_mesh(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1));
  flat.vertices.row(2).setZero();
  EXPECT_NE(error(flat, across(10)).find("no volume"), std::string::npos);
  TriangleMesh nan = sphere;
  nan.vertices(1, 5) = std::nan("");
  EXPECT_NE(error(nan, across(10)).find("vertex 5"), std::string::npos);
  TriangleMesh bad_index = sphere;
  bad_index.triangles(2, 7) = 100000;
  EXPECT_NE(error(bad_index, across(10)).find("100000"), std::string::npos);
  VoxelizeOptions small_limit = cell_size(0.001);
  small_limit.max_memory_bytes = 1000000;
  const std::string memory = error(sphere, small_limit);
  EXPECT_NE(memory.find("memory limit of 1 MB given: use a larger cell size"), std::string::npos) << memory;
  EXPECT_NE(memory.find("2002 x 2002 x 2002"), std::string::npos) << memory;
  // an absurd grid is refused before anything is allocated, whatever the limit
  VoxelizeOptions absurd = cell_size(1e-9);
  absurd.max_memory_bytes = ~std::uint64_t{0};
  EXPECT_FALSE(voxelize(sphere, absurd).ok());
  // 1336^3 cells, each axis short of the bound: more than int indices address, whatever the limit
  VoxelizeOptions past_int = cell_size(0.0015);
  past_int.max_memory_bytes = ~std::uint64_t{0};
  const std::string past_int_error = error(sphere, past_int);
  EXPECT_NE(past_int_error.find("more samples than int indices address"), std::string::npos) << past_int_error;
  // thinner than a cell
  EXPECT_NE(error(box_mesh(Eigen::Vector3d(0.01, 0.01, 0.01), Eigen::Vector3d(0.5, 0.5, 0.04)), cell_size(0.1))
                .find("thinner than a cell"),
            std::string::npos);
}

TEST(Voxelize, ASurfaceMostlyOpenCannotBeDecided) {
  const TriangleMesh torn = test::remove_triangles(sphere_mesh(1.0, 3), 0.5);
  const Result<Voxelization> v = voxelize(torn, across(20));
  ASSERT_FALSE(v.ok());
  EXPECT_NE(v.message().find("open edges"), std::string::npos) << v.message();
}

TEST(SurfaceRepair, CountsEachKindOfProblem) {
  TriangleMesh box = box_mesh(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1));
  EXPECT_TRUE(repair_surface(box).problems.clean());
  EXPECT_EQ(repair_surface(box).problems.components, 1);
  EXPECT_NEAR(repair_surface(box).solid_volume[0], 1.0, 1e-15);
  EXPECT_EQ(repair_surface(test::remove_triangles(box, 1.0 / 12.0)).problems.open_edges, 3);
  // a third triangle on edge (0, 1): non-manifold, and the edge's two other uses are no longer a pair
  TriangleMesh fin = box;
  fin.vertices.conservativeResize(3, 9);
  fin.vertices.col(8) = Eigen::Vector3d(0.5, -1.0, 0.0);
  fin.triangles.conservativeResize(3, 13);
  fin.triangles.col(12) = Eigen::Vector3i(0, 1, 8);
  fin.parts[0].triangle_count = 13;
  EXPECT_EQ(repair_surface(fin).problems.non_manifold_edges, 1);
  TriangleMesh degenerate = box;
  degenerate.triangles.col(3) = Eigen::Vector3i(0, 0, 1);
  EXPECT_EQ(repair_surface(degenerate).problems.degenerate_triangles, 1);
  const RepairedSurface flipped = repair_surface(test::flip_triangles(box, 1.0));
  EXPECT_EQ(flipped.problems.flipped_triangles, 12);
  EXPECT_NEAR(flipped.solid_volume[0], 1.0, 1e-15);
}

}  // namespace
}  // namespace cubespring
