// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The explicit stability limit against the body's spectrum (dense eigenvalues of M^-1/2 K M^-1/2)
// and against what symplectic Euler does just below and just above it.
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cubespring/integrator.h"
#include "cubespring/stable_time_step.h"
#include "test_support.h"

namespace cubespring {
namespace {

struct Body {
  std::string name;
  LatticeDesc desc;
};

std::vector<Body> bodies() {
  Material tissue = test::notes_material(0.3);
  Material stiff = test::notes_material(0.45);
  stiff.young_modulus = 8e5;
  std::vector<Body> list;
  list.push_back({"cubes 4x3x2", box_lattice({4, 3, 2}, Eigen::Vector3d::Constant(0.01), tissue)});
  list.push_back({"bricks 3x3x3", box_lattice({3, 3, 3}, {0.01, 0.013, 0.008}, tissue)});
  Body exact{"exact-bending 4x2x2", box_lattice({4, 2, 2}, Eigen::Vector3d::Constant(0.01), tissue)};
  exact.desc.model = CellModel::kExactBending;
  list.push_back(exact);
  // an L of two materials: the stiff cells set the highest frequency
  Body shape{"L with a stiff foot", {}};
  shape.desc.materials = {tissue, stiff};
  for (int x = 0; x < 4; ++x) {
    for (int z = 0; z < 2; ++z) {
      shape.desc.cells.push_back({x, 0, z});
      shape.desc.cell_material.push_back(x == 0 ? 1 : 0);
    }
  }
  for (int y = 1; y < 4; ++y) {
    shape.desc.cells.push_back({0, y, 0});
    shape.desc.cell_material.push_back(0);
  }
  list.push_back(shape);
  return list;
}

double true_max_frequency(const Model& model) {
  const Eigen::MatrixXd k = test::dense_stiffness(model, model.rest_positions, StiffnessKind::kPositiveSemiDefinite);
  Eigen::VectorXd scale(k.rows());
  for (Eigen::Index i = 0; i < k.rows(); ++i) scale[i] = 1.0 / std::sqrt(model.mass[i / 3]);
  const Eigen::MatrixXd a = scale.asDiagonal() * k * scale.asDiagonal();
  return std::sqrt(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(a, Eigen::EigenvaluesOnly).eigenvalues().maxCoeff());
}

TEST(StableTimeStep, LanczosFindsTheHighestFrequencyAndGershgorinBoundsIt) {
  for (const Body& body : bodies()) {
    Result<Model> model = build_model(body.desc);
    ASSERT_TRUE(model.ok()) << body.name << ": " << model.message();
    const double exact = true_max_frequency(*model);
    const double lanczos = max_frequency(*model, FrequencyBound::kLanczos);
    const double gershgorin = max_frequency(*model, FrequencyBound::kGershgorin);
    EXPECT_GE(lanczos, exact * (1.0 - 1e-9)) << body.name;
    EXPECT_LE(lanczos, exact * 1.001) << body.name;
    EXPECT_GE(gershgorin, exact) << body.name;
    EXPECT_NEAR(max_stable_time_step(*model, FrequencyBound::kLanczos), 2.0 / lanczos, 1e-12 / lanczos) << body.name;
  }
}

TEST(StableTimeStep, StiffnessDampingShortensTheStep) {
  Material damped = test::notes_material(0.3);
  damped.stiffness_damping = 1e-4;
  const Model model = test::box_model({3, 2, 2}, damped);
  const double omega = max_frequency(model, FrequencyBound::kLanczos);
  const double zeta = 0.5 * 1e-4 * omega;
  EXPECT_NEAR(max_stable_time_step(model, FrequencyBound::kLanczos) * omega / 2.0, std::sqrt(1.0 + zeta * zeta) - zeta,
              1e-12);
}

// Symplectic Euler on an undamped free body with random velocities: bounded at 0.99 of the
// Lanczos limit for 5000 steps, blown up (caught by the speed check) at 1.02 of it.
TEST(StableTimeStep, SymplecticEulerIsStableJustBelowTheLanczosLimitAndNotJustAbove) {
  Material m;  // E = 1 MPa, nu = 0.3, no damping
  const Model model = test::box_model({4, 3, 3}, m);
  const double limit = max_stable_time_step(model, FrequencyBound::kLanczos);
  EXPECT_GT(max_stable_time_step(model, FrequencyBound::kGershgorin), 0.5 * limit);
  EXPECT_LT(max_stable_time_step(model, FrequencyBound::kGershgorin), limit);
  for (const auto& [factor, stable] : {std::pair{0.99, true}, std::pair{1.02, false}}) {
    State state = rest_state(model);
    std::mt19937 random(3);
    std::uniform_real_distribution<double> uniform(-0.01, 0.01);
    for (Eigen::Index i = 0; i < state.velocities.size(); ++i) state.velocities.data()[i] = uniform(random);
    StepSettings settings;
    settings.time_step = factor * limit;
    Stepper stepper(model);
    StepReport report;
    double fastest = 0.0;
    for (int i = 0; i < 5000 && report.ok(); ++i) {
      report = stepper.step(model, Constraints(model), Loads{}, settings, state);
      fastest = std::max(fastest, state.velocities.colwise().norm().maxCoeff());
    }
    EXPECT_EQ(report.ok(), stable) << factor << " x " << limit << " s: " << report.message;
    if (stable) {
      EXPECT_LT(fastest, 1.0) << "velocities of 1 cm/s grew to " << fastest << " m/s";
    }
  }
}

// A block of 5 kPa tissue, neo-Hookean, of brick cells 10 x 12 x 8 mm.
LatticeDesc neo_hookean_bricks(const Eigen::Vector3i& counts) {
  Material tissue;
  tissue.young_modulus = 5e3;
  tissue.poisson_ratio = 0.45;
  LatticeDesc desc = box_lattice(counts, {0.01, 0.012, 0.008}, tissue);
  desc.law = CellLaw::kNeoHookean;
  return desc;
}

// The thin-cell factor against the geometry it reads: a brick cell's thickness across each pair
// of faces is its volume over the area of the other two, whatever the shear.
TEST(CompressedStepFactor, FollowsTheThinnestCellAndOnlyTheNeoHookeanLaw) {
  LatticeDesc desc = neo_hookean_bricks({1, 1, 1});
  const Model model = build_model(desc).value();
  EXPECT_EQ(compressed_step_factor(model, model.rest_positions), 1.0);

  // the top face lowered to 30% of the height, then slid 2 mm along x: the thickness across z
  // stays 30% (a shear keeps volume and base; across x it is 0.0024 / |(0.002, 0.0024)| = 77%),
  // so 0.3 / 0.5 of the rest step
  Eigen::Matrix3Xd squeezed = model.rest_positions;
  for (int corner = 4; corner < 8; ++corner) {
    const int node = model.cell_nodes[0][static_cast<std::size_t>(corner)];
    squeezed(2, node) = 0.3 * 0.008;
    squeezed(0, node) += 0.002;
  }
  EXPECT_NEAR(compressed_step_factor(model, squeezed), 0.3 / kThickEnough, 1e-12);

  // a cell at 60% keeps the rest step; an inverted one asks for the least, 0.2
  Eigen::Matrix3Xd mild = model.rest_positions;
  Eigen::Matrix3Xd inverted = model.rest_positions;
  for (int corner = 4; corner < 8; ++corner) {
    const int node = model.cell_nodes[0][static_cast<std::size_t>(corner)];
    mild(2, node) = 0.6 * 0.008;
    inverted(2, node) = -0.2 * 0.008;
  }
  EXPECT_EQ(compressed_step_factor(model, mild), 1.0);
  EXPECT_EQ(compressed_step_factor(model, inverted), 0.2);

  // stretched flat: 2 times as wide each way and 0.4 as thick; across z the thickness is 0.4 and
  // the face 4 times its rest area, so 0.4 / 0.5 / sqrt(4 / 2) of the rest step (a cell's
  // stiffness across grows with its face); a face at most twice its rest area counts as at rest
  const Eigen::Matrix3d flat = Eigen::Vector3d(2.0, 2.0, 0.4).asDiagonal();
  EXPECT_NEAR(compressed_step_factor(model, flat * model.rest_positions), 0.4 / kThickEnough / std::sqrt(2.0), 1e-12);
  const Eigen::Matrix3d wide = Eigen::Vector3d(1.4, 1.4, 0.4).asDiagonal();
  EXPECT_NEAR(compressed_step_factor(model, wide * model.rest_positions), 0.4 / kThickEnough, 1e-12);

  // the springs law's springs are linear in length: no thinner step
  desc.law = CellLaw::kSprings;
  const Model springs = build_model(desc).value();
  EXPECT_EQ(compressed_step_factor(springs, squeezed), 1.0);
}

// Many cells: the factor is that of the thinnest cell across its thinnest axis, as a brute
// force over every cell and axis finds it by the definition (stable_time_step.h), for bodies
// jittered at random, some stretched flat and some squeezed until cells turn inside out. 576
// cells: the search goes through them in blocks (of 256), the last one partly filled.
TEST(CompressedStepFactor, IsTheThinnestOfManyCells) {
  const Model model = build_model(neo_hookean_bricks({12, 8, 6})).value();
  const auto by_definition = [&](const Eigen::Matrix3Xd& x) {
    double thinnest = 1.0;
    for (int c = 0; c < model.num_cells(); ++c) {
      Eigen::Vector3d edge[3];
      for (int axis = 0; axis < 3; ++axis) {
        edge[axis].setZero();
        for (int corner = 0; corner < 8; ++corner) {
          const double side = ((corner >> axis) & 1) != 0 ? 0.25 : -0.25;
          edge[axis] += side * x.col(model.cell_nodes[c][static_cast<std::size_t>(corner)]);
        }
      }
      const double volume = edge[0].dot(edge[1].cross(edge[2]));
      for (int axis = 0; axis < 3; ++axis) {
        const double face = edge[(axis + 1) % 3].cross(edge[(axis + 2) % 3]).norm();
        const double rest_face = model.cell_size[(axis + 1) % 3] * model.cell_size[(axis + 2) % 3];
        const double thickness = std::max(volume / face / model.cell_size[axis], 0.0);
        thinnest = std::min(thinnest, thickness / std::sqrt(std::max(face / (2.0 * rest_face), 1.0)));
      }
    }
    return std::clamp(thinnest / kThickEnough, 0.2, 1.0);
  };
  std::mt19937 random(7);
  std::uniform_real_distribution<double> jitter(-0.003, 0.003);
  int between = 0;                // trials whose factor is neither bound: a cell decides it
  int inverted = 0, widened = 0;  // trials with a cell inside out, a face over twice its rest area
  for (int trial = 0; trial < 60; ++trial) {
    Eigen::Matrix3Xd x = model.rest_positions;
    if (trial % 3 == 1) x = Eigen::Vector3d(2.2, 1.9, 0.6).asDiagonal() * x;  // stretched flat
    if (trial % 3 == 2) x = Eigen::Vector3d(1.0, 1.0, 0.3).asDiagonal() * x;  // squeezed: some turn inside out
    for (Eigen::Index n = 0; n < x.cols(); ++n) {
      for (int k = 0; k < 3; ++k) x(k, n) += jitter(random);
    }
    SCOPED_TRACE(trial);
    const double factor = compressed_step_factor(model, x);
    EXPECT_NEAR(factor, by_definition(x), 1e-14);
    between += factor > 0.2 && factor < 1.0 ? 1 : 0;
    bool any_inverted = false, any_widened = false;
    for (int c = 0; c < model.num_cells(); ++c) {
      any_inverted = any_inverted || cell_signed_volume(model, x, c) <= 0.0;
    }
    any_widened = trial % 3 == 1;  // 2.2 x 1.9 of the rest faces normal to z, before the jitter
    inverted += any_inverted ? 1 : 0;
    widened += any_widened ? 1 : 0;
  }
  EXPECT_GT(between, 15);
  EXPECT_GT(inverted, 0);
  EXPECT_GT(widened, 0);
  // a position that is not a number asks for the least factor, as an inverted cell does
  Eigen::Matrix3Xd lost = model.rest_positions;
  lost(0, 5) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(compressed_step_factor(model, lost), 0.2);
  lost = model.rest_positions;  // and in the last block
  lost(2, model.num_nodes() - 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(compressed_step_factor(model, lost), 0.2);
}

// A bar of 7 x across x ny x nz cubes of 5 kPa neo-Hookean tissue; with an inclusion, the cells at
// x = 0 are of 40 kPa.
LatticeDesc soft_bar(int ny, int nz, bool inclusion) {
  Material soft;
  soft.young_modulus = 5e3;
  soft.poisson_ratio = 0.45;
  LatticeDesc desc = box_lattice({7, ny, nz}, Eigen::Vector3d::Constant(0.01), soft);
  desc.law = CellLaw::kNeoHookean;
  if (inclusion) {
    Material stiff = soft;
    stiff.young_modulus = 4e4;
    desc.materials.push_back(stiff);
    for (const Eigen::Vector3i& cell : desc.cells) desc.cell_material.push_back(cell.x() == 0 ? 1 : 0);
  }
  return desc;
}

// A bar of 7 cubes of 5 kPa tissue along x whose first is a 40 kPa inclusion, and the same bar
// all soft. A cell's rest step comes from the Gershgorin bounds of the nodes of the cell and of the
// cells around it: cell x reads the nodes x - 1 .. x + 2, so the inclusion (nodes 0 and 1, whose
// rows hold its stiffness) holds cells 0 to 2 and no cell from 3 on, which have the steps of the
// all-soft bar to the bit. The least is the body's step.
TEST(CellStableTimeSteps, ACellTwoCellsFromAStiffInclusionKeepsTheStepOfSoftTissue) {
  LatticeDesc all_soft = soft_bar(2, 2, false);
  all_soft.model = CellModel::kExactBending;
  LatticeDesc inclusion = soft_bar(2, 2, true);
  inclusion.model = CellModel::kExactBending;
  const Model model = build_model(inclusion).value();
  const Model soft_model = build_model(all_soft).value();
  const Eigen::VectorXd steps = cell_stable_time_steps(model);
  const Eigen::VectorXd soft_steps = cell_stable_time_steps(soft_model);
  ASSERT_EQ(steps.size(), model.num_cells());
  EXPECT_EQ(steps.minCoeff(), max_stable_time_step(model));
  EXPECT_EQ(soft_steps.minCoeff(), max_stable_time_step(soft_model));
  // the least step at each x (cells come in columns of 2 x 2 along x)
  std::vector<double> at_x(7, std::numeric_limits<double>::infinity());
  for (int c = 0; c < model.num_cells(); ++c) {
    const int x = model.cell_grid_index[static_cast<std::size_t>(c)].x();
    at_x[static_cast<std::size_t>(x)] = std::min(at_x[static_cast<std::size_t>(x)], steps[c]);
    if (x >= 3) {
      EXPECT_EQ(steps[c], soft_steps[c]) << "cell " << c << " at x = " << x;
    }
  }
  EXPECT_EQ(at_x[0], steps.minCoeff());
  EXPECT_EQ(at_x[1], at_x[0]);
  EXPECT_LT(at_x[2], 0.8 * at_x[3]) << "its neighbour's node 1 bears the inclusion";
  EXPECT_GT(at_x[3], 1.5 * at_x[0]) << "soft tissue's step, against 40 kPa's";
}

// One tissue throughout: every cell keeps the body's step. Gershgorin's bound over a cell's
// neighbourhood is up to 35% longer in a block's middle than at its corners (the bound's slack,
// not the tissue's); a probe's thin cells that planned on it made the drag's force ring (a 5 kPa
// block: 11.2% rough against 1.7%). Fails without the cap: the middle cells' 0.98 ms against 0.73.
TEST(CellStableTimeSteps, OneTissueThroughoutKeepsTheBodysStepInEveryCell) {
  Material tissue;
  tissue.young_modulus = 5e3;
  tissue.poisson_ratio = 0.45;
  tissue.density = 1060;
  LatticeDesc block = box_lattice({8, 8, 4}, Eigen::Vector3d::Constant(0.005), tissue);
  block.model = CellModel::kExactBending;
  const Model model = build_model(block).value();
  const Eigen::VectorXd steps = cell_stable_time_steps(model);
  EXPECT_EQ(steps.minCoeff(), max_stable_time_step(model));
  EXPECT_EQ(steps.maxCoeff(), steps.minCoeff());
}

// The step thin cells allow: each thin cell its factor times its own rest step, the least of
// them; infinity while none is thin. A cell squeezed to 30% far from the inclusion allows 0.6 of
// its own step, longer than the inclusion's whole step; beside the inclusion, 0.6 of that.
TEST(CompressedTimeStep, EachThinCellAllowsItsFactorTimesItsOwnStep) {
  LatticeDesc desc = soft_bar(1, 1, true);
  const Model model = build_model(desc).value();
  const Eigen::VectorXd steps = cell_stable_time_steps(model);
  EXPECT_EQ(compressed_time_step(model, model.rest_positions, steps), std::numeric_limits<double>::infinity());

  // cell x's top face lowered to 30% of its height: the thickness across z of that cell (its
  // neighbours' faces are slanted, thicker than half)
  const auto squeeze = [&](Eigen::Matrix3Xd x, int cell) {
    for (int corner = 4; corner < 8; ++corner) x(2, model.cell_nodes[static_cast<std::size_t>(cell)][corner]) = 0.003;
    return x;
  };
  const auto cell_at = [&](int x) {
    for (int c = 0; c < model.num_cells(); ++c) {
      if (model.cell_grid_index[static_cast<std::size_t>(c)].x() == x) return c;
    }
    return -1;
  };
  const int far = cell_at(5), near = cell_at(1);
  const Eigen::Matrix3Xd far_thin = squeeze(model.rest_positions, far);
  ASSERT_NEAR(compressed_step_factor(model, far_thin), 0.3 / kThickEnough, 1e-12);
  EXPECT_NEAR(compressed_time_step(model, far_thin, steps), 0.3 / kThickEnough * steps[far], 1e-12 * steps[far]);
  EXPECT_GT(compressed_time_step(model, far_thin, steps), steps.minCoeff());
  const Eigen::Matrix3Xd both_thin = squeeze(far_thin, near);
  EXPECT_NEAR(compressed_time_step(model, both_thin, steps), 0.3 / kThickEnough * steps[near], 1e-12 * steps[near]);
  EXPECT_LT(steps[near], steps[far]);

  EXPECT_THROW(compressed_time_step(model, far_thin, steps.head(3)), std::invalid_argument);
  desc.law = CellLaw::kSprings;  // linear springs: a thin cell is no stiffer
  const Model springs = build_model(desc).value();
  EXPECT_EQ(compressed_time_step(springs, far_thin, cell_stable_time_steps(springs)),
            std::numeric_limits<double>::infinity());
}

}  // namespace
}  // namespace cubespring
