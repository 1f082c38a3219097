// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Cells taken out at run time (cutting): the body left is the one its remaining cells make, its
// mass and momentum fall by exactly what left, its state and constraints carry over, and a
// stepper that stepped the old body steps the new one as a fresh one would.
#include <algorithm>
#include <cstdlib>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "closed_surface.h"
#include "cubespring/cell_removal.h"
#include "cubespring/integrator.h"
#include "cubespring/lattice_surface.h"
#include "cubespring/mass_scaling.h"
#include "cubespring/model.h"
#include "cubespring/stable_time_step.h"
#include "cubespring/stiffness_row_sums.h"
#include "test_support.h"

namespace cubespring {
namespace {

// A block of two materials (a stiff core), neo-Hookean or springs, exact-bending cells.
LatticeDesc two_material_desc(const Eigen::Vector3i& counts, CellLaw law) {
  LatticeDesc desc = box_lattice(counts, Eigen::Vector3d::Constant(0.005), soft_tissue(8e3));
  desc.model = CellModel::kExactBending;
  desc.law = law;
  desc.materials.push_back(soft_tissue(4e4));
  desc.materials.back().density = 1100.0;
  desc.cell_material.assign(desc.cells.size(), 0);
  for (std::size_t c = 0; c < desc.cells.size(); ++c) {
    if ((desc.cells[c] - counts / 2).cwiseAbs().maxCoeff() <= 1) desc.cell_material[c] = 1;
  }
  return desc;
}

Model two_material_block(const Eigen::Vector3i& counts, CellLaw law) {
  Result<Model> model = build_model(two_material_desc(counts, law));
  EXPECT_TRUE(model.ok()) << model.message();
  return std::move(model).value();
}

State moving_state(const Model& model, unsigned seed) {
  State state = rest_state(model);
  state.positions = test::perturbed(model, 2e-4, seed);
  std::mt19937 rng(seed + 1);
  std::uniform_real_distribution<double> speed(-0.05, 0.05);
  for (Eigen::Index i = 0; i < state.velocities.size(); ++i) state.velocities.data()[i] = speed(rng);
  state.time = 0.25;
  return state;
}

std::vector<int> random_cells(const Model& model, int count, std::mt19937& rng) {
  std::uniform_int_distribution<int> cell(0, model.num_cells() - 1);
  std::vector<int> cells;
  for (int i = 0; i < count; ++i) cells.push_back(cell(rng));
  return cells;
}

double cells_mass(const Model& model) {
  double mass = 0.0;
  for (int c = 0; c < model.num_cells(); ++c) {
    mass += model.materials[static_cast<std::size_t>(model.cell_material[static_cast<std::size_t>(c)])].density *
            model.rest_cell_volume();
  }
  return mass;
}

Eigen::Vector3d momentum(const Model& model, const State& state) { return state.velocities * model.mass; }

// The volume the surface encloses at rest [m^3].
double enclosed_volume(const Model& model, const LatticeSurface& surface) {
  return test::enclosed_volume(surface_vertices(surface, model.rest_positions), surface.triangles);
}

TEST(CellRemoval, RemovingNothingRebuildsTheSameModel) {
  for (const CellLaw law : {CellLaw::kSprings, CellLaw::kNeoHookean}) {
    const Model model = two_material_block({5, 4, 3}, law);
    const State state = moving_state(model, 3);
    Result<CellRemoval> removal = remove_cells(model, state, Constraints(model), {});
    ASSERT_TRUE(removal.ok()) << removal.message();
    const Model& after = removal->model;
    EXPECT_EQ(after.rest_positions, model.rest_positions);
    EXPECT_EQ(after.mass, model.mass);
    EXPECT_EQ(after.mass_damping, model.mass_damping);
    EXPECT_EQ(after.spring_nodes, model.spring_nodes);
    EXPECT_EQ(after.spring_stiffness, model.spring_stiffness);
    EXPECT_EQ(after.cell_nodes, model.cell_nodes);
    EXPECT_EQ(after.cell_twist_stiffness, model.cell_twist_stiffness);
    EXPECT_EQ(after.cell_law, model.cell_law);
    EXPECT_EQ(after.law_constants.size(), model.law_constants.size());
    EXPECT_NE(after.revision, model.revision);  // a new model: engines built from the old one rebuild
    EXPECT_TRUE(removal->state == state);
    EXPECT_EQ(removal->pieces, 1);
  }
}

TEST(CellRemoval, MassAndMomentumFallByWhatLeft) {
  const Model model = two_material_block({8, 6, 5}, CellLaw::kNeoHookean);
  const State state = moving_state(model, 11);
  std::mt19937 rng(5);
  const std::vector<int> cells = random_cells(model, 40, rng);
  Result<CellRemoval> removal = remove_cells(model, state, Constraints(model), cells);
  ASSERT_TRUE(removal.ok()) << removal.message();
  const Model& after = removal->model;

  // mass: the remaining cells' density times volume, and the old mass less what left
  std::vector<char> removed(static_cast<std::size_t>(model.num_cells()), 0);
  for (const int c : cells) removed[static_cast<std::size_t>(c)] = 1;
  const int left = static_cast<int>(std::count(removed.begin(), removed.end(), char{1}));
  EXPECT_EQ(removal->removed_cells, left);
  EXPECT_EQ(after.num_cells(), model.num_cells() - left);
  EXPECT_NEAR(after.total_mass(), cells_mass(after), 1e-12 * cells_mass(after));
  EXPECT_NEAR(after.total_mass(), model.total_mass() - removal->removed_mass, 1e-12 * model.total_mass());

  // momentum: the old body's less that of the removed cells' lumped masses, summed here cell by
  // cell from the old model
  Eigen::Vector3d leaving = Eigen::Vector3d::Zero();
  for (int c = 0; c < model.num_cells(); ++c) {
    if (!removed[static_cast<std::size_t>(c)]) continue;
    const double eighth =
        model.materials[static_cast<std::size_t>(model.cell_material[static_cast<std::size_t>(c)])].density *
        model.rest_cell_volume() / 8.0;
    for (const int node : model.cell_nodes[static_cast<std::size_t>(c)]) leaving += eighth * state.velocities.col(node);
  }
  const double scale = (state.velocities.cwiseAbs() * model.mass).norm();
  EXPECT_LT((momentum(model, state) - momentum(after, removal->state) - leaving).norm(), 1e-12 * scale);
  EXPECT_LT((removal->removed_momentum - leaving).norm(), 1e-12 * scale);
}

TEST(CellRemoval, EachRemainingNodeKeepsItsStateAndConstraint) {
  const Model model = two_material_block({6, 5, 4}, CellLaw::kNeoHookean);
  const State state = moving_state(model, 17);
  Constraints constraints(model);
  ASSERT_TRUE(constraints.fix_box(model, {-1, -1, -1}, {1, 1, 0.0001}).ok());  // the base
  ASSERT_TRUE(constraints.prescribe_position(model.num_nodes() - 1, {0.1, 0.2, 0.3}).ok());
  std::vector<int> cells;  // the top layer's first row, and one base cell
  for (int c = 0; c < model.num_cells(); ++c) {
    const Eigen::Vector3i g = model.cell_grid_index[static_cast<std::size_t>(c)];
    if ((g.z() == 3 && g.y() == 0) || g == Eigen::Vector3i(0, 0, 0)) cells.push_back(c);
  }
  Result<CellRemoval> removal = remove_cells(model, state, constraints, cells);
  ASSERT_TRUE(removal.ok()) << removal.message();
  const Model& after = removal->model;
  int kept = 0;
  for (int n = 0; n < model.num_nodes(); ++n) {
    const int to = removal->new_node[static_cast<std::size_t>(n)];
    // a node leaves when no remaining cell has it: the base cell's corner at the origin, and
    // the top row's outer corners
    const Eigen::Vector3i g = model.node_grid_index[static_cast<std::size_t>(n)];
    const bool leaves = g == Eigen::Vector3i(0, 0, 0) || (g.z() == 4 && g.y() == 0);
    ASSERT_EQ(to == -1, leaves) << g.transpose();
    if (to == -1) continue;
    ++kept;
    EXPECT_EQ(after.node_grid_index[static_cast<std::size_t>(to)], g);
    EXPECT_EQ(removal->state.positions.col(to), state.positions.col(n));
    EXPECT_EQ(removal->state.velocities.col(to), state.velocities.col(n));
    EXPECT_EQ(removal->constraints.driven_axes(to), constraints.driven_axes(n));
    if (constraints.is_driven(n)) {
      EXPECT_EQ(removal->constraints.target(to), constraints.target(n));
    }
  }
  EXPECT_EQ(kept, after.num_nodes());
  EXPECT_EQ(removal->state.time, state.time);
  for (int c = 0; c < model.num_cells(); ++c) {
    const int to = removal->new_cell[static_cast<std::size_t>(c)];
    if (to < 0) continue;
    EXPECT_EQ(after.cell_grid_index[static_cast<std::size_t>(to)], model.cell_grid_index[static_cast<std::size_t>(c)]);
    EXPECT_EQ(after.cell_material[static_cast<std::size_t>(to)], model.cell_material[static_cast<std::size_t>(c)]);
  }
  // nodal loads follow their nodes
  const Eigen::Matrix3Xd loads = test::perturbed(model, 1.0, 3);
  const Eigen::Matrix3Xd carried = carry_node_columns(*removal, loads);
  for (int n = 0; n < model.num_nodes(); ++n) {
    const int to = removal->new_node[static_cast<std::size_t>(n)];
    if (to >= 0) {
      EXPECT_EQ(carried.col(to), loads.col(n));
    }
  }
}

// The body a cut leaves is the body of its remaining cells: built here from a block's cells less
// its far half (which changes the axis its nodes are numbered along: x-major before, z-major
// after), with the same arrays, and the same steps from the carried state, on both integrators.
TEST(CellRemoval, ACutBodyIsTheBodyOfItsRemainingCells) {
  const Eigen::Vector3i counts(24, 20, 14);
  const auto cut_away = [](const Eigen::Vector3i& g) { return g.x() >= 10; };
  const LatticeDesc desc = two_material_desc(counts, CellLaw::kNeoHookean);
  LatticeDesc kept = desc;
  kept.cells.clear();
  kept.cell_material.clear();
  for (std::size_t c = 0; c < desc.cells.size(); ++c) {
    if (cut_away(desc.cells[c])) continue;
    kept.cells.push_back(desc.cells[c]);
    kept.cell_material.push_back(desc.cell_material[c]);
  }
  Result<Model> built = build_model(desc);
  ASSERT_TRUE(built.ok()) << built.message();
  const Model& model = *built;
  std::vector<int> cells;
  for (int c = 0; c < model.num_cells(); ++c) {
    if (cut_away(model.cell_grid_index[static_cast<std::size_t>(c)])) cells.push_back(c);
  }
  const State state = moving_state(model, 29);
  Result<CellRemoval> removal = remove_cells(model, state, Constraints(model), cells);
  ASSERT_TRUE(removal.ok()) << removal.message();
  Result<Model> expected = build_model(kept);
  ASSERT_TRUE(expected.ok()) << expected.message();
  const Model& after = removal->model;
  EXPECT_EQ(model.major_axis, 0);
  EXPECT_EQ(after.major_axis, 2);
  EXPECT_EQ(after.major_axis, expected->major_axis);
  EXPECT_EQ(after.rest_positions, expected->rest_positions);
  EXPECT_EQ(after.mass, expected->mass);
  EXPECT_EQ(after.spring_nodes, expected->spring_nodes);
  EXPECT_EQ(after.spring_stiffness, expected->spring_stiffness);
  EXPECT_EQ(after.cell_nodes, expected->cell_nodes);
  EXPECT_EQ(after.cell_material, expected->cell_material);
  for (const Integrator integrator : {Integrator::kSymplecticEuler, Integrator::kImplicitEuler}) {
    StepSettings settings;
    settings.integrator = integrator;
    settings.time_step = integrator == Integrator::kImplicitEuler ? 1e-3 : 1e-4;
    Loads loads;
    loads.gravity = {0, 0, -9.81};
    State cut_body = removal->state, built_body = removal->state;
    Stepper cut_stepper(after), built_stepper(*expected);
    for (int i = 0; i < 3; ++i) {
      ASSERT_TRUE(cut_stepper.step(after, removal->constraints, loads, settings, cut_body).ok());
      ASSERT_TRUE(built_stepper.step(*expected, Constraints(*expected), loads, settings, built_body).ok());
    }
    EXPECT_TRUE(cut_body == built_body) << (integrator == Integrator::kImplicitEuler ? "implicit" : "explicit");
  }
}

// A beam held at one end, cut through by a slab of cells: the free piece falls freely (its
// internal forces sum to zero), its centre following symplectic Euler's free fall exactly,
// x_n = x_0 - g dt^2 n (n + 1) / 2, away from the held piece.
TEST(CellRemoval, APieceCutOffFallsFreely) {
  LatticeDesc desc = box_lattice({12, 3, 3}, Eigen::Vector3d::Constant(0.01), soft_tissue(2e4));
  desc.materials[0].mass_damping = 0.0;  // free fall: no drag on the piece
  desc.model = CellModel::kExactBending;
  desc.law = CellLaw::kNeoHookean;
  Result<Model> built = build_model(desc);
  ASSERT_TRUE(built.ok()) << built.message();
  const Model& model = *built;
  Constraints constraints(model);
  ASSERT_TRUE(constraints.fix_box(model, {-1, -1, -1}, {0.0001, 1, 1}).ok());
  std::vector<int> slab;
  for (int c = 0; c < model.num_cells(); ++c) {
    if (model.cell_grid_index[static_cast<std::size_t>(c)].x() == 6) slab.push_back(c);
  }
  Result<CellRemoval> removal = remove_cells(model, rest_state(model), constraints, slab);
  ASSERT_TRUE(removal.ok()) << removal.message();
  EXPECT_EQ(removal->pieces, 2);
  const Model& after = removal->model;
  std::vector<int> free_nodes, held_nodes;
  for (int n = 0; n < after.num_nodes(); ++n) {
    (after.node_grid_index[static_cast<std::size_t>(n)].x() >= 7 ? free_nodes : held_nodes).push_back(n);
  }
  const auto centre_z = [&](const State& s, const std::vector<int>& nodes) {
    double mz = 0.0, m = 0.0;
    for (const int n : nodes) {
      mz += after.mass[n] * s.positions(2, n);
      m += after.mass[n];
    }
    return mz / m;
  };
  State state = removal->state;
  const double start = centre_z(state, free_nodes), held_start = centre_z(state, held_nodes);
  Loads loads;
  loads.gravity = {0, 0, -9.81};
  StepSettings settings;
  settings.time_step = 2e-4;
  Stepper stepper(after);
  const int steps = 500;
  for (int i = 0; i < steps; ++i) ASSERT_TRUE(stepper.step(after, removal->constraints, loads, settings, state).ok());
  const double fall = 9.81 * settings.time_step * settings.time_step * steps * (steps + 1) / 2.0;  // 0.1 s: 49 mm
  const double free_drop = start - centre_z(state, free_nodes), held_drop = held_start - centre_z(state, held_nodes);
  EXPECT_NEAR(free_drop, fall, 1e-9);
  EXPECT_GT(free_drop - held_drop, 0.5 * fall);  // the held piece swings undamped, but held
}

TEST(CellRemoval, BadRemovalsAreRefusedWithTheirCause) {
  const Model model = test::box_model({2, 2, 2}, Material{});
  const State state = rest_state(model);
  const Constraints constraints(model);
  Result<CellRemoval> out_of_range = remove_cells(model, state, constraints, {0, 8});
  ASSERT_FALSE(out_of_range.ok());
  EXPECT_NE(out_of_range.message().find("cell 8 to remove is out of range: the body has 8 cells"), std::string::npos)
      << out_of_range.message();
  Result<CellRemoval> all = remove_cells(model, state, constraints, {0, 1, 2, 3, 4, 5, 6, 7, 3});
  ASSERT_FALSE(all.ok());
  EXPECT_NE(all.message().find("all 8 cells"), std::string::npos) << all.message();
  State short_state = state;
  short_state.velocities.conservativeResize(3, 5);
  Result<CellRemoval> sizes = remove_cells(model, short_state, constraints, {0});
  ASSERT_FALSE(sizes.ok());
  EXPECT_NE(sizes.message().find("5 velocities for a body of 27 nodes"), std::string::npos) << sizes.message();
}

// The stable steps of a cut body read its stiffness's row sums: carried through a chain of cuts
// (each summing again only the rows it changed), they stay those of the body summed whole, and so
// do the mass scaling and each cell's step that read them.
TEST(CellRemoval, RowSumsCarriedThroughCutsAreTheWholeBodys) {
  std::mt19937 rng(77);
  Model model = two_material_block({10, 8, 6}, CellLaw::kNeoHookean);
  State state = rest_state(model);
  Constraints constraints(model);
  Eigen::VectorXd sums = stiffness_row_sums(model);
  int changed_rows = 0;
  for (int cut = 0; cut < 8; ++cut) {
    Result<CellRemoval> removal = remove_cells(model, state, constraints, random_cells(model, 1 + cut * 3, rng));
    ASSERT_TRUE(removal.ok()) << removal.message();
    const Eigen::VectorXd after = stiffness_row_sums_after(model, sums, *removal);
    for (int n = 0; n < model.num_nodes(); ++n) {  // rows the cut changed, which the sums followed
      const int to = removal->new_node[static_cast<std::size_t>(n)];
      changed_rows += to >= 0 && std::abs(after[to] - sums[n]) > 1e-6 * sums[n];
    }
    sums = after;
    model = std::move(removal->model);
    state = std::move(removal->state);
    constraints = std::move(removal->constraints);
    const Eigen::VectorXd whole = stiffness_row_sums(model);
    ASSERT_EQ(sums.size(), whole.size());
    EXPECT_LE((sums - whole).cwiseAbs().maxCoeff(), 1e-12 * whole.maxCoeff()) << "cut " << cut;
  }
  EXPECT_GT(changed_rows, 50);
  const Eigen::VectorXd steps = cell_stable_time_steps(model, sums), whole_steps = cell_stable_time_steps(model);
  EXPECT_LE((steps - whole_steps).cwiseAbs().maxCoeff(), 1e-12 * whole_steps.maxCoeff());
  Model scaled = model, scaled_whole = model;
  const MassScaling scaling = add_mass_for_time_step(scaled, 0.05, sums);
  const MassScaling scaling_whole = add_mass_for_time_step(scaled_whole, 0.05);
  EXPECT_GT(scaling.nodes, 0);  // the stiff core's nodes took inertia
  EXPECT_EQ(scaling.nodes, scaling_whole.nodes);
  EXPECT_NEAR(scaling.time_step_after, scaling_whole.time_step_after, 1e-12 * scaling_whole.time_step_after);
  EXPECT_LE((scaled.inertia() - scaled_whole.inertia()).cwiseAbs().maxCoeff(),
            1e-12 * scaled_whole.inertia().maxCoeff());
  // sums of another body are refused, naming the sizes
  try {
    (void)cell_stable_time_steps(model, Eigen::VectorXd::Ones(3));
    ADD_FAILURE() << "three row sums were taken for " << model.num_nodes() << " nodes";
  } catch (const std::invalid_argument& wrong) {
    EXPECT_NE(
        std::string(wrong.what()).find("3 row sums for a body of " + std::to_string(model.num_nodes()) + " nodes"),
        std::string::npos)
        << wrong.what();
  }
}

// Random cuts one after another, the body stepped between them: each leaves a body whose mass is
// its cells', whose lattice surface is closed, oriented and encloses its cells' volume, and whose
// state stays finite. CUBESPRING_RANDOM_CUTS sets the count (the documented long run: 10,000).
TEST(CellRemoval, RandomCutsLeaveASoundBody) {
  const char* count_text = std::getenv("CUBESPRING_RANDOM_CUTS");
  const int cuts = count_text != nullptr ? std::atoi(count_text) : 60;
  std::mt19937 rng(2026);
  const Model start = two_material_block({16, 16, 16}, CellLaw::kNeoHookean);
  Model model = start;
  State state = rest_state(model);
  Constraints constraints(model);
  Loads loads;
  loads.gravity = {0, 0, -9.81};
  StepSettings settings;
  settings.time_step = 2e-4;
  for (int cut = 0; cut < cuts; ++cut) {
    if (model.num_cells() < 64) {  // cut away: start again from the whole block
      model = start;
      state = rest_state(model);
      constraints = Constraints(model);
    }
    std::vector<int> cells;
    if (rng() % 2 == 0) {
      cells = random_cells(model, 1 + static_cast<int>(rng() % 40), rng);
    } else {  // a stroke: the cells along a random segment through the block, a cell wide
      std::uniform_real_distribution<double> unit(0.0, 16.0);
      const Eigen::Vector3d a(unit(rng), unit(rng), unit(rng)), b(unit(rng), unit(rng), unit(rng));
      for (int c = 0; c < model.num_cells(); ++c) {
        const Eigen::Vector3d centre = model.cell_grid_index[static_cast<std::size_t>(c)].cast<double>().array() + 0.5;
        const double along = std::clamp((centre - a).dot(b - a) / std::max((b - a).squaredNorm(), 1e-12), 0.0, 1.0);
        if ((a + along * (b - a) - centre).norm() < 0.8) cells.push_back(c);
      }
    }
    if (cells.size() >= static_cast<std::size_t>(model.num_cells())) continue;
    Result<CellRemoval> removal = remove_cells(model, state, constraints, cells);
    ASSERT_TRUE(removal.ok()) << "cut " << cut << ": " << removal.message();
    model = std::move(removal->model);
    state = std::move(removal->state);
    constraints = std::move(removal->constraints);
    ASSERT_NEAR(model.total_mass(), cells_mass(model), 1e-12 * cells_mass(model)) << "cut " << cut;
    const LatticeSurface surface = lattice_boundary_surface(model);
    ASSERT_TRUE(test::closed_and_oriented(surface.triangles)) << "cut " << cut;
    ASSERT_NEAR(enclosed_volume(model, surface), model.num_cells() * model.rest_cell_volume(),
                1e-9 * model.num_cells() * model.rest_cell_volume())
        << "cut " << cut;
    Stepper stepper(model);  // one per body: the cut body is a new one
    for (int i = 0; i < 3; ++i) {
      const StepReport report = stepper.step(model, constraints, loads, settings, state);
      ASSERT_TRUE(report.ok()) << "cut " << cut << ": " << report.message;
    }
    ASSERT_TRUE(state.positions.allFinite() && state.velocities.allFinite()) << "cut " << cut;
  }
}

}  // namespace
}  // namespace cubespring
