// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Selective mass scaling (mass_scaling.h): the step it buys against Gershgorin's bound worked out
// by brute force from the dense stiffness, its budget, and a stiff inclusion stepped at the longer
// step: stable where the unscaled body blows up, and at rest where the unscaled body rests.
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include <gtest/gtest.h>

#include "cubespring/integrator.h"
#include "cubespring/mass_scaling.h"
#include "cubespring/stable_time_step.h"
#include "test_support.h"

namespace cubespring {
namespace {

// A 6 x 3 x 3 block of 5 kPa tissue (1 cm cells) with a 40 kPa inclusion of 2 x 1 x 1 cells at
// its core, as the demo's tumour sits in its liver.
Model block_with_inclusion(double mass_damping = 0.0) {
  Material tissue;
  tissue.young_modulus = 5e3;
  tissue.poisson_ratio = 0.45;
  tissue.density = 1060;
  tissue.mass_damping = mass_damping;
  Material tumour = tissue;
  tumour.young_modulus = 4e4;
  tumour.density = 1100;
  LatticeDesc desc = box_lattice({6, 3, 3}, Eigen::Vector3d::Constant(0.01), tissue);
  desc.model = CellModel::kExactBending;
  desc.materials = {tissue, tumour};
  desc.cell_material.assign(desc.cells.size(), 0);
  for (std::size_t c = 0; c < desc.cells.size(); ++c) {
    const Eigen::Vector3i& cell = desc.cells[c];
    if ((cell.x() == 2 || cell.x() == 3) && cell.y() == 1 && cell.z() == 1) desc.cell_material[c] = 1;
  }
  Result<Model> model = build_model(desc);
  EXPECT_TRUE(model.ok()) << model.message();
  return std::move(model).value();
}

// Each node's largest row sum of |K| from the dense stiffness at rest.
Eigen::VectorXd row_sums(const Model& model) {
  const Eigen::MatrixXd k = test::dense_stiffness(model, model.rest_positions, StiffnessKind::kPositiveSemiDefinite);
  Eigen::VectorXd sums = Eigen::VectorXd::Zero(model.num_nodes());
  for (Eigen::Index row = 0; row < k.rows(); ++row) {
    sums[row / 3] = std::max(sums[row / 3], k.row(row).cwiseAbs().sum());
  }
  return sums;
}

TEST(MassScaling, BuysTheLowestGershgorinBoundItsBudgetAffords) {
  const Model original = block_with_inclusion();
  Model model = original;
  const double budget = 0.05 * original.total_mass();
  const MassScaling scaling = add_mass_for_time_step(model, 0.05);

  EXPECT_EQ(scaling.time_step_before, max_stable_time_step(original));
  EXPECT_EQ(scaling.time_step_after, max_stable_time_step(model));
  EXPECT_GT(scaling.time_step_after, 1.2 * scaling.time_step_before) << "the inclusion set the step";
  EXPECT_NEAR(scaling.added_mass, budget, 1e-9 * budget) << "the whole budget is spent";
  EXPECT_NEAR(scaling.added_fraction, 0.05, 1e-9);
  ASSERT_EQ(model.inertial_mass.size(), model.num_nodes());
  EXPECT_NEAR((model.inertial_mass - model.mass).sum(), scaling.added_mass, 1e-12 * budget);
  EXPECT_EQ(model.mass, original.mass) << "the weight is unchanged";

  // against the definition: every node's bound is at most the target, those that took inertia
  // are at it, and any lower target costs more than the budget
  const double target = std::pow(2.0 / scaling.time_step_after, 2);  // no stiffness damping
  const Eigen::VectorXd sums = row_sums(original);
  int took = 0;
  for (int n = 0; n < model.num_nodes(); ++n) {
    EXPECT_LE(sums[n] / model.inertial_mass[n], target * (1 + 1e-9)) << "node " << n;
    EXPECT_GE(model.inertial_mass[n], model.mass[n]) << "node " << n;
    if (model.inertial_mass[n] > model.mass[n]) {
      ++took;
      EXPECT_NEAR(sums[n] / model.inertial_mass[n], target, 1e-9 * target) << "node " << n;
    }
  }
  EXPECT_EQ(took, scaling.nodes);
  EXPECT_LT(took, model.num_nodes() / 2) << "the bulk keeps its mass";
  const auto cost = [&](double lambda) {
    double added = 0.0;
    for (int n = 0; n < model.num_nodes(); ++n) added += std::max(0.0, sums[n] / lambda - original.mass[n]);
    return added;
  };
  EXPECT_LE(cost(target), budget * (1 + 1e-9));
  EXPECT_GT(cost(target * (1 - 1e-6)), budget);
}

TEST(MassScaling, NothingAddedLeavesTheModelAndWrongFractionsThrow) {
  const Model original = block_with_inclusion();
  Model model = original;
  const MassScaling none = add_mass_for_time_step(model, 0.0);
  EXPECT_EQ(none.nodes, 0);
  EXPECT_EQ(none.added_mass, 0.0);
  EXPECT_EQ(none.time_step_after, none.time_step_before);
  EXPECT_EQ(model.inertial_mass.size(), 0);
  EXPECT_EQ(&model.inertia(), &model.mass);
  for (const double wrong : {-0.01, 1.5, std::numeric_limits<double>::quiet_NaN()}) {
    EXPECT_THROW(add_mass_for_time_step(model, wrong), std::invalid_argument) << wrong;
  }
  // a second call replaces the first's inertia rather than adding to it
  const MassScaling first = add_mass_for_time_step(model, 0.02);
  const MassScaling again = add_mass_for_time_step(model, 0.02);
  EXPECT_EQ(first.time_step_after, again.time_step_after);
  EXPECT_EQ(again.time_step_before, none.time_step_before);
}

// The block clamped at x = 0 under gravity, stepped with symplectic Euler for `seconds` at
// `step`; the x = 6 cm end's mean sag [m], or NaN if the step failed.
double tip_sag(const Model& model, double step, double seconds) {
  Constraints constraints(model);
  EXPECT_TRUE(constraints.fix_box(model, Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(1e-9, 1, 1)).ok());
  Loads loads;
  loads.gravity = Eigen::Vector3d(0, 0, -9.81);
  StepSettings settings;
  settings.time_step = step;
  State state = rest_state(model);
  Stepper stepper(model);
  for (int i = 0; i < static_cast<int>(seconds / step); ++i) {
    if (!stepper.step(model, constraints, loads, settings, state).ok()) return std::numeric_limits<double>::quiet_NaN();
  }
  double sag = 0.0;
  int count = 0;
  for (int n = 0; n < model.num_nodes(); ++n) {
    if (model.rest_positions(0, n) > 0.06 - 1e-9) {
      sag += state.positions(2, n) - model.rest_positions(2, n);
      ++count;
    }
  }
  return sag / count;
}

// Stepped at 0.9 of the longer step, the scaled block comes to the unscaled one's rest (gravity
// weighs the mass, not the inertia), while the unscaled block blows up at that step.
TEST(MassScaling, TheLongerStepIsStableAndKeepsTheEquilibrium) {
  const Model original = block_with_inclusion(200.0);  // damped to rest within the run
  Model scaled = original;
  const MassScaling scaling = add_mass_for_time_step(scaled, 0.2);
  std::printf("20%% of the mass on %d of %d nodes: the step %.3f ms, %.2fx\n", scaling.nodes, scaled.num_nodes(),
              1e3 * scaling.time_step_after, scaling.time_step_after / scaling.time_step_before);
  const double longer = 0.9 * scaling.time_step_after;
  const double reference = tip_sag(original, 0.9 * scaling.time_step_before, 3.0);
  ASSERT_TRUE(std::isfinite(reference));
  ASSERT_LT(reference, -1e-4) << "it sags";
  const double sag = tip_sag(scaled, longer, 3.0);
  EXPECT_NEAR(sag, reference, 1e-4 * std::abs(reference));
  EXPECT_TRUE(std::isnan(tip_sag(original, longer, 1.5))) << "unscaled, " << longer << " s is beyond its stable step";
}

}  // namespace
}  // namespace cubespring
