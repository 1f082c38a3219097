// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <tuple>

#include <gtest/gtest.h>

#include "cubespring/model.h"
#include "cubespring/voxelize.h"
#include "test_support.h"

namespace cubespring {
namespace {

TEST(Model, BoxCounts) {
  const Model model = test::box_model({3, 2, 4}, Material{});
  EXPECT_EQ(model.num_nodes(), 4 * 3 * 5);
  EXPECT_EQ(model.num_cells(), 24);
  // unique edges along x: 3 * 3 * 5, along y: 4 * 2 * 5, along z: 4 * 3 * 4; plus 4 diagonals per cell
  EXPECT_EQ(model.num_springs(), 45 + 40 + 48 + 4 * 24);
}

TEST(Model, MassIsLumpedAnEighthPerCorner) {
  const Material m = test::notes_material(0.3);
  const Model model = test::box_model({3, 3, 3}, m);
  const double cell_mass = m.density * 1e-6;
  EXPECT_NEAR(model.total_mass(), m.density * 27e-6, 1e-15);
  EXPECT_NEAR(model.mass[model.node_at({0, 0, 0})], cell_mass / 8, 1e-18);  // corner
  EXPECT_NEAR(model.mass[model.node_at({1, 1, 1})], cell_mass, 1e-18);      // interior
  EXPECT_NEAR(model.mass[model.node_at({1, 0, 0})], cell_mass / 4, 1e-18);  // edge
}

TEST(Model, SharedEdgesSumTheirCellsStiffness) {
  const Model model = test::box_model({2, 2, 2}, test::notes_material(0.3));
  const double k_edge = 211.5384615384615;
  // the x-edge through the block's centre is shared by 4 cells, a boundary edge by 1
  for (int s = 0; s < model.num_springs(); ++s) {
    const auto& ends = model.spring_nodes[s];
    const Eigen::Vector3i a = model.node_grid_index[ends[0]];
    const Eigen::Vector3i b = model.node_grid_index[ends[1]];
    if ((b - a) != Eigen::Vector3i(1, 0, 0)) continue;
    const int cells = (a.y() == 1 ? 2 : 1) * (a.z() == 1 ? 2 : 1);
    EXPECT_NEAR(model.spring_stiffness[s], cells * k_edge, 1e-9) << a.transpose();
    EXPECT_EQ(model.spring_cell_offset[s + 1] - model.spring_cell_offset[s], cells);
  }
}

TEST(Model, TwoMaterialsKeepTheirOwnStiffness) {
  LatticeDesc desc = box_lattice({2, 1, 1}, Eigen::Vector3d::Constant(0.01), test::notes_material(0.3));
  Material stiff = test::notes_material(0.3);
  stiff.young_modulus = 4e5;
  desc.materials.push_back(stiff);
  desc.cell_material = {0, 1};
  Result<Model> model = build_model(desc);
  ASSERT_TRUE(model.ok()) << model.message();
  // the y-edges of the interface face carry one share of each material (k is proportional to E)
  const int a = model->node_at({1, 0, 0});
  const int b = model->node_at({1, 1, 0});
  for (int s = 0; s < model->num_springs(); ++s) {
    if (model->spring_nodes[s] == std::array<int, 2>{a, b}) {
      EXPECT_NEAR(model->spring_stiffness[s], 5 * 211.5384615384615, 1e-9);
    }
  }
}

TEST(Model, RejectsBadDescriptions) {
  LatticeDesc desc = box_lattice({1, 1, 1}, Eigen::Vector3d::Constant(0.01), Material{});
  desc.cells.push_back(desc.cells[0]);
  Result<Model> duplicate = build_model(desc);
  ASSERT_FALSE(duplicate.ok());
  EXPECT_NE(duplicate.message().find("listed twice"), std::string::npos);

  desc = box_lattice({1, 1, 1}, Eigen::Vector3d(0.01, -0.01, 0.01), Material{});
  Result<Model> negative = build_model(desc);
  ASSERT_FALSE(negative.ok());
  EXPECT_NE(negative.message().find("cell_size"), std::string::npos);

  desc = box_lattice({0, 1, 1}, Eigen::Vector3d::Constant(0.01), Material{});
  Result<Model> empty = build_model(desc);
  ASSERT_FALSE(empty.ok());
  EXPECT_NE(empty.message().find("no cells"), std::string::npos);

  desc = box_lattice({1, 1, 1}, Eigen::Vector3d::Constant(0.01), Material{});
  desc.materials[0].young_modulus = 0.0;
  Result<Model> soft = build_model(desc);
  ASSERT_FALSE(soft.ok());
  EXPECT_NE(soft.message().find("young_modulus"), std::string::npos);

  desc = box_lattice({1, 1, 1}, Eigen::Vector3d::Constant(0.01), Material{});
  desc.cell_material = {3};
  Result<Model> missing = build_model(desc);
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.message().find("material 3"), std::string::npos);

  // sides each fine, but a cell volume of 1e-360 m^3 underflows to 0
  desc = box_lattice({1, 1, 1}, Eigen::Vector3d::Constant(1e-120), Material{});
  Result<Model> vanishing = build_model(desc);
  ASSERT_FALSE(vanishing.ok());
  EXPECT_NE(vanishing.message().find("out of the range of double"), std::string::npos) << vanishing.message();
}

// Bodies too large to build are refused by their cell count before anything is allocated: past
// the int indices of their springs, or past a memory limit (the estimate of voxelize.h).
TEST(Model, RefusesALatticeTooLargeToBuild) {
  EXPECT_TRUE(check_lattice_size(1000).ok());
  const Status past_int = check_lattice_size(kMaxCells + 1);
  ASSERT_FALSE(past_int.ok());
  EXPECT_NE(past_int.message().find("at most " + std::to_string(kMaxCells)), std::string::npos) << past_int.message();
  const std::uint64_t thousand_cells = estimate_body_bytes(1000, 1000, 7000);
  EXPECT_TRUE(check_lattice_size(1000, thousand_cells).ok());
  const Status over = check_lattice_size(1001, thousand_cells);
  ASSERT_FALSE(over.ok());
  EXPECT_NE(over.message().find("1001 cells take about"), std::string::npos) << over.message();
  EXPECT_NE(over.message().find("memory limit"), std::string::npos) << over.message();
}

TEST(Model, AnyCellSetSharesNodes) {
  // an L of three cells: 8 + 4 + 4 nodes
  LatticeDesc desc;
  desc.cells = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  Result<Model> model = build_model(desc);
  ASSERT_TRUE(model.ok()) << model.message();
  EXPECT_EQ(model->num_nodes(), 16);
  EXPECT_EQ(model->node_at({2, 2, 0}), -1);
}

// Nodes are numbered along the axis the box is longest along (Model::major_axis) when the layers
// across it hold at least kMinMajorLayerNodes nodes, else along z; the axis after the major one
// is the fastest. Whatever the order, node_at finds every node, every spring runs from its lower
// node index to its higher, and a cell's diagonal k joins its corners k and 7 - k.
TEST(Model, NodesAreNumberedAlongTheLongAxisOfABigEnoughBox) {
  struct Case {
    Eigen::Vector3i cells;
    int major_axis;
  };
  // 21 x 16 x 16 nodes: layers across x of 256; 21 x 16 x 15: of 240, too few; ties go to z, then y
  for (const Case& c : {Case{{20, 15, 15}, 0}, Case{{20, 15, 14}, 2}, Case{{15, 20, 15}, 1}, Case{{15, 15, 20}, 2},
                        Case{{20, 20, 15}, 1}, Case{{20, 20, 20}, 2}}) {
    const Model model = test::box_model(c.cells, Material{});
    ASSERT_EQ(model.major_axis, c.major_axis) << c.cells.transpose();
    const int fast = (c.major_axis + 1) % 3, middle = (c.major_axis + 2) % 3;
    const auto order = [&](const Eigen::Vector3i& index) {
      return std::make_tuple(index[c.major_axis], index[middle], index[fast]);
    };
    for (int n = 0; n < model.num_nodes(); ++n) {
      ASSERT_EQ(model.node_at(model.node_grid_index[n]), n);
      if (n > 0) {
        ASSERT_LT(order(model.node_grid_index[n - 1]), order(model.node_grid_index[n])) << n;
      }
    }
    for (const auto& ends : model.spring_nodes) ASSERT_LT(ends[0], ends[1]);
    for (int cell = 0; cell < model.num_cells(); cell += 97) {
      for (int k = 0; k < 4; ++k) {
        std::array<int, 2> corners{model.cell_nodes[cell][k], model.cell_nodes[cell][7 - k]};
        std::sort(corners.begin(), corners.end());
        EXPECT_EQ(model.spring_nodes[model.cell_diagonals[cell][k]], corners) << cell << ", " << k;
      }
    }
  }
}

}  // namespace
}  // namespace cubespring
