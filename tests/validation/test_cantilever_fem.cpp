// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The cantilever under self-weight against CalculiX (C3D20R, on meshes whose nodes include the
// lattice nodes): linear at several nu, refinement, and large deflection (NLGEOM, neo-Hookean and
// St Venant-Kirchhoff). Each test prints a table row; the README records them.
#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "calculix_beam.h"
#include "cubespring/validation/calculix_result.h"
#include "cubespring/validation/experiments.h"
#ifdef CUBESPRING_CLI_PATH
#include <nlohmann/json.hpp>

#include "cli/tool_run.h"
#endif

namespace cubespring {
namespace {

using validation::BeamReference;
using validation::BeamReferenceSpec;

constexpr double kLength = 0.16;
constexpr double kWidth = 0.04;

struct Comparison {
  double lattice_tip = 0, reference_tip = 0;
  double tip_error = 0;   // relative
  double mean_error = 0;  // nodal |u - u_ref| / |reference tip|
  double max_error = 0;
};

std::optional<BeamReference> reference(const BeamReferenceSpec& spec, const std::string& name) {
  if (!validation::calculix_available()) return std::nullopt;
  BeamReferenceSpec s = spec;
  s.work_dir = ::testing::TempDir() + "cubespring_ccx_" + name;
  validation::BeamResult result = validation::compute_beam_reference(s);
  EXPECT_TRUE(result.reference.has_value()) << result.error;
  return result.reference;
}

// The lattice beam with the reference's material; linear runs use a thousandth of gravity and
// scale back (the lattice solver is nonlinear; at that load it is linear to 1e-6).
ExperimentResult lattice(const BeamReferenceSpec& spec, const Eigen::Vector3i& cells, bool linear,
                         CellModel model = CellModel::kBaudet2007) {
  ExperimentSettings settings;
  settings.model = model;
  settings.material.young_modulus = spec.young_modulus;
  settings.material.poisson_ratio = spec.poisson_ratio;
  settings.material.density = spec.density;
  settings.cells = cells;
  settings.cell_size = Eigen::Vector3d::Constant(spec.size.x() / cells.x());
  settings.gravity = linear ? spec.gravity * 1e-3 : spec.gravity;
  Result<ExperimentResult> result = run_experiment(Experiment::kCantilever, settings);
  if (!result) throw std::runtime_error(result.message());
  ExperimentResult r = std::move(result).value();
  if (linear) {
    r.state.positions = r.model.rest_positions + 1e3 * (r.state.positions - r.model.rest_positions);
    *r.tip_deflection *= 1e3;
  }
  return r;
}

Comparison compare(const ExperimentResult& lattice_result, const BeamReference& ref) {
  Comparison c;
  c.lattice_tip = *lattice_result.tip_deflection;
  c.reference_tip = ref.tip_deflection();
  c.tip_error = c.lattice_tip / c.reference_tip - 1.0;
  const Model& model = lattice_result.model;
  for (int n = 0; n < model.num_nodes(); ++n) {
    const Eigen::Vector3d rest = model.rest_positions.col(n);
    const std::optional<Eigen::Vector3d> expected = ref.displacement_at(rest);
    EXPECT_TRUE(expected.has_value()) << "the reference mesh lacks lattice node " << rest.transpose();
    if (!expected) continue;
    const Eigen::Vector3d u = lattice_result.state.positions.col(n) - rest;
    const double error = (u - *expected).norm() / std::abs(c.reference_tip);
    c.mean_error += error / model.num_nodes();
    c.max_error = std::max(c.max_error, error);
  }
  return c;
}

void print_row(const std::string& label, const Comparison& c) {
  std::printf("| %s | %.4f | %.4f | %+.2f%% | %.2f%% | %.2f%% |\n", label.c_str(), 1e3 * c.lattice_tip,
              1e3 * c.reference_tip, 100 * c.tip_error, 100 * c.mean_error, 100 * c.max_error);
  std::fflush(stdout);
}

BeamReferenceSpec beam(double nu, const Eigen::Vector3i& elements) {
  BeamReferenceSpec spec;
  spec.size = {kLength, kWidth, kWidth};
  spec.elements = elements;
  spec.poisson_ratio = nu;
  return spec;
}

#define REQUIRE_CALCULIX() \
  if (!validation::calculix_available()) GTEST_SKIP() << "ccx (calculix-ccx) is not installed"

class LinearCantilever : public ::testing::TestWithParam<std::pair<double, double>> {};

// 16x4x4 lattice against C3D20R at h/2. The paper's model is too stiff, more so as nu grows; the
// exact-bending model must stay within 3% up to nu = 0.45 and 3.5% at 0.49 (issue 6 targets).
TEST_P(LinearCantilever, CoarseLatticeAgainstFiniteElements) {
  REQUIRE_CALCULIX();
  const auto [nu, expected_tip_error] = GetParam();
  const BeamReferenceSpec spec = beam(nu, {32, 8, 8});
  const auto ref = reference(spec, "linear_" + std::to_string(nu));
  ASSERT_TRUE(ref);
  const Comparison paper = compare(lattice(spec, {16, 4, 4}, true), *ref);
  const Comparison exact = compare(lattice(spec, {16, 4, 4}, true, CellModel::kExactBending), *ref);
  print_row("baudet2007 16x4x4, nu = " + std::to_string(nu), paper);
  print_row("exact-bending 16x4x4, nu = " + std::to_string(nu), exact);
  EXPECT_NEAR(paper.tip_error, expected_tip_error, 0.015);  // model notes section 7
  EXPECT_LT(paper.max_error, 2.0 * std::abs(paper.tip_error) + 0.02);
  EXPECT_LT(std::abs(exact.tip_error), nu < 0.46 ? 0.03 : 0.035);

  // The same beam as 32x8x8 cells of 0.005 m, against the same mesh (its nodes are the lattice's;
  // the h/2 references of LinearCantileverRefinement are 0.1% (nu = 0.3) to 0.45% (0.49) apart
  // from it): refinement halves the paper's error at least, and exact-bending stays within 2%.
  const Comparison paper_fine = compare(lattice(spec, {32, 8, 8}, true), *ref);
  const Comparison exact_fine = compare(lattice(spec, {32, 8, 8}, true, CellModel::kExactBending), *ref);
  print_row("baudet2007 32x8x8 vs the same mesh, nu = " + std::to_string(nu), paper_fine);
  print_row("exact-bending 32x8x8 vs the same mesh, nu = " + std::to_string(nu), exact_fine);
  EXPECT_LT(std::abs(paper_fine.tip_error), 0.5 * std::abs(paper.tip_error));
  EXPECT_LT(std::abs(exact_fine.tip_error), 0.02);
}

INSTANTIATE_TEST_SUITE_P(PoissonRatios, LinearCantilever,
                         ::testing::Values(std::pair{0.0, -0.032}, std::pair{0.3, -0.101}, std::pair{0.45, -0.144},
                                           std::pair{0.49, -0.160}));

// The reference is converged (h/2 and h/4 agree within 1%), and the 32x8x8 lattice of 0.005 m
// cells, compared node by node with the h/4 mesh, has less than half the coarse lattice's error.
TEST(LinearCantileverRefinement, ReferenceConvergesAndLatticeImproves) {
  REQUIRE_CALCULIX();
  const auto coarse_ref = reference(beam(0.3, {32, 8, 8}), "refine_32");
  const auto fine_ref = reference(beam(0.3, {64, 16, 16}), "refine_64");
  ASSERT_TRUE(coarse_ref && fine_ref);
  EXPECT_NEAR(coarse_ref->tip_deflection() / fine_ref->tip_deflection(), 1.0, 0.01);
  const Comparison coarse = compare(lattice(beam(0.3, {64, 16, 16}), {16, 4, 4}, true), *fine_ref);
  const Comparison fine = compare(lattice(beam(0.3, {64, 16, 16}), {32, 8, 8}, true), *fine_ref);
  const Comparison exact_fine =
      compare(lattice(beam(0.3, {64, 16, 16}), {32, 8, 8}, true, CellModel::kExactBending), *fine_ref);
  print_row("baudet2007 16x4x4 vs h/4, nu = 0.3", coarse);
  print_row("baudet2007 32x8x8 vs h/2, nu = 0.3", fine);
  print_row("exact-bending 32x8x8 vs h/2, nu = 0.3", exact_fine);
  EXPECT_LT(std::abs(fine.tip_error), 0.5 * std::abs(coarse.tip_error));
  EXPECT_LT(std::abs(exact_fine.tip_error), 0.01);
}

// Near incompressibility, on the fine lattice: the exact-bending target is 2%.
TEST(LinearCantileverRefinement, NearlyIncompressibleFineLattice) {
  REQUIRE_CALCULIX();
  const BeamReferenceSpec spec = beam(0.49, {64, 16, 16});
  const auto ref = reference(spec, "refine_64_049");
  ASSERT_TRUE(ref);
  const Comparison paper = compare(lattice(spec, {32, 8, 8}, true), *ref);
  const Comparison exact = compare(lattice(spec, {32, 8, 8}, true, CellModel::kExactBending), *ref);
  print_row("baudet2007 32x8x8 vs h/2, nu = 0.49", paper);
  print_row("exact-bending 32x8x8 vs h/2, nu = 0.49", exact);
  EXPECT_LT(std::abs(exact.tip_error), 0.02);
  EXPECT_LT(std::abs(exact.tip_error), std::abs(paper.tip_error));
}

// Beams of other lengths, 4x4 cells of 1 cm in section, at nu = 0.3 and 0.49: both models against
// C3D20R at h/2; exact-bending must beat the paper's model and stay within the given bound.
void compare_beam_length(int length_cells, double exact_bound) {
  for (double nu : {0.3, 0.49}) {
    BeamReferenceSpec spec = beam(nu, {2 * length_cells, 8, 8});
    spec.size = {0.01 * length_cells, kWidth, kWidth};
    const auto ref = reference(spec, "length_" + std::to_string(length_cells) + "_" + std::to_string(nu));
    ASSERT_TRUE(ref);
    const Eigen::Vector3i cells(length_cells, 4, 4);
    const Comparison paper = compare(lattice(spec, cells, true), *ref);
    const Comparison exact = compare(lattice(spec, cells, true, CellModel::kExactBending), *ref);
    const std::string label = std::to_string(length_cells) + "x4x4, nu = " + std::to_string(nu);
    print_row("baudet2007 " + label, paper);
    print_row("exact-bending " + label, exact);
    EXPECT_LT(std::abs(exact.tip_error), std::abs(paper.tip_error));
    EXPECT_LT(std::abs(exact.tip_error), exact_bound);
  }
}

// A short beam, 8x4x4 (L/h = 2), where shear and the clamp dominate: the notes find every
// 8-node model off here at nu = 0.49.
TEST(ShortCantilever, BothModelsAgainstFiniteElements) {
  REQUIRE_CALCULIX();
  compare_beam_length(8, 0.06);
}

// A slender beam, 32x4x4 (L/h = 8), where bending dominates shear.
TEST(SlenderCantilever, BothModelsAgainstFiniteElements) {
  REQUIRE_CALCULIX();
  compare_beam_length(32, 0.03);
}

class LargeDeflection : public ::testing::TestWithParam<double> {};

// Soft beams sag a third of their length and more: the lattice's own large-deformation response
// against CalculiX with NLGEOM, neo-Hookean and St Venant-Kirchhoff (the laws differ here).
TEST_P(LargeDeflection, AgainstNonlinearFiniteElements) {
  REQUIRE_CALCULIX();
  const double young = GetParam();
  BeamReferenceSpec spec = beam(0.3, {32, 8, 8});
  spec.young_modulus = young;
  spec.nonlinear = true;
  const auto neo_hookean = reference(spec, "nh_" + std::to_string(young));
  ASSERT_TRUE(neo_hookean);
  const ExperimentResult lattice_result = lattice(spec, {16, 4, 4}, false);
  const Comparison nh = compare(lattice_result, *neo_hookean);
  print_row("baudet2007 E = " + std::to_string(young) + " vs neo-Hookean", nh);
  const Comparison exact = compare(lattice(spec, {16, 4, 4}, false, CellModel::kExactBending), *neo_hookean);
  print_row("exact-bending E = " + std::to_string(young) + " vs neo-Hookean", exact);
  // St Venant-Kirchhoff softens without bound in compression: at E = 3e4 Pa CalculiX finds no
  // equilibrium past 56% of the load (measured once, recorded in the README), so it runs at 1e5 only
  if (young >= 1e5) {
    spec.neo_hookean = false;
    const auto saint_venant = reference(spec, "svk_" + std::to_string(young));
    ASSERT_TRUE(saint_venant);
    print_row("baudet2007 E = " + std::to_string(young) + " vs St Venant-Kirchhoff",
              compare(lattice_result, *saint_venant));
  }
  EXPECT_LT(std::abs(nh.tip_error), 0.12);
  // the deflection is large: a third of the length or more, well past linear theory's reach
  EXPECT_GT(std::abs(nh.reference_tip), 0.3 * kLength);
}

INSTANTIATE_TEST_SUITE_P(SoftMaterials, LargeDeflection, ::testing::Values(1e5, 3e4));

// The .frd file that ccx writes beside its .dat holds the same solution on every node. The tool
// reads it (`measure cantilever --reference`) and must find what this file finds from the .dat.
TEST(ReferenceFile, TheToolComparesWithTheFrdAsThisTestDoesWithTheDat) {
  REQUIRE_CALCULIX();
  BeamReferenceSpec spec = beam(0.3, {32, 8, 8});
  spec.gravity = 9.81e-3;  // linear for the lattice too, which the tool solves at this gravity
  const auto ref = reference(spec, "frd");
  ASSERT_TRUE(ref);
  const std::string work_dir = ::testing::TempDir() + "cubespring_ccx_frd";
  Result<FemSolution> frd = read_calculix_frd(work_dir + "/beam.frd");
  ASSERT_TRUE(frd) << frd.message();
  // C3D20R: corners and mid-edge nodes of 32 x 8 x 8 bricks
  EXPECT_EQ(frd->rest_positions.cols(), 33 * 9 * 9 + 32 * 9 * 9 + 33 * 8 * 9 * 2);
  int corners = 0;
  for (Eigen::Index n = 0; n < frd->rest_positions.cols(); ++n) {
    const std::optional<Eigen::Vector3d> dat = ref->displacement_at(frd->rest_positions.col(n));
    if (!dat) continue;
    ++corners;
    EXPECT_LT((frd->displacements.col(n) - *dat).norm(), 1e-5 * std::abs(ref->tip_deflection())) << n;
  }
  EXPECT_EQ(corners, 33 * 9 * 9);

#ifdef CUBESPRING_CLI_PATH
  const std::string png = work_dir + "/beam.png";
  const test::ToolRun run = test::run_tool("measure cantilever --gravity 9.81e-3 --json --png " + png +
                                               " --width 320 --height 180 --reference " + work_dir + "/beam.frd",
                                           false);
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const nlohmann::json tool = nlohmann::json::parse(run.out)["reference"];
  const Comparison mine = compare(lattice(spec, {16, 4, 4}, true), *ref);
  std::printf("tool: tip error %+.4f%%, nodal mean %.4f%%, max %.4f%%; from the .dat: %+.4f%%, %.4f%%, %.4f%%\n",
              100 * tool["tip_error"].get<double>(), 100 * tool["mean_nodal_error"].get<double>(),
              100 * tool["max_nodal_error"].get<double>(), 100 * mine.tip_error, 100 * mine.mean_error,
              100 * mine.max_error);
  EXPECT_EQ(tool["matched_nodes"], 17 * 5 * 5);
  EXPECT_NEAR(tool["tip_error"].get<double>(), mine.tip_error, 1e-4);
  EXPECT_NEAR(tool["mean_nodal_error"].get<double>(), mine.mean_error, 1e-4);
  EXPECT_NEAR(tool["max_nodal_error"].get<double>(), mine.max_error, 1e-4);
#endif
}

}  // namespace
}  // namespace cubespring
