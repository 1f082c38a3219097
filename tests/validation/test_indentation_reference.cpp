// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Re-solves the sphere indentation's CalculiX references (indentation.h) on four meshes, checks
// that they converge and that they are the committed ones. Half an hour on one core (the finest mesh
// a quarter of an hour): label reference, which CI does not run. To remake the file:
//   ctest --test-dir build/release -R IndentationReference --output-on-failure
// then copy the file it names over tests/data/calculix/indentation.csv.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bonded_layer.h"
#include "calculix_common.h"
#include "indentation.h"

namespace cubespring::validation {
namespace {

constexpr int kMeshLevels[] = {1, 2, 3, 4};  // the finest two show the convergence

// At 2 mm the block is a thick layer (chi = 0.09): Hertz with the bonded-layer correction holds.
double hertz_on_the_layer(double depth) {
  return hertz_on_bonded_layer(kIndentationYoung, kIndentationPoisson, kIndentationRadius, depth,
                               kIndentationThickness);
}

TEST(IndentationReference, CalculixRemakesTheCommittedRows) {
  if (!calculix_available()) GTEST_SKIP() << "ccx not found (Debian's calculix-ccx)";
  std::vector<IndentationRow> solved;
  const std::string path = ::testing::TempDir() + "indentation.csv";
  for (const int level : kMeshLevels) {
    const std::string work_dir = ::testing::TempDir() + "cubespring_ccx_indentation_" + std::to_string(level);
    for (const IndentationRow& row : solve_indentation_with_calculix(level, work_dir)) {
      std::printf(
          "depth %.0f mm, mesh level %d (%d elements): force %.6g N (base %.6g N), contact radius %.1f mm, "
          "penetration %.2f um\n",
          1e3 * row.depth, row.mesh_level, row.elements, row.force, row.base_force, 1e3 * row.contact_radius,
          1e6 * row.penetration);
      solved.push_back(row);
    }
    std::fflush(stdout);
    write_indentation_rows(solved, path);  // as far as it got
  }
  std::printf("wrote %s\n", path.c_str());

  // the sphere's force is the base's; the overlap is small beside the depth
  for (const IndentationRow& row : solved) {
    EXPECT_NEAR(row.force, row.base_force, 1e-4 * row.force) << row.depth << " m, level " << row.mesh_level;
    EXPECT_LT(row.penetration, 0.01 * row.depth) << row.depth << " m, level " << row.mesh_level;
  }
  // the finest two meshes agree within 2% at every depth
  const std::size_t depths = kIndentationDepths.size();
  ASSERT_EQ(solved.size(), std::size(kMeshLevels) * depths);
  for (std::size_t d = 0; d < depths; ++d) {
    const IndentationRow& fine = solved[solved.size() - depths + d];
    const IndentationRow& medium = solved[solved.size() - 2 * depths + d];
    std::printf("depth %.0f mm: the finest two differ by %+.2f%%\n", 1e3 * fine.depth,
                100 * (medium.force / fine.force - 1));
    EXPECT_NEAR(medium.force, fine.force, 0.02 * fine.force) << fine.depth << " m";
  }
  // at 2 mm the block is a thick layer (chi = 0.09): Hertz with Dimitriadis's correction holds
  const IndentationRow& shallow = solved[solved.size() - depths];
  const double expected = hertz_on_the_layer(shallow.depth);
  std::printf("depth %.0f mm: force / (Hertz x bonded-layer factor) = %.4f\n", 1e3 * shallow.depth,
              shallow.force / expected);
  EXPECT_NEAR(shallow.force, expected, 0.05 * expected);

  const std::vector<IndentationRow> committed =
      read_indentation_rows(CUBESPRING_TEST_DATA_DIR "/calculix/indentation.csv");
  ASSERT_EQ(committed.size(), solved.size());
  for (std::size_t r = 0; r < solved.size(); ++r) {
    EXPECT_EQ(solved[r].mesh_level, committed[r].mesh_level);
    EXPECT_EQ(solved[r].elements, committed[r].elements);
    EXPECT_NEAR(solved[r].depth, committed[r].depth, 1e-9);
    EXPECT_NEAR(solved[r].force, committed[r].force, 1e-6 * std::abs(committed[r].force));
  }
}

}  // namespace
}  // namespace cubespring::validation
