// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Faces between cells split at run time (a blade's cut): nothing leaves, the nodes the split
// parts are duplicated, mass and momentum are kept, a body split through is two bodies, a crack
// is a closed surface, and cells split from their face neighbours let go of the cells they touch
// along an edge only when no cell lies between.
#include <algorithm>
#include <cstdlib>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "closed_surface.h"
#include "cubespring/cell_removal.h"
#include "cubespring/face_split.h"
#include "cubespring/integrator.h"
#include "cubespring/lattice_surface.h"
#include "cubespring/model.h"
#include "test_support.h"

namespace cubespring {
namespace {

Model build(const LatticeDesc& desc) {
  Result<Model> model = build_model(desc);
  EXPECT_TRUE(model.ok()) << model.message();
  return std::move(model).value();
}

LatticeDesc tissue_box(const Eigen::Vector3i& counts, CellLaw law = CellLaw::kNeoHookean) {
  LatticeDesc desc = box_lattice(counts, Eigen::Vector3d::Constant(0.01), soft_tissue(2e4));
  desc.model = CellModel::kExactBending;
  desc.law = law;
  return desc;
}

// Every face between layer `layer` - 1 and `layer` along z.
std::vector<CellFace> faces_below_layer(const Model& model, int layer) {
  std::vector<CellFace> faces;
  for (const Eigen::Vector3i& cell : model.cell_grid_index) {
    if (cell.z() == layer - 1) faces.push_back({cell, 2});
  }
  return faces;
}

Eigen::Vector3d momentum(const Model& model, const State& state) { return state.velocities * model.mass; }
// The size of the sums above [kg m/s]: their rounding, over a thousand nodes, is relative to it.
double momentum_scale(const Model& model, const State& state) {
  return std::max(1e-3, state.velocities.colwise().norm().dot(model.mass));
}

double cells_mass(const Model& model) {
  double mass = 0.0;
  for (const int m : model.cell_material) mass += model.materials[static_cast<std::size_t>(m)].density;
  return mass * model.rest_cell_volume();
}

double lattice_volume(const Model& model) {
  const LatticeSurface surface = lattice_boundary_surface(model);
  return test::enclosed_volume(surface_vertices(surface, model.rest_positions), surface.triangles);
}

TEST(FaceSplit, SplittingNoFaceRebuildsTheSameModel) {
  const Model model = build(tissue_box({4, 3, 2}));
  State state = rest_state(model);
  state.positions = test::perturbed(model, 1e-4, 5);
  Result<FaceSplit> split = split_faces(model, state, Constraints(model), {});
  ASSERT_TRUE(split.ok()) << split.message();
  EXPECT_EQ(split->model.rest_positions, model.rest_positions);
  EXPECT_EQ(split->model.spring_nodes, model.spring_nodes);
  EXPECT_EQ(split->model.spring_stiffness, model.spring_stiffness);
  EXPECT_EQ(split->model.cell_nodes, model.cell_nodes);
  EXPECT_EQ(split->model.mass, model.mass);
  EXPECT_EQ(split->state.positions, state.positions);
  EXPECT_EQ(split->nodes_added, 0);
  EXPECT_EQ(split->pieces, 1);
}

// A column split through: its node count grows by one layer of nodes, mass and momentum are what
// they were, and it makes two pieces.
TEST(FaceSplit, ASplitThroughKeepsMassAndMomentum) {
  const Model model = build(tissue_box({3, 2, 8}));
  State state = rest_state(model);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> speed(-0.1, 0.1);
  for (Eigen::Index i = 0; i < state.velocities.size(); ++i) state.velocities.data()[i] = speed(rng);
  Result<FaceSplit> split = split_faces(model, state, Constraints(model), faces_below_layer(model, 4));
  ASSERT_TRUE(split.ok()) << split.message();
  EXPECT_EQ(split->faces_split, 6);
  EXPECT_EQ(split->nodes_added, 4 * 3);  // the nodes of the plane z = 4, once more
  EXPECT_EQ(split->pieces, 2);
  EXPECT_NEAR(split->model.total_mass(), model.total_mass(), 1e-15 * model.total_mass());
  EXPECT_NEAR(split->model.total_mass(), cells_mass(split->model), 1e-15 * model.total_mass());
  EXPECT_LE((momentum(split->model, split->state) - momentum(model, state)).norm(), 1e-15);
  // each copy has the mass of its side's cells: the plane's corner nodes a quarter cell's
  for (int n = 0; n < split->model.num_nodes(); ++n) {
    const Eigen::Vector3i& g = split->model.node_grid_index[static_cast<std::size_t>(n)];
    if (g.z() != 4 || g.x() % 3 != 0 || g.y() % 2 != 0) continue;
    EXPECT_NEAR(split->model.mass[n], 1060.0 * 1e-6 / 8.0, 1e-15) << "node " << n;
  }
  // the split is kept: splitting it again adds nothing
  Result<FaceSplit> again = split_faces(split->model, split->state, split->constraints, faces_below_layer(model, 4));
  ASSERT_TRUE(again.ok()) << again.message();
  EXPECT_EQ(again->faces_split, 0);
  EXPECT_EQ(again->nodes_added, 0);
}

// A beam held at one end and split through in its middle: the free half falls as symplectic
// Euler's free fall, x_n = x_0 - g dt^2 n (n + 1) / 2, and steps exactly as that half built as a
// body of its own.
TEST(FaceSplit, AHalfSplitOffFallsAsABodyOfItsOwn) {
  LatticeDesc desc = tissue_box({3, 3, 10});
  desc.materials[0].mass_damping = 0.0;
  const Model model = build(desc);
  Constraints constraints(model);
  ASSERT_TRUE(constraints.fix_box(model, {-1, -1, 0.0999}, {1, 1, 1}).ok());  // its top
  Result<FaceSplit> split = split_faces(model, rest_state(model), constraints, faces_below_layer(model, 5));
  ASSERT_TRUE(split.ok()) << split.message();
  const Model& after = split->model;
  ASSERT_EQ(split->pieces, 2);

  LatticeDesc lower_desc = desc;  // the lower half alone
  lower_desc.cells.clear();
  for (const Eigen::Vector3i& cell : desc.cells) {
    if (cell.z() < 5) lower_desc.cells.push_back(cell);
  }
  const Model lower = build(lower_desc);
  State lower_state = rest_state(lower);
  State state = split->state;
  // disturb both alike, so that the halves' internal forces are not zero
  const Eigen::Matrix3Xd disturbed = test::perturbed(lower, 3e-4, 9);
  std::vector<int> lower_node(static_cast<std::size_t>(after.num_nodes()), -1);  // its node in `lower`
  for (int c = 0; c < lower.num_cells(); ++c) {
    int in_after = -1;
    for (int a = 0; a < after.num_cells(); ++a) {
      if (after.cell_grid_index[static_cast<std::size_t>(a)] == lower.cell_grid_index[static_cast<std::size_t>(c)])
        in_after = a;
    }
    ASSERT_GE(in_after, 0);
    for (std::size_t k = 0; k < kCornersPerCell; ++k) {
      lower_node[static_cast<std::size_t>(after.cell_nodes[static_cast<std::size_t>(in_after)][k])] =
          lower.cell_nodes[static_cast<std::size_t>(c)][k];
    }
  }
  lower_state.positions = disturbed;
  for (int n = 0; n < after.num_nodes(); ++n) {
    if (lower_node[static_cast<std::size_t>(n)] >= 0)
      state.positions.col(n) = disturbed.col(lower_node[static_cast<std::size_t>(n)]);
  }
  const auto centre_z = [](const Model& m, const State& s, const std::vector<int>& nodes) {
    double mz = 0.0, total = 0.0;
    for (const int n : nodes) {
      mz += m.mass[n] * s.positions(2, n);
      total += m.mass[n];
    }
    return mz / total;
  };
  std::vector<int> free_nodes;
  for (int n = 0; n < after.num_nodes(); ++n) {
    if (lower_node[static_cast<std::size_t>(n)] >= 0) free_nodes.push_back(n);
  }
  const double start = centre_z(after, state, free_nodes);
  Loads loads;
  loads.gravity = {0, 0, -9.81};
  StepSettings settings;
  settings.time_step = 2e-4;
  Stepper stepper(after), lower_stepper(lower);
  const int steps = 400;
  for (int i = 0; i < steps; ++i) {
    ASSERT_TRUE(stepper.step(after, split->constraints, loads, settings, state).ok());
    ASSERT_TRUE(lower_stepper.step(lower, Constraints(lower), loads, settings, lower_state).ok());
  }
  const double fall = 9.81 * settings.time_step * settings.time_step * steps * (steps + 1) / 2.0;
  EXPECT_NEAR(start - centre_z(after, state, free_nodes), fall, 1e-9);
  double largest = 0.0;
  for (const int n : free_nodes) {
    largest = std::max(
        largest, (state.positions.col(n) - lower_state.positions.col(lower_node[static_cast<std::size_t>(n)])).norm());
  }
  EXPECT_LT(largest, 1e-12);  // the same forces, summed in another order
}

// A crack from one side to the middle of a block: one piece, its lattice surface closed and
// oriented, enclosing the block's volume (the crack's two faces enclose none); the crack's tip
// keeps its nodes.
TEST(FaceSplit, ACrackIsAClosedSurfaceAndOpensUnderTension) {
  const Model model = build(tissue_box({4, 2, 4}));
  std::vector<CellFace> crack;
  for (const Eigen::Vector3i& cell : model.cell_grid_index) {
    if (cell.z() == 1 && cell.x() < 2) crack.push_back({cell, 2});
  }
  Constraints constraints(model);
  Result<FaceSplit> split = split_faces(model, rest_state(model), constraints, crack);
  ASSERT_TRUE(split.ok()) << split.message();
  const Model& after = split->model;
  EXPECT_EQ(split->pieces, 1);
  EXPECT_EQ(split->nodes_added, 2 * 3);  // x = 0, 1 across the crack's 3 rows; its tip x = 2 is one
  const LatticeSurface surface = lattice_boundary_surface(after);
  EXPECT_TRUE(test::closed_and_oriented(surface.triangles));
  EXPECT_NEAR(lattice_volume(after), 32 * 1e-6, 1e-15);
  EXPECT_EQ(surface.triangles.cols(), lattice_boundary_surface(model).triangles.cols() + 2 * 2 * 4);

  // pulled apart along z, the crack opens at its mouth and not at its tip
  Constraints pull(after);
  ASSERT_TRUE(pull.prescribe_box_axis_displacement(after, {-1, -1, -1}, {1, 1, 0.0001}, 2, 0.0).ok());
  ASSERT_TRUE(pull.prescribe_box_axis_displacement(after, {-1, -1, 0.0399}, {1, 1, 1}, 2, 0.004).ok());
  ASSERT_TRUE(pull.fix_box(after, {-1, -1, -1}, {0.0001, 1, 0.0001}).ok());
  State state = split->state;
  StepSettings settings;
  settings.time_step = 2e-4;
  Stepper stepper(after);
  Loads loads;
  for (int i = 0; i < 3000; ++i) ASSERT_TRUE(stepper.step(after, pull, loads, settings, state).ok());
  const auto opening = [&](int x) {  // between the copies at (x, 1, 2)
    std::vector<int> copies;
    for (int n = 0; n < after.num_nodes(); ++n) {
      if (after.node_grid_index[static_cast<std::size_t>(n)] == Eigen::Vector3i(x, 1, 2)) copies.push_back(n);
    }
    return copies.size() == 2 ? (state.positions.col(copies[0]) - state.positions.col(copies[1])).norm() : 0.0;
  };
  EXPECT_GT(opening(0), 1e-3);  // a quarter of the pull or more at the mouth
  EXPECT_GT(opening(0), opening(1));
  EXPECT_EQ(opening(2), 0.0);  // the tip: one node
}

// A cell split from both its face neighbours in a 2 x 2 slab lets go of the diagonal one too
// (they touch along an edge, but the split cells lie between); with no cell between, an edge
// holds as before.
TEST(FaceSplit, AnEdgeHoldsOnlyWhereNoCellLiesBetween) {
  LatticeDesc desc = tissue_box({2, 2, 1});
  Model model = build(desc);
  Result<FaceSplit> split = split_faces(model, rest_state(model), Constraints(model), {{{0, 0, 0}, 0}, {{0, 0, 0}, 1}});
  ASSERT_TRUE(split.ok()) << split.message();
  EXPECT_EQ(split->pieces, 2);

  desc.cells = {{0, 0, 0}, {1, 1, 0}};  // a diagonal pair alone: joined along their edge
  model = build(desc);
  EXPECT_EQ(split_faces(model, rest_state(model), Constraints(model), {})->pieces, 1);

  desc.cells = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}};  // an L: splitting its corner cell off parts it
  model = build(desc);
  split = split_faces(model, rest_state(model), Constraints(model), {{{0, 0, 0}, 0}});
  ASSERT_TRUE(split.ok()) << split.message();
  EXPECT_EQ(split->pieces, 2);
}

TEST(FaceSplit, BadFacesAreRefusedWithTheirCause) {
  const Model model = build(tissue_box({2, 2, 2}));
  const State state = rest_state(model);
  const Constraints constraints(model);
  const auto message = [&](const std::vector<CellFace>& faces) {
    Result<FaceSplit> split = split_faces(model, state, constraints, faces);
    return split.ok() ? std::string("accepted") : split.message();
  };
  EXPECT_NE(message({{{0, 0, 0}, 3}}).find("split face 0 (cell (0, 0, 0), axis 3): the axis must be 0, 1 or 2"),
            std::string::npos)
      << message({{{0, 0, 0}, 3}});
  EXPECT_NE(message({{{0, 0, 0}, 0}, {{1, 0, 0}, 0}}).find("cell (2, 0, 0) is not a cell of the body"),
            std::string::npos)
      << message({{{1, 0, 0}, 0}});
  LatticeDesc twice = tissue_box({2, 2, 2});
  twice.split_faces = {{{0, 0, 0}, 1}, {{0, 0, 0}, 1}};
  Result<Model> listed_twice = build_model(twice);
  ASSERT_FALSE(listed_twice.ok());
  EXPECT_NE(listed_twice.message().find("split face 1 (cell (0, 0, 0), axis 1) is listed twice"), std::string::npos)
      << listed_twice.message();
  State short_state = state;
  short_state.positions.conservativeResize(3, 4);
  Result<FaceSplit> sizes = split_faces(model, short_state, constraints, {});
  ASSERT_FALSE(sizes.ok());
  EXPECT_NE(sizes.message().find("4 positions"), std::string::npos) << sizes.message();
}

// Cells removed beside a split: the split faces of removed cells go with them, and copies that
// only the removed cells kept apart are one node again, at their mean weighted by the mass each
// keeps, so that momentum falls by exactly what left.
TEST(FaceSplit, RemovingCellsBesideASplitKeepsMomentum) {
  const Model model = build(tissue_box({2, 2, 1}));
  State state = rest_state(model);
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> speed(-0.1, 0.1);
  Result<FaceSplit> split =
      split_faces(model, state, Constraints(model), {{{0, 0, 0}, 0}, {{0, 0, 0}, 1}});  // (0,0) split off
  ASSERT_TRUE(split.ok()) << split.message();
  State moving = split->state;
  for (Eigen::Index i = 0; i < moving.velocities.size(); ++i) moving.velocities.data()[i] = speed(rng);
  // take out (1,0) and (0,1): (0,0) and (1,1) now touch along an edge with nothing between
  std::vector<int> between;
  for (int c = 0; c < split->model.num_cells(); ++c) {
    const Eigen::Vector3i& g = split->model.cell_grid_index[static_cast<std::size_t>(c)];
    if (g.x() != g.y()) between.push_back(c);
  }
  Result<CellRemoval> removal = remove_cells(split->model, moving, split->constraints, between);
  ASSERT_TRUE(removal.ok()) << removal.message();
  EXPECT_EQ(removal->pieces, 1);
  EXPECT_TRUE(removal->model.split_faces.empty());
  EXPECT_LE(
      (momentum(split->model, moving) - momentum(removal->model, removal->state) - removal->removed_momentum).norm(),
      1e-15);
  EXPECT_NEAR(removal->model.total_mass(), cells_mass(removal->model), 1e-15);
}

// Random splits and removals one after another, the body stepped between them (explicit and
// implicit): mass is its cells', momentum is kept by each split and falls by what each removal
// took, the lattice surface stays closed,
// oriented and encloses the cells' volume, states stay finite. CUBESPRING_RANDOM_SPLITS sets the
// count.
TEST(FaceSplit, RandomSplitsAndRemovalsLeaveASoundBody) {
  const char* count_text = std::getenv("CUBESPRING_RANDOM_SPLITS");
  const int cuts = count_text != nullptr ? std::atoi(count_text) : 40;
  std::mt19937 rng(2027);
  const Model start = build(tissue_box({10, 10, 10}));
  Model model = start;
  State state = rest_state(model);
  Constraints constraints(model);
  Loads loads;
  loads.gravity = {0, 0, -9.81};
  std::uniform_real_distribution<double> unit(0.0, 10.0);
  for (int cut = 0; cut < cuts; ++cut) {
    if (model.num_cells() < 64) {
      model = start;
      state = rest_state(model);
      constraints = Constraints(model);
    }
    // a blade: the faces crossed by a random plane within a random disc, or a few cells burnt
    if (rng() % 3 != 0) {
      const Eigen::Vector3d centre(unit(rng), unit(rng), unit(rng));
      const Eigen::Vector3d normal = Eigen::Vector3d(unit(rng) - 5, unit(rng) - 5, unit(rng) - 5).normalized();
      const double radius = 1.0 + unit(rng) / 2;
      std::vector<CellFace> faces;
      for (const Eigen::Vector3i& cell : model.cell_grid_index) {
        for (int axis = 0; axis < 3; ++axis) {
          const Eigen::Vector3d a = cell.cast<double>().array() + 0.5;
          Eigen::Vector3d b = a;
          b[axis] += 1.0;
          const double da = (a - centre).dot(normal), db = (b - centre).dot(normal);
          if ((da < 0) == (db < 0)) continue;
          const Eigen::Vector3d crossing = a + da / (da - db) * (b - a);
          if ((crossing - centre).norm() < radius) faces.push_back({cell, axis});
        }
      }
      // only faces between two cells of the body
      std::vector<CellFace> inside;
      for (const CellFace& face : faces) {
        Eigen::Vector3i next = face.cell;
        next[face.axis] += 1;
        if (std::find(model.cell_grid_index.begin(), model.cell_grid_index.end(), next) != model.cell_grid_index.end())
          inside.push_back(face);
      }
      const Eigen::Vector3d before = momentum(model, state);
      Result<FaceSplit> split = split_faces(model, state, constraints, inside);
      ASSERT_TRUE(split.ok()) << "cut " << cut << ": " << split.message();
      model = std::move(split->model);
      state = std::move(split->state);
      constraints = std::move(split->constraints);
      ASSERT_LE((momentum(model, state) - before).norm(), 1e-13 * momentum_scale(model, state)) << "cut " << cut;
    } else {
      std::uniform_int_distribution<int> pick(0, model.num_cells() - 1);
      std::vector<int> cells;
      for (int i = 0; i < 1 + static_cast<int>(rng() % 20); ++i) cells.push_back(pick(rng));
      if (cells.size() >= static_cast<std::size_t>(model.num_cells())) continue;
      const Eigen::Vector3d before = momentum(model, state);
      Result<CellRemoval> removal = remove_cells(model, state, constraints, cells);
      ASSERT_TRUE(removal.ok()) << "cut " << cut << ": " << removal.message();
      // the removed cells' momentum leaves, whether the removal parts or joins a node's copies
      ASSERT_LE((momentum(removal->model, removal->state) + removal->removed_momentum - before).norm(),
                1e-13 * momentum_scale(model, state))
          << "cut " << cut;
      model = std::move(removal->model);
      state = std::move(removal->state);
      constraints = std::move(removal->constraints);
    }
    ASSERT_NEAR(model.total_mass(), cells_mass(model), 1e-12 * cells_mass(model)) << "cut " << cut;
    const LatticeSurface surface = lattice_boundary_surface(model);
    ASSERT_TRUE(test::closed_and_oriented(surface.triangles)) << "cut " << cut;
    ASSERT_NEAR(lattice_volume(model), model.num_cells() * model.rest_cell_volume(),
                1e-9 * model.num_cells() * model.rest_cell_volume())
        << "cut " << cut;
    Stepper stepper(model);
    StepSettings settings;
    settings.time_step = cut % 2 == 0 ? 2e-4 : 2e-3;
    settings.integrator = cut % 2 == 0 ? Integrator::kSymplecticEuler : Integrator::kImplicitEuler;
    for (int i = 0; i < 3; ++i) {
      const StepReport report = stepper.step(model, constraints, loads, settings, state);
      ASSERT_TRUE(report.ok()) << "cut " << cut << ": " << report.message;
    }
    ASSERT_TRUE(state.positions.allFinite() && state.velocities.allFinite()) << "cut " << cut;
  }
}

}  // namespace
}  // namespace cubespring
