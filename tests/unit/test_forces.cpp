// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Forces: equilibrium at rest, energy gradient, invariance, balance, the correction's size and sign.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "cubespring/forces.h"
#include "forces/force_engine.h"
#include "forces/grid/grid_forces.h"
#include "forces/grid/grid_layout.h"
#include "test_support.h"

namespace cubespring {
namespace {

using test::elastic_forces;
using test::on_spring_lists;

// Gives the workspace the model's engine on the spring lists with one block of every node.
void use_one_block(const Model& model, ForceWorkspace& ws) {
  auto engine = std::make_shared<ForceEngine>(engine_with_grid(model, std::numeric_limits<double>::quiet_NaN(), ws));
  engine->blocks = ForceBlocks{{}, {}, model.num_nodes()};
  ws.engine = engine;
}

// Gives the workspace the model's engine (at the default fill) with this grid layout.
void use_grid(const Model& model, std::shared_ptr<const GridLayout> grid, ForceWorkspace& ws) {
  auto engine = std::make_shared<ForceEngine>(engine_with_grid(model, kDefaultMinGridFill, ws));
  engine->grid = std::move(grid);
  ws.engine = engine;
}
using test::notes_material;

// The middle cell of a body, and a state 1 mm and 0.1 m/s off rest at random; crushed: that
// cell's top face also pushed 1.5 cm down, through its bottom face, so the inversion recovery acts.
int middle_cell(const Model& model) { return model.num_cells() / 2; }
State disturbed_state(const Model& model, bool crushed) {
  State state = rest_state(model);
  state.positions = test::perturbed(model, 1e-3);
  state.velocities = test::perturbed(model, 0.1) - model.rest_positions;
  if (crushed) {
    for (int corner = 4; corner < 8; ++corner)
      state.positions(2, model.cell_nodes[middle_cell(model)][corner]) -= 0.015;
  }
  return state;
}

TEST(Forces, RestStateIsInEquilibrium) {
  const Model model = test::box_model({3, 2, 2}, notes_material(0.45));
  EXPECT_LT(elastic_forces(model, model.rest_positions).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_NEAR(elastic_energy(model, model.rest_positions), 0.0, 1e-20);
}

TEST(Forces, AreMinusTheEnergyGradient) {
  for (double nu : {0.0, 0.3, 0.49}) {
    const Model model = test::box_model({2, 2, 1}, notes_material(nu));
    const Eigen::Matrix3Xd x = test::perturbed(model, 1e-3);
    const Eigen::Matrix3Xd f = elastic_forces(model, x);
    const double worst = (test::finite_difference_forces(model, x) - f).cwiseAbs().maxCoeff();
    EXPECT_LT(worst, 1e-6 * f.cwiseAbs().maxCoeff()) << "nu " << nu;
  }
}

TEST(Forces, CrushedCellRecoveryIsAnEnergyGradient) {
  const Model model = test::box_model({1, 1, 1}, notes_material(0.3));
  Eigen::Matrix3Xd x = model.rest_positions;
  for (int n = 0; n < model.num_nodes(); ++n) {
    if (model.node_grid_index[n].z() == 1) x(2, n) -= 0.015;  // top face through the bottom one
  }
  x = x + test::perturbed(model, 5e-4) - model.rest_positions;
  ASSERT_LT(cell_signed_volume(model, x, 0), 0.0);
  const Eigen::Matrix3Xd f = elastic_forces(model, x);
  const double step = 1e-8;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    Eigen::Matrix3Xd plus = x, minus = x;
    plus.data()[i] += step;
    minus.data()[i] -= step;
    const double derivative = (elastic_energy(model, plus) - elastic_energy(model, minus)) / (2 * step);
    EXPECT_NEAR(-derivative, f.data()[i], 1e-6 * f.cwiseAbs().maxCoeff()) << i;
  }
  // the recovery pushes the top face back up
  double top_force = 0.0;
  for (int n = 0; n < model.num_nodes(); ++n) {
    if (model.node_grid_index[n].z() == 1) top_force += f(2, n);
  }
  EXPECT_GT(top_force, 0.0);
}

TEST(Forces, RigidRotationGivesNoForce) {
  const Model model = test::box_model({2, 2, 2}, notes_material(0.45));
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(M_PI / 6, Eigen::Vector3d(0.3, -0.5, 0.8).normalized()).toRotationMatrix();
  const Eigen::Matrix3Xd x = (rotation * model.rest_positions).colwise() + Eigen::Vector3d(0.1, 0.2, -0.3);
  const double scale = 1e5 * 0.01 * 0.01;  // E h^2
  EXPECT_LT(elastic_forces(model, x).cwiseAbs().maxCoeff(), 1e-10 * scale);
}

TEST(Forces, RotateWithTheBody) {
  const Model model = test::box_model({2, 1, 1}, notes_material(0.3));
  const Eigen::Matrix3Xd x = test::perturbed(model, 1e-3);
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(1.1, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Matrix3Xd rotated_forces = elastic_forces(model, rotation * x);
  const Eigen::Matrix3Xd forces = elastic_forces(model, x);
  EXPECT_LT((rotated_forces - rotation * forces).cwiseAbs().maxCoeff(), 1e-9 * forces.cwiseAbs().maxCoeff());
}

TEST(Forces, NetForceAndTorqueVanish) {
  const Model model = test::box_model({3, 2, 1}, notes_material(0.4));
  const Eigen::Matrix3Xd x = test::perturbed(model, 2e-3);
  const Eigen::Matrix3Xd f = elastic_forces(model, x);
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();
  for (int n = 0; n < model.num_nodes(); ++n) torque += Eigen::Vector3d(x.col(n)).cross(Eigen::Vector3d(f.col(n)));
  const double scale = f.cwiseAbs().maxCoeff();
  EXPECT_LT(f.rowwise().sum().cwiseAbs().maxCoeff(), 1e-12 * scale);
  EXPECT_LT(torque.cwiseAbs().maxCoeff(), 1e-12 * scale * 0.03);
}

TEST(Forces, CorrectionSizeAndSignUnderUniaxialStress) {
  // lateral correction force per node / axial force per node = (1 - 4 nu) / 2, outward positive
  for (double nu : {0.0, 0.3, 0.45}) {
    const Model model = test::box_model({1, 1, 1}, notes_material(nu));
    Model springs_only = model;
    for (auto& d : springs_only.cell_correction) d.setZero();
    springs_only.mark_changed();
    const double eps = 1e-7;
    const Eigen::Vector3d strain(eps, -nu * eps, -nu * eps);
    const Eigen::Matrix3Xd x = model.rest_positions + strain.asDiagonal() * model.rest_positions;
    const Eigen::Matrix3Xd correction = elastic_forces(model, x) - elastic_forces(springs_only, x);
    const double axial_per_node = 1e5 * eps * 1e-4 / 4;
    for (int n = 0; n < model.num_nodes(); ++n) {
      const double outward = model.node_grid_index[n].y() == 1 ? 1.0 : -1.0;
      EXPECT_NEAR(outward * correction(1, n) / axial_per_node, (1 - 4 * nu) / 2, 1e-5) << nu;
    }
    // and the total lateral force vanishes: the lateral faces are free
    const Eigen::Matrix3Xd total = elastic_forces(model, x);
    EXPECT_LT(total.row(1).cwiseAbs().maxCoeff(), 1e-5 * axial_per_node);
  }
}

// Threads take whole blocks of the force pass, whose sums do not depend on who runs them: the
// same bits from 1 and 2 threads on bodies of at least 2 blocks: a box, with twist and stiffness
// damping, an ellipsoid of cells (irregular ends of rows), each also with a crushed cell (the
// inversion forces, added between the passes).
TEST(Forces, ThreadCountDoesNotChangeABit) {
  Material damped = notes_material(0.3);
  damped.stiffness_damping = 1e-4;
  LatticeDesc ellipsoid;
  ellipsoid.materials = {damped};
  for (int i = 0; i < 11; ++i) {
    for (int j = 0; j < 11; ++j) {
      for (int k = 0; k < 29; ++k) {  // semi-axes 5, 5 and 14 cells
        if ((i - 5) * (i - 5) / 25.0 + (j - 5) * (j - 5) / 25.0 + (k - 14) * (k - 14) / 196.0 <= 1.0)
          ellipsoid.cells.push_back({i, j, k});
      }
    }
  }
  LatticeDesc exact = box_lattice({16, 12, 8}, Eigen::Vector3d::Constant(0.01), damped);
  exact.model = CellModel::kExactBending;
  LatticeDesc neo_hookean = box_lattice({16, 12, 8}, Eigen::Vector3d::Constant(0.01), damped);
  neo_hookean.law = CellLaw::kNeoHookean;  // corner forces without a twist
  LatticeDesc neo_hookean_exact = exact;
  neo_hookean_exact.law = CellLaw::kNeoHookean;
  const std::vector<std::pair<const char*, LatticeDesc>> bodies{
      {"box", box_lattice({16, 12, 8}, Eigen::Vector3d::Constant(0.01), notes_material(0.3))},
      {"exact-bending box", exact},
      {"ellipsoid", ellipsoid},
      {"neo-hookean box", neo_hookean},
      {"neo-hookean exact-bending box", neo_hookean_exact}};
  for (const auto& [name, desc] : bodies) {
    for (const bool crushed : {false, true}) {
      Result<Model> built = build_model(desc);
      ASSERT_TRUE(built.ok()) << built.message();
      for (const bool lists : {false, true}) {  // the grid passes where the body has them, and the lists
        const Model& model = built.value();
        const auto options = [&](int threads) {
          return lists ? on_spring_lists(ForceOptions{true, threads}) : ForceOptions{true, threads};
        };
        ASSERT_GE(split_force_blocks(model).count(), 2) << name << ": too few springs for 2 blocks";
        const State state = disturbed_state(model, crushed);
        if (crushed) {
          ASSERT_LT(cell_signed_volume(model, state.positions, middle_cell(model)), 0.0) << name;
        }
        Loads loads;
        loads.gravity = {0, 0, -9.81};
        ForceWorkspace ws;
        Eigen::Matrix3Xd one, two;
        compute_forces(model, state, loads, options(1), ws, one);
        compute_forces(model, state, loads, options(2), ws, two);
        EXPECT_EQ(std::memcmp(one.data(), two.data(), sizeof(double) * one.size()), 0)
            << name << (crushed ? ", crushed" : "") << (lists ? ", spring lists" : "");
      }
    }
  }
}

// The blocks' halos lose nothing: a body cut into blocks gets the forces of the same body as one
// block (no halo at all) to rounding, springs, correction, twist and inversion alike.
TEST(Forces, BlocksAndTheirHalosGiveTheForcesOfOneBlock) {
  Material damped = notes_material(0.3);
  damped.stiffness_damping = 1e-4;
  for (const CellModel cell_model : {CellModel::kBaudet2007, CellModel::kExactBending}) {
    for (const CellLaw law : {CellLaw::kSprings, CellLaw::kNeoHookean}) {
      LatticeDesc desc = box_lattice({16, 12, 8}, Eigen::Vector3d::Constant(0.01), damped);
      desc.model = cell_model;
      desc.law = law;
      Result<Model> built = build_model(desc);
      ASSERT_TRUE(built.ok()) << built.message();
      const Model& blocked = built.value();  // on the spring lists, which the blocks cut
      const Model& whole = blocked;          // in one block of every node
      ASSERT_GE(split_force_blocks(blocked).count(), 2) << "too few springs for 2 blocks";
      const State state = disturbed_state(blocked, true);  // a crushed cell too
      Loads loads;
      loads.gravity = {0, 0, -9.81};
      ForceWorkspace blocked_ws, whole_ws;
      use_one_block(whole, whole_ws);
      Eigen::Matrix3Xd by_blocks, at_once;
      compute_forces(blocked, state, loads, on_spring_lists(ForceOptions{true, 2}), blocked_ws, by_blocks);
      compute_forces(whole, state, loads, on_spring_lists(ForceOptions{true, 1}), whole_ws, at_once);
      ASSERT_EQ(whole_ws.engine->blocks.count(), 1);
      const double scale = at_once.cwiseAbs().maxCoeff();
      EXPECT_LT((by_blocks - at_once).cwiseAbs().maxCoeff(), 1e-12 * scale)
          << cell_model_name(cell_model) << ", " << cell_law_name(law);
    }
  }
}

// The grid passes (bodies that fill at least 45% of their bounding box) add the same springs,
// correction, twist, damping and inversion recovery (or the neo-Hookean law's cell term, each
// body with either law) as the spring lists, to rounding: a box, a
// box with holes and a stiff inclusion of another material, the same holes in one material, in
// both models, each with a crushed cell and with a spring of zero length (no direction: no force);
// and boxes numbered along x (non-cubic cells, an inclusion) and y (exact-bending).
TEST(Forces, GridPassesGiveTheForcesOfTheSpringLists) {
  Material damped = notes_material(0.3);
  damped.stiffness_damping = 1e-4;
  damped.mass_damping = 2.0;
  Material stiff = notes_material(0.45);
  stiff.young_modulus *= 20.0;
  LatticeDesc holes = box_lattice({9, 7, 6}, Eigen::Vector3d(0.01, 0.012, 0.008), damped);
  holes.materials.push_back(stiff);
  std::vector<Eigen::Vector3i> kept;
  for (const Eigen::Vector3i& cell : holes.cells) {
    if ((cell.x() * 7 + cell.y() * 3 + cell.z() * 5) % 4 == 0 && cell.x() > 0) continue;  // about a quarter gone
    kept.push_back(cell);
    holes.cell_material.push_back(cell.x() >= 3 && cell.x() <= 5 && cell.y() >= 2 && cell.y() <= 4 ? 1 : 0);
  }
  holes.cells = kept;
  LatticeDesc exact_box = box_lattice({7, 5, 4}, Eigen::Vector3d::Constant(0.01), damped);
  exact_box.model = CellModel::kExactBending;
  LatticeDesc exact_holes = holes;
  exact_holes.cell_size.setConstant(0.01);  // the exact-bending model takes cubes only
  exact_holes.model = CellModel::kExactBending;
  LatticeDesc one_material_holes = holes;  // the grid's uniform coefficients, empty cells inside
  one_material_holes.cell_material.assign(holes.cells.size(), 0);
  // bodies long enough along x or y to be numbered along it (Model::major_axis): the grid's axes
  // turned, with cells of three sides and an inclusion
  LatticeDesc along_x = box_lattice({20, 15, 15}, Eigen::Vector3d(0.01, 0.012, 0.008), damped);
  along_x.materials.push_back(stiff);
  for (const Eigen::Vector3i& cell : along_x.cells) along_x.cell_material.push_back(cell.y() < 5 ? 1 : 0);
  LatticeDesc exact_along_y = box_lattice({15, 20, 15}, Eigen::Vector3d::Constant(0.01), damped);
  exact_along_y.model = CellModel::kExactBending;
  const std::vector<std::tuple<const char*, LatticeDesc, int>> bodies{
      {"box", box_lattice({7, 5, 4}, Eigen::Vector3d::Constant(0.01), damped), 2},
      {"holes and inclusion", holes, 2},
      {"holes", one_material_holes, 2},
      {"exact-bending box", exact_box, 2},
      {"exact-bending holes and inclusion", exact_holes, 2},
      {"box along x, inclusion", along_x, 0},
      {"exact-bending box along y", exact_along_y, 1}};
  for (const auto& [body, body_desc, major_axis] : bodies) {
    for (const CellLaw law : {CellLaw::kSprings, CellLaw::kNeoHookean}) {
      LatticeDesc desc = body_desc;
      desc.law = law;
      const std::string name = std::string(body) + ", " + cell_law_name(law);
      Result<Model> built = build_model(desc);
      ASSERT_TRUE(built.ok()) << built.message();
      const Model& grid = built.value();
      ASSERT_TRUE(uses_grid_passes(grid)) << name;
      ASSERT_EQ(grid.major_axis, major_axis) << name;
      const Model& lists = grid;  // with on_spring_lists
      for (const bool crushed : {false, true}) {
        State state = disturbed_state(grid, crushed);
        if (crushed) {
          ASSERT_LT(cell_signed_volume(grid, state.positions, middle_cell(grid)), 0.0) << name;
          const auto& ends = grid.spring_nodes[grid.num_springs() / 3];
          state.positions.col(ends[1]) = state.positions.col(ends[0]);
        }
        Loads loads;
        loads.gravity = {0, 0, -9.81};
        for (const bool damping : {true, false}) {
          ForceWorkspace grid_ws, lists_ws;
          Eigen::Matrix3Xd by_grid, by_lists;
          compute_forces(grid, state, loads, ForceOptions{damping, 1}, grid_ws, by_grid);
          compute_forces(lists, state, loads, on_spring_lists(ForceOptions{damping, 1}), lists_ws, by_lists);
          ASSERT_TRUE(by_grid.allFinite()) << name;
          const double scale = by_lists.cwiseAbs().maxCoeff();
          EXPECT_LT((by_grid - by_lists).cwiseAbs().maxCoeff(), 1e-12 * scale)
              << name << (crushed ? ", crushed" : "") << (damping ? "" : ", no damping");
        }
      }
    }
  }
}

// A box numbered along x (Model::major_axis) and its copy turned so that it is numbered along z
// as before, x -> z, y -> x, z -> y (a rotation): in both models, damped, with a crushed cell
// and gravity, the forces turn with the body, on 1 and 2 threads, to rounding.
TEST(Forces, ABoxNumberedAlongXHasTheForcesOfItsTurnedCopy) {
  Material damped = notes_material(0.3);
  damped.stiffness_damping = 1e-4;
  damped.mass_damping = 2.0;
  const auto turned = [](const Eigen::Vector3d& v) { return Eigen::Vector3d(v.y(), v.z(), v.x()); };
  for (const CellModel cell_model : {CellModel::kBaudet2007, CellModel::kExactBending}) {
    LatticeDesc along_x = box_lattice({20, 15, 15}, Eigen::Vector3d::Constant(0.01), damped);
    along_x.model = cell_model;
    LatticeDesc along_z = box_lattice({15, 15, 20}, Eigen::Vector3d::Constant(0.01), damped);
    along_z.model = cell_model;
    Result<Model> built_x = build_model(along_x), built_z = build_model(along_z);
    ASSERT_TRUE(built_x.ok() && built_z.ok());
    const Model& model_x = built_x.value();
    const Model& model_z = built_z.value();
    ASSERT_EQ(model_x.major_axis, 0);
    ASSERT_EQ(model_z.major_axis, 2);
    ASSERT_TRUE(uses_grid_passes(model_x));
    ASSERT_TRUE(uses_grid_passes(model_z));
    const State state_x = disturbed_state(model_x, true);
    State state_z = rest_state(model_z);
    std::vector<int> turned_node(model_x.num_nodes());
    for (int n = 0; n < model_x.num_nodes(); ++n) {
      const Eigen::Vector3i& index = model_x.node_grid_index[n];
      turned_node[n] = model_z.node_at({index.y(), index.z(), index.x()});
      ASSERT_GE(turned_node[n], 0);
      state_z.positions.col(turned_node[n]) = turned(state_x.positions.col(n));
      state_z.velocities.col(turned_node[n]) = turned(state_x.velocities.col(n));
    }
    Loads loads_x, loads_z;
    loads_x.gravity = {0, 0, -9.81};
    loads_z.gravity = turned(loads_x.gravity);
    for (const int threads : {1, 2}) {
      ForceWorkspace ws_x, ws_z;
      Eigen::Matrix3Xd forces_x, forces_z;
      compute_forces(model_x, state_x, loads_x, ForceOptions{true, threads}, ws_x, forces_x);
      compute_forces(model_z, state_z, loads_z, ForceOptions{true, threads}, ws_z, forces_z);
      double worst = 0.0;
      for (int n = 0; n < model_x.num_nodes(); ++n) {
        worst = std::max(worst, (turned(forces_x.col(n)) - forces_z.col(turned_node[n])).cwiseAbs().maxCoeff());
      }
      EXPECT_LT(worst, 1e-12 * forces_z.cwiseAbs().maxCoeff()) << cell_model_name(cell_model) << ", " << threads;
    }
  }
}

// A body of one material takes its cells' coefficients and springs' stiffness as constants on
// the grid (grid_layout.h: uniform_cells, SpringFamily::uniform; an edge's share times its
// cells), and they give the bits of the per-point arrays: a damped box and a box with holes
// in both models, with a crushed cell. Two materials keep the edges' arrays.
TEST(Forces, OneMaterialsConstantsGiveThePerPointArraysBits) {
  Material damped = notes_material(0.3);
  damped.stiffness_damping = 1e-4;
  damped.mass_damping = 2.0;
  LatticeDesc holes = box_lattice({9, 7, 6}, Eigen::Vector3d::Constant(0.01), damped);
  std::vector<Eigen::Vector3i> kept;
  for (const Eigen::Vector3i& cell : holes.cells) {
    if ((cell.x() * 7 + cell.y() * 3 + cell.z() * 5) % 4 != 0 || cell.x() == 0) kept.push_back(cell);
  }
  holes.cells = kept;
  for (const CellModel cell_model : {CellModel::kBaudet2007, CellModel::kExactBending}) {
    for (LatticeDesc desc : {box_lattice({6, 5, 4}, Eigen::Vector3d::Constant(0.01), damped), holes}) {
      desc.model = cell_model;
      Result<Model> built = build_model(desc);
      ASSERT_TRUE(built.ok()) << built.message();
      const Model& constants = built.value();
      const std::string what =
          std::string(cell_model_name(cell_model)) + ", " + std::to_string(desc.cells.size()) + " cells";
      const std::shared_ptr<const GridLayout> grid = build_grid_layout(constants);
      ASSERT_NE(grid, nullptr) << what;
      ASSERT_TRUE(grid->uniform_cells) << what;
      for (const SpringFamily& family : grid->families) ASSERT_TRUE(family.uniform) << what;
      auto arrays = std::make_shared<GridLayout>(*grid);
      arrays->uniform_cells = false;
      for (SpringFamily& family : arrays->families) family.uniform = false;
      const Model& per_point = constants;  // on `arrays`
      for (const bool crushed : {false, true}) {
        const State state = disturbed_state(constants, crushed);
        ForceWorkspace ws_constants, ws_arrays;
        use_grid(per_point, arrays, ws_arrays);
        Eigen::Matrix3Xd by_constants, by_arrays;
        compute_forces(constants, state, Loads{}, ForceOptions{true, 1}, ws_constants, by_constants);
        compute_forces(per_point, state, Loads{}, ForceOptions{true, 1}, ws_arrays, by_arrays);
        ASSERT_EQ(ws_arrays.engine->grid, arrays) << what << ": the per-point grid was not the one stepped";
        ASSERT_GT(by_arrays.cwiseAbs().maxCoeff(), 0.0) << what;
        EXPECT_TRUE(by_constants == by_arrays) << what << (crushed ? ", crushed" : "");
      }
    }
  }
  LatticeDesc inclusion = box_lattice({6, 5, 4}, Eigen::Vector3d::Constant(0.01), damped);
  Material stiff = damped;
  stiff.young_modulus *= 20.0;
  inclusion.materials.push_back(stiff);
  for (const Eigen::Vector3i& cell : inclusion.cells)
    inclusion.cell_material.push_back(cell == Eigen::Vector3i(2, 2, 2) ? 1 : 0);
  Result<Model> built = build_model(inclusion);
  ASSERT_TRUE(built.ok()) << built.message();
  const std::shared_ptr<const GridLayout> grid = build_grid_layout(built.value());
  ASSERT_NE(grid, nullptr);
  for (int f = 0; f < kSpringFamilies; ++f) EXPECT_EQ(grid->families[f].uniform, false) << f;
}

// ... but only while every cell has them: after one diagonal's or edge's stiffness, or its
// damping, or one cell's correction, or its twist is changed (and Model::mark_changed), the grid
// passes still give the lists' forces, which the change moves by far more than the rounding;
// a workspace whose engine was built before the change rebuilds it.
TEST(Forces, GridPassesTakeAChangedSpringOrCell) {
  Material damped = notes_material(0.3);
  damped.stiffness_damping = 1e-4;
  enum class Change { kDiagonalStiffness, kDiagonalDamping, kEdgeStiffness, kEdgeDamping, kCellCorrection, kCellTwist };
  for (const CellModel cell_model : {CellModel::kBaudet2007, CellModel::kExactBending}) {
    LatticeDesc desc = box_lattice({5, 4, 3}, Eigen::Vector3d::Constant(0.01), damped);
    desc.model = cell_model;
    Result<Model> built = build_model(desc);
    ASSERT_TRUE(built.ok()) << built.message();
    const Model& before = built.value();
    const auto axes_spanned = [&](int spring) {
      return (before.node_grid_index[before.spring_nodes[spring][1]] -
              before.node_grid_index[before.spring_nodes[spring][0]])
          .cwiseAbs()
          .sum();
    };
    int diagonal = 0;  // the first spring whose ends differ along every axis
    while (axes_spanned(diagonal) != 3) ++diagonal;
    int edge = before.num_springs() / 2;  // an edge inside the body
    while (axes_spanned(edge) != 1) ++edge;
    for (const Change change : {Change::kDiagonalStiffness, Change::kDiagonalDamping, Change::kEdgeStiffness,
                                Change::kEdgeDamping, Change::kCellCorrection, Change::kCellTwist}) {
      if (change == Change::kCellTwist && !before.has_twist) continue;
      Model changed = before;
      const State state = disturbed_state(changed, false);
      ForceWorkspace kept;  // its engine built for the model before the change
      Eigen::Matrix3Xd by_kept;
      compute_forces(changed, state, Loads{}, ForceOptions{true, 1}, kept, by_kept);
      const int cell = middle_cell(changed);
      switch (change) {
        case Change::kDiagonalStiffness: changed.spring_stiffness[diagonal] *= 3.0; break;
        case Change::kDiagonalDamping: changed.spring_damping[diagonal] *= 3.0; break;
        case Change::kEdgeStiffness: changed.spring_stiffness[edge] *= 3.0; break;
        case Change::kEdgeDamping: changed.spring_damping[edge] *= 3.0; break;
        case Change::kCellCorrection: changed.cell_correction[cell] *= 1.5; break;
        case Change::kCellTwist: changed.cell_twist_stiffness[cell] *= 1.5; break;
      }
      changed.mark_changed();
      ASSERT_TRUE(uses_grid_passes(changed));
      const Model& lists = changed;  // with on_spring_lists
      compute_forces(changed, state, Loads{}, ForceOptions{true, 1}, kept, by_kept);
      ForceWorkspace ws;
      Eigen::Matrix3Xd by_grid, by_lists, unchanged;
      compute_forces(changed, state, Loads{}, ForceOptions{true, 1}, ws, by_grid);
      compute_forces(lists, state, Loads{}, on_spring_lists(ForceOptions{true, 1}), ws, by_lists);
      compute_forces(before, state, Loads{}, ForceOptions{true, 1}, ws, unchanged);
      const double scale = by_lists.cwiseAbs().maxCoeff();
      const std::string what =
          std::string(cell_model_name(cell_model)) + ", change " + std::to_string(static_cast<int>(change));
      ASSERT_GT((by_lists - unchanged).cwiseAbs().maxCoeff(), 1e-9 * scale) << what;
      EXPECT_LT((by_grid - by_lists).cwiseAbs().maxCoeff(), 1e-12 * scale) << what;
      EXPECT_TRUE(by_kept == by_grid) << what;
    }
  }
}

// The grid passes cut the z-layers of cells into one chunk per thread (at most one per 1024
// points and per layer of cells); a chunk recomputes the spring forces of the layer below its
// first in its own ring of layers. Any thread count gives the same bits, and the lists' forces
// to rounding: a plate of 3 layers of cells (16128 points: with 3 or 4 threads, chunks of 2
// layers, 1 layer, and the top layer of points alone, which recompute the layers below theirs),
// in the exact-bending model, and a box of 24 x 24 x 14 cells (9375 points: 2, 3 and 4 chunks),
// numbered along y (Model::major_axis: 25 layers of 25 x 15 points) in both models, each with a
// crushed cell.
TEST(Forces, GridChunksGiveTheSameBitsOnAnyThreadCount) {
  Material damped = notes_material(0.3);
  damped.stiffness_damping = 1e-4;
  // layers across x would hold 63 x 4 points, too few to number the nodes along x
  LatticeDesc plate = box_lattice({63, 62, 3}, Eigen::Vector3d::Constant(0.01), damped);
  plate.model = CellModel::kExactBending;
  LatticeDesc exact_box = box_lattice({24, 24, 14}, Eigen::Vector3d::Constant(0.01), damped);
  exact_box.model = CellModel::kExactBending;
  const std::vector<std::tuple<const char*, LatticeDesc, int>> bodies{
      {"exact-bending plate", plate, 2},
      {"box", box_lattice({24, 24, 14}, Eigen::Vector3d::Constant(0.01), damped), 1},
      {"exact-bending box", exact_box, 1}};
  for (const auto& [name, desc, major_axis] : bodies) {
    Result<Model> built = build_model(desc);
    ASSERT_TRUE(built.ok()) << built.message();
    const Model& grid = built.value();
    ASSERT_TRUE(uses_grid_passes(grid)) << name;
    ASSERT_EQ(grid.major_axis, major_axis) << name;
    const Model& lists = grid;  // with on_spring_lists
    const State state = disturbed_state(grid, true);
    Loads loads;
    loads.gravity = {0, 0, -9.81};
    ForceWorkspace ws;
    Eigen::Matrix3Xd one, many, by_lists;
    compute_forces(grid, state, loads, ForceOptions{true, 1}, ws, one);
    for (const int threads : {2, 3, 4}) {
      compute_forces(grid, state, loads, ForceOptions{true, threads}, ws, many);
      EXPECT_EQ(std::memcmp(one.data(), many.data(), sizeof(double) * one.size()), 0)
          << name << ", " << threads << " threads";
    }
    compute_forces(lists, state, loads, on_spring_lists(ForceOptions{true, 2}), ws, by_lists);
    EXPECT_LT((one - by_lists).cwiseAbs().maxCoeff(), 1e-12 * by_lists.cwiseAbs().maxCoeff()) << name;
  }
}

// A stepped pyramid numbered along z, each step's layers of cells narrower and starting a row
// later than the one below: the grid passes compute a layer's span of nodes only (from its first
// node to its last), and a place of a thread's ring of temporaries that held a wider layer is
// cleared outside the span of the narrower layer that takes it (an empty cell beside the body
// reads zeros there). States that change from call to call, one workspace on 1 and 2 threads
// (the pyramid has points enough for two: each sweeps its own ring, one of them down), both
// models and both laws: the forces of the spring lists.
TEST(Forces, GridPassesComputeEachLayersSpanOfNodesOnly) {
  Material damped = notes_material(0.3);
  damped.stiffness_damping = 1e-4;
  for (const CellModel cell_model : {CellModel::kBaudet2007, CellModel::kExactBending}) {
    for (const CellLaw law : {CellLaw::kSprings, CellLaw::kNeoHookean}) {
      LatticeDesc pyramid;
      pyramid.cell_size.setConstant(0.01);
      pyramid.materials = {damped};
      pyramid.model = cell_model;
      pyramid.law = law;
      for (int z = 0; z < 16; ++z) {
        const int inset = z / 4;  // 10 x 10 cells, then 8 x 8, 6 x 6, 4 x 4, four layers each
        for (int y = inset; y < 10 - inset; ++y) {
          for (int x = inset; x < 10 - inset; ++x) pyramid.cells.push_back({x, y, z});
        }
      }
      Result<Model> built = build_model(pyramid);
      ASSERT_TRUE(built.ok()) << built.message();
      const Model& model = built.value();
      const std::string name =
          std::string(cell_model == CellModel::kBaudet2007 ? "paper" : "exact-bending") + ", " + cell_law_name(law);
      ASSERT_TRUE(uses_grid_passes(model)) << name;
      ASSERT_EQ(model.major_axis, 2) << name;
      const std::shared_ptr<const GridLayout> grid = build_grid_layout(model);
      ASSERT_NE(grid, nullptr);
      ASSERT_EQ(grid_threads(*grid, 2), 2) << name;
      // the points the passes compute, of 11 x 11 x 17: in layers of points 0-4 all 121 (the first
      // node at row 0, x 0, the last at row 10, x 10), then 4 layers each from row i, x i to row
      // 10 - i, x 10 - i, for insets i = 1, 2, 3: 12 (10 - 2i) + 1 points
      int spanned = 0;
      for (const PointSpan& span : grid->layer_spans) spanned += span.end - span.begin;
      EXPECT_EQ(spanned, 5 * 121 + 4 * (97 + 73 + 49)) << name;
      EXPECT_EQ(grid->layer_spans.back().begin, 3 * 11 + 3) << name;

      Loads loads;
      loads.gravity = {0, 0, -9.81};
      ForceWorkspace grid_ws, lists_ws;
      for (int call = 0; call < 5; ++call) {  // 2 calls on one thread, then 3 on two (a new scratch)
        State state = rest_state(model);      // a new state each call
        state.positions = test::perturbed(model, 1e-3, 11 + call);
        state.velocities = test::perturbed(model, 0.1, 21 + call) - model.rest_positions;
        const int threads = call < 2 ? 1 : 2;
        Eigen::Matrix3Xd by_grid, by_lists;
        compute_forces(model, state, loads, ForceOptions{true, threads}, grid_ws, by_grid);
        compute_forces(model, state, loads, on_spring_lists(ForceOptions{true, 1}), lists_ws, by_lists);
        ASSERT_TRUE(by_grid.allFinite()) << name;
        EXPECT_LT((by_grid - by_lists).cwiseAbs().maxCoeff(), 1e-12 * by_lists.cwiseAbs().maxCoeff())
            << name << ", call " << call << ", " << threads << " threads";
      }
    }
  }
}

// Whether the OpenMP runtime gives a region the `threads` it asks for (not with OMP_DYNAMIC or a
// lower OMP_THREAD_LIMIT): given fewer, the grid passes fall back to an even split for the
// threads they get, and the tests of the planned splits would pass without running them.
bool runtime_gives(int threads) {
  int given = 1;
#ifdef _OPENMP
#pragma omp parallel num_threads(threads)
  {
    if (omp_get_thread_num() == 0) given = omp_get_num_threads();
  }
#endif
  return given == threads;
}

// The body of the tests of the grid's threads: a box swept by 25 z-layers of points, disturbed
// (with a crushed cell) and under gravity, and its forces on one thread.
struct LayeredBody {
  State state;
  Loads loads;
  Eigen::Matrix3Xd one_thread;
};
LayeredBody layered_body(const Model& model) {
  EXPECT_TRUE(uses_grid_passes(model));
  EXPECT_EQ(model.major_axis, 2);  // 25 z-layers of points
  LayeredBody body{disturbed_state(model, true), Loads{}, Eigen::Matrix3Xd{}};
  body.loads.gravity = {0, 0, -9.81};
  ForceWorkspace ws;
  compute_forces(model, body.state, body.loads, ForceOptions{true, 1}, ws, body.one_thread);
  return body;
}

// Threads share the grid's layers in pairs, one sweeping its pair's region up, the other down,
// meeting wherever they get to (GridSplit); any meeting point gives one thread's bits. A box of 24
// layers of cells (25 of points), damped, with a crushed cell in layer 12, in both models: on 2
// threads every meeting point from 0 (the lower thread gathers nothing) to 25 (the upper
// nothing); on 3 threads a pair's region below 16 and a thread alone above; on 4 two pairs.
// Then states that change from call to call, with meeting points that make a thread read the
// other's layers at once.
TEST(Forces, PairsOfThreadsMeetAnywhereAndKeepTheBits) {
  Material damped = notes_material(0.3);
  damped.stiffness_damping = 1e-4;  // the velocities are copied in and read too
  LatticeDesc exact = box_lattice({14, 24, 24}, Eigen::Vector3d::Constant(0.01), damped);
  exact.model = CellModel::kExactBending;
  Result<Model> exact_model = build_model(exact);
  ASSERT_TRUE(exact_model.ok()) << exact_model.message();
  const std::vector<std::pair<const char*, Model>> bodies{{"paper", test::box_model({14, 24, 24}, damped)},
                                                          {"exact-bending", exact_model.value()}};
  ASSERT_TRUE(runtime_gives(2) && runtime_gives(3) && runtime_gives(4)) << "the splits would go untested";
  for (const auto& [name, model] : bodies) {
    // named references, not a structured binding: an OpenMP region may capture them (C++17)
    const LayeredBody body = layered_body(model);
    const State& state = body.state;
    const Loads& loads = body.loads;
    const Eigen::Matrix3Xd& one = body.one_thread;
    ForceWorkspace ws;
    Eigen::Matrix3Xd many;
    compute_forces(model, state, loads, ForceOptions{true, 1}, ws, many);  // a split set from now on stays
    std::vector<std::vector<int>> splits;
    for (int meet = 0; meet <= 25; ++meet) splits.push_back({0, meet, 25});
    for (int meet : {0, 9, 16}) splits.push_back({0, meet, 16, 25});
    for (int meet : {12, 25}) splits.push_back({0, 5, 12, meet, 25});
    for (const std::vector<int>& split : splits) {
      ws.grid_split = GridSplit{split, {}, 0, true};
      compute_forces(model, state, loads, ForceOptions{true, static_cast<int>(split.size()) - 1}, ws, many);
      ASSERT_EQ(ws.grid_split.first_layers, split);  // fixed: used as it was
      EXPECT_EQ(std::memcmp(one.data(), many.data(), sizeof(double) * one.size()), 0)
          << name << ", split " << ::testing::PrintToString(split);
    }
    // a thread that copies in one layer reads the other's next ones at once: it must wait for
    // their copy, not read those of the state before (the states alternate)
    State moved = state;
    moved.positions.array() += 2e-4;
    Eigen::Matrix3Xd moved_one;
    compute_forces(model, moved, loads, ForceOptions{true, 1}, ws, moved_one);
    for (const std::vector<int>& split : {std::vector<int>{0, 1, 25}, {0, 24, 25}}) {
      ws.grid_split = GridSplit{split, {}, 0, true};
      for (int call = 0; call < 20; ++call) {
        const bool odd = call % 2 == 1;
        compute_forces(model, odd ? moved : state, loads, ForceOptions{true, 2}, ws, many);
        const Eigen::Matrix3Xd& expected = odd ? moved_one : one;
        ASSERT_EQ(std::memcmp(expected.data(), many.data(), sizeof(double) * one.size()), 0)
            << name << ", split " << split[1] << ", call " << call;
      }
    }
  }
}

// The grid passes tell a crushed cell by the signed volume of its mean edge vectors, which they
// take from its diagonals: a cell inside a box mapped by an affine map of determinant 0.19 or
// 0.21 (a squash along each axis, along a slanted axis, and a squash with a shear), each cell
// crushed exactly where cell_signed_volume() is below kCrushedVolumeFraction of its rest volume;
// in a box numbered along z and one along x (the grid's axes turned), damped, in both models,
// on 1 thread, on 2 that meet at every layer around that cell (the layer's claimer alone counts
// it) and on 3, a thread alone above a pair from the cell's layer or the one above (whose sweep
// recomputes the cell's layer without counting it).
TEST(Forces, GridPassesFindTheCellsTheirVolumeSaysAreCrushed) {
  const Eigen::Matrix3d slant = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  Eigen::Matrix3d shear;
  shear << 1, 0.5, 0, 0, 1, 0.3, 0, 0, 1;
  Material damped = notes_material(0.3);
  damped.stiffness_damping = 1e-4;  // the passes' variants with rates
  ASSERT_TRUE(runtime_gives(2) && runtime_gives(3)) << "the splits' counts would go untested";
  for (const Eigen::Vector3i& cells : {Eigen::Vector3i(14, 14, 16), Eigen::Vector3i(20, 15, 15)}) {
    for (const CellModel cell_model : {CellModel::kBaudet2007, CellModel::kExactBending}) {
      LatticeDesc desc = box_lattice(cells, Eigen::Vector3d::Constant(0.01), damped);
      desc.model = cell_model;
      Result<Model> built = build_model(desc);
      ASSERT_TRUE(built.ok()) << built.message();
      const Model& model = built.value();
      const std::shared_ptr<const GridLayout> grid = build_grid_layout(model);
      ASSERT_NE(grid, nullptr);
      ASSERT_GE(grid_threads(*grid, 3), 3);
      const auto inside = std::find(model.cell_grid_index.begin(), model.cell_grid_index.end(), cells / 2);
      ASSERT_NE(inside, model.cell_grid_index.end());
      const int cell = static_cast<int>(inside - model.cell_grid_index.begin());
      const Eigen::Vector3d centre = model.rest_positions(Eigen::all, model.cell_nodes[cell]).rowwise().mean();
      for (int kind = 0; kind < 5; ++kind) {
        for (const double determinant : {0.19, 0.21}) {
          Eigen::Matrix3d map = Eigen::Matrix3d::Identity();
          map(kind % 3, kind % 3) = determinant;                 // kinds 0-2: along x, y, z
          if (kind == 3) map = slant * map * slant.transpose();  // along a slanted axis
          if (kind == 4) map = shear * map;
          ASSERT_NEAR(map.determinant(), determinant, 1e-12);
          State state = rest_state(model);
          for (const int node : model.cell_nodes[cell]) {
            state.positions.col(node) = centre + map * (model.rest_positions.col(node) - centre);
          }
          int expected = 0;
          for (int c = 0; c < model.num_cells(); ++c) {
            expected +=
                cell_signed_volume(model, state.positions, c) < kCrushedVolumeFraction * model.rest_cell_volume();
          }
          ASSERT_EQ(expected, determinant < kCrushedVolumeFraction ? 1 : 0);  // the neighbours stay whole
          const std::string what = ::testing::PrintToString(cells.transpose()) + ", " + cell_model_name(cell_model) +
                                   ", kind " + std::to_string(kind) + ", determinant " + std::to_string(determinant);
          std::vector<double> scratch;
          GridSplit split;
          Eigen::Matrix3Xd forces;
          EXPECT_EQ(grid_spring_forces(*grid, state, true, 1, scratch, split, forces).crushed, expected) << what;
          const int layers = grid->points.z();
          const int layer = model.node_grid_index[model.cell_nodes[cell][0]][model.major_axis];
          std::vector<std::vector<int>> splits;
          for (int meet = layer - 1; meet <= layer + 2; ++meet) splits.push_back({0, meet, layers});
          for (int alone = layer; alone <= layer + 1; ++alone) splits.push_back({0, 1, alone, layers});
          for (const std::vector<int>& first_layers : splits) {
            split = GridSplit{first_layers, {}, 0, true};
            const int threads = static_cast<int>(first_layers.size()) - 1;
            EXPECT_EQ(grid_spring_forces(*grid, state, true, threads, scratch, split, forces).crushed, expected)
                << what << ", split " << ::testing::PrintToString(first_layers);
            ASSERT_EQ(split.first_layers, first_layers) << what << ": the split was not used as it was";
          }
        }
      }
    }
  }
}

// Without a fixed split, each pair's threads claim layers as they go and the split records where
// they met (the layers each copies in next); a split that does not fit the grid is made even. The
// boundary between two pairs' regions moves away from the slower region (its later thread's
// time): from 1 layer against 24 (and 24 against the top layer of points) by 2 layers at least in
// 6 rounds of timed calls, and so does that of a pair beside a thread alone (3 threads). Given one
// thread of the two planned (in a nested region), it does every layer.
TEST(Forces, GridSplitsFollowTheThreadsAndKeepTheBits) {
  ASSERT_TRUE(runtime_gives(2) && runtime_gives(3) && runtime_gives(4)) << "the splits would go untested";
  const Model model = test::box_model({14, 24, 24}, notes_material(0.3));
  // named references, not a structured binding: an OpenMP region may capture them (C++17)
  const LayeredBody body = layered_body(model);
  const State& state = body.state;
  const Loads& loads = body.loads;
  const Eigen::Matrix3Xd& one = body.one_thread;
  ForceWorkspace ws;
  Eigen::Matrix3Xd two;
  compute_forces(model, state, loads, ForceOptions{true, 1}, ws, two);  // a split set from now on stays
  for (const std::vector<int>& split : {std::vector<int>{0, 1, 25}, {0, 25, 25}, {0, 0, 25}}) {
    ws.grid_split = GridSplit{split, {}, 0};
    for (int call = 0; call < 20; ++call) {
      compute_forces(model, state, loads, ForceOptions{true, 2}, ws, two);
      ASSERT_EQ(ws.grid_split.first_layers.size(), 3u);
      EXPECT_EQ(ws.grid_split.first_layers[0], 0);
      EXPECT_EQ(ws.grid_split.first_layers[2], 25);
      EXPECT_GE(ws.grid_split.first_layers[1], 0);
      EXPECT_LE(ws.grid_split.first_layers[1], 25);
      ASSERT_EQ(std::memcmp(one.data(), two.data(), sizeof(double) * one.size()), 0) << split[1] << ", call " << call;
    }
  }
  ws.grid_split = GridSplit{{0, 26, 25}, {}, 0, true};  // a meeting point beyond the grid
  compute_forces(model, state, loads, ForceOptions{true, 2}, ws, two);
  EXPECT_EQ(ws.grid_split.first_layers, (std::vector<int>{0, 12, 25}));
  EXPECT_EQ(std::memcmp(one.data(), two.data(), sizeof(double) * one.size()), 0);

#ifdef _OPENMP
  // inside another parallel region the runtime gives the grid passes one thread of the 2 they
  // plan for (nested regions are off): that thread takes every layer, whatever the split
  Eigen::Matrix3Xd nested[2];
#pragma omp parallel num_threads(2)
  {
    ForceWorkspace own;
    own.grid_split = GridSplit{{0, 1, 25}, {}, 0, true};
    compute_forces(model, state, loads, ForceOptions{true, 2}, own, nested[omp_get_thread_num()]);
  }
  for (const Eigen::Matrix3Xd& forces : nested) {
    if (forces.size() == 0) continue;  // the outer region got one thread
    EXPECT_EQ(std::memcmp(one.data(), forces.data(), sizeof(double) * one.size()), 0) << "nested";
  }
#endif
  Eigen::Matrix3Xd four;
  for (const int boundary : {1, 24}) {  // the upper pair, then the lower, far the slower
    ws.grid_split = GridSplit{{0, 0, boundary, boundary, 25}, {}, 0};
    for (int call = 0; call < 6 * 8; ++call) compute_forces(model, state, loads, ForceOptions{true, 4}, ws, four);
    const std::vector<int>& first = ws.grid_split.first_layers;
    EXPECT_GE(std::abs(first[2] - boundary), 2) << boundary;
    EXPECT_TRUE(first[0] <= first[1] && first[1] <= first[2] && first[2] <= first[3] && first[3] <= first[4])
        << ::testing::PrintToString(first);
    EXPECT_EQ(std::memcmp(one.data(), four.data(), sizeof(double) * one.size()), 0);
  }
  // 3 threads: a pair's region below a thread alone, its boundary moving the same way
  Eigen::Matrix3Xd three;
  for (const int boundary : {1, 24}) {  // the thread alone, then the pair, far the slower
    ws.grid_split = GridSplit{{0, 0, boundary, 25}, {}, 0};
    for (int call = 0; call < 6 * 8; ++call) compute_forces(model, state, loads, ForceOptions{true, 3}, ws, three);
    const std::vector<int>& first = ws.grid_split.first_layers;
    EXPECT_GE(std::abs(first[2] - boundary), 2) << boundary;
    EXPECT_TRUE(first[0] <= first[1] && first[1] <= first[2] && first[2] <= first[3])
        << ::testing::PrintToString(first);
    EXPECT_EQ(std::memcmp(one.data(), three.data(), sizeof(double) * one.size()), 0);
  }
}

// A workspace used by one body and then another whose grid arrays have the same size, but
// another shape, starts afresh: the second body's forces are those of a workspace of its own.
TEST(Forces, AWorkspaceMovedToAnotherBodyForgetsTheFirst) {
  // 2 x 4 x 2 points and 3 x 2 x 3: the same size of grid arrays and rings (grid_forces.cpp)
  const Model first = test::box_model({1, 3, 1}, notes_material(0.3));
  const Model second = test::box_model({2, 1, 2}, notes_material(0.45));
  ASSERT_TRUE(uses_grid_passes(first));
  ASSERT_TRUE(uses_grid_passes(second));
  State first_state = rest_state(first);
  first_state.positions = test::perturbed(first, 1e-3);
  State second_state = rest_state(second);
  second_state.positions = test::perturbed(second, 1e-3);
  ForceWorkspace shared, own;
  Eigen::Matrix3Xd forces, expected;
  compute_forces(first, first_state, Loads{}, ForceOptions{}, shared, forces);
  compute_forces(second, second_state, Loads{}, ForceOptions{}, own, expected);
  ASSERT_EQ(shared.grid_arrays.size(), own.grid_arrays.size())
      << "the bodies no longer test a workspace of the same size";
  compute_forces(second, second_state, Loads{}, ForceOptions{}, shared, forces);
  EXPECT_EQ(std::memcmp(forces.data(), expected.data(), sizeof(double) * forces.size()), 0);
}

// Which bodies the grid passes take: those that fill at least kDefaultMinGridFill (0.45) of their
// box, or whatever ForceOptions::min_grid_fill says; a sparse body forced onto the grid, its box
// mostly empty points, still gets the forces of the spring lists.
TEST(Forces, GridPassesTakeBodiesThatFillEnoughOfTheirBox) {
  ASSERT_EQ(kDefaultMinGridFill, 0.45);  // the fills below are chosen about it
  LatticeDesc sparse;
  sparse.cell_size.setConstant(0.01);
  sparse.materials = {notes_material(0.3)};
  for (int i = 0; i < 5; ++i) sparse.cells.push_back({i, std::min(i, 3), 0});  // 5 of the 20 cells of a 5x4 box
  const Result<Model> built = build_model(sparse);
  ASSERT_TRUE(built.ok()) << built.message();
  EXPECT_FALSE(uses_grid_passes(built.value()));
  LatticeDesc denser = sparse;
  denser.cells.push_back({1, 0, 0});
  denser.cells.push_back({2, 1, 0});
  denser.cells.push_back({3, 2, 0});  // 8 of 20: 0.40
  EXPECT_FALSE(uses_grid_passes(build_model(denser).value()));
  denser.cells.push_back({0, 1, 0});  // 9 of 20: 0.45
  EXPECT_TRUE(uses_grid_passes(build_model(denser).value()));
  LatticeDesc exact = box_lattice({3, 2, 2}, Eigen::Vector3d::Constant(0.01), notes_material(0.3));
  exact.model = CellModel::kExactBending;
  EXPECT_TRUE(uses_grid_passes(build_model(exact).value()));

  const Model& sparse_model = built.value();
  const ForceOptions anywhere{true, 1, 0.0};
  ASSERT_TRUE(uses_grid_passes(sparse_model, anywhere));
  const State state = disturbed_state(sparse_model, false);
  Loads loads;
  loads.gravity = {0, 0, -9.81};
  ForceWorkspace grid_ws, lists_ws;
  Eigen::Matrix3Xd by_grid, by_lists;
  compute_forces(sparse_model, state, loads, anywhere, grid_ws, by_grid);
  compute_forces(sparse_model, state, loads, ForceOptions{true, 1}, lists_ws, by_lists);
  ASSERT_NE(grid_ws.engine->grid, nullptr);
  ASSERT_EQ(lists_ws.engine->grid, nullptr);
  EXPECT_LT((by_grid - by_lists).cwiseAbs().maxCoeff(), 1e-12 * by_lists.cwiseAbs().maxCoeff());

  const Model full = build_model(exact).value();
  EXPECT_FALSE(uses_grid_passes(full, ForceOptions{true, 1, 1.01}));
  EXPECT_FALSE(uses_grid_passes(full, ForceOptions{true, 1, std::numeric_limits<double>::quiet_NaN()}));
  EXPECT_TRUE(uses_grid_passes(full, ForceOptions{true, 1, 1.0}));
}

TEST(Forces, GravityPullsEveryMass) {
  const Model model = test::box_model({2, 2, 2}, notes_material(0.3));
  Loads loads;
  loads.gravity = {0, 0, -9.81};
  ForceWorkspace ws;
  Eigen::Matrix3Xd f;
  compute_forces(model, rest_state(model), loads, ForceOptions{}, ws, f);
  EXPECT_NEAR(f.row(2).sum(), -9.81 * model.total_mass(), 1e-12);
}

}  // namespace
}  // namespace cubespring
