// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Re-solves the bonded-plates compression's CalculiX references (bonded_compression.h) and checks
// that they are the committed ones. Tens of minutes: label reference, which CI does not run. To
// remake the files:
//   ctest --test-dir build/release -R BondedCompressionReference --output-on-failure
// then copy the two files it names over tests/data/calculix/bonded_compression{,_nodes}.csv.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bonded_compression.h"
#include "calculix_common.h"

namespace cubespring::validation {
namespace {

constexpr int kMeshes[] = {8, 12, 16};  // the finest two show the convergence

TEST(BondedCompressionReference, CalculixRemakesTheCommittedRows) {
  if (!calculix_available()) GTEST_SKIP() << "ccx not found (Debian's calculix-ccx)";
  std::vector<BondedCompressionRow> solved;
  const std::string summary = ::testing::TempDir() + "bonded_compression.csv";
  const std::string nodes = ::testing::TempDir() + "bonded_compression_nodes.csv";
  for (const double strain : kPlatesStrains) {
    for (const int elements : kMeshes) {
      const std::string work_dir = ::testing::TempDir() + "cubespring_ccx_bonded_" +
                                   std::to_string(static_cast<int>(std::round(-1e4 * strain))) + "_" +
                                   std::to_string(elements);
      solved.push_back(solve_bonded_compression_with_calculix(strain, elements, work_dir));
      const BondedCompressionRow& row = solved.back();
      std::printf("strain %.4f, %d elements: platen force %.6g N, volume change %.3e, bulge %.4f mm\n", row.strain,
                  row.elements, row.platen_force, row.volume_change, 1e3 * row.bulge);
      std::fflush(stdout);
      write_bonded_compression_rows(solved, summary, nodes);  // as far as it got
    }
  }
  std::printf("wrote %s and %s\n", summary.c_str(), nodes.c_str());
  const std::vector<BondedCompressionRow> committed =
      read_bonded_compression_rows(CUBESPRING_TEST_DATA_DIR "/calculix/bonded_compression.csv",
                                   CUBESPRING_TEST_DATA_DIR "/calculix/bonded_compression_nodes.csv");
  ASSERT_EQ(committed.size(), solved.size());
  for (std::size_t r = 0; r < solved.size(); ++r) {
    EXPECT_EQ(solved[r].elements, committed[r].elements);
    EXPECT_NEAR(solved[r].platen_force, committed[r].platen_force, 1e-6 * std::abs(committed[r].platen_force));
    EXPECT_NEAR(solved[r].bulge, committed[r].bulge, 1e-6 * std::abs(committed[r].bulge));
    ASSERT_EQ(solved[r].grid_displacements.size(), committed[r].grid_displacements.size());
    for (std::size_t n = 0; n < solved[r].grid_displacements.size(); ++n) {
      EXPECT_LT((solved[r].grid_displacements[n] - committed[r].grid_displacements[n]).norm(), 1e-9);
    }
  }
}

}  // namespace
}  // namespace cubespring::validation
