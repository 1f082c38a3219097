// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Re-solves the self-weight block's CalculiX references (self_weight_cube.h) and checks that they
// are the committed ones. Minutes: label reference, which CI does not run. To remake the file:
//   ctest --test-dir build/dev -L reference --output-on-failure
// then copy the file it names over tests/data/calculix/self_weight_cube.csv.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "calculix_common.h"
#include "self_weight_cube.h"

namespace cubespring::validation {
namespace {

// Three meshes of each modulus: the finest two show the convergence.
constexpr double kModuli[] = {5e3, 1e4};
constexpr int kMeshes[] = {8, 12, 16};

TEST(SelfWeightReference, CalculixRemakesTheCommittedRows) {
  if (!calculix_available()) GTEST_SKIP() << "ccx not found (Debian's calculix-ccx)";
  const std::vector<SelfWeightRow> committed =
      read_self_weight_rows(CUBESPRING_TEST_DATA_DIR "/calculix/self_weight_cube.csv");
  const std::string fresh_path = ::testing::TempDir() + "self_weight_cube.csv";
  std::ofstream fresh(fresh_path);
  fresh << "# 12 cm cube, nu 0.45, density 1060 kg/m^3, g 9.81 m/s^2, base z = 0 bonded or on a frictionless\n"
        << "# floor (held along z; the base's centre node along x and y, the end of its x-row along y);\n"
        << "# C3D20R NLGEOM, *HYPERELASTIC, NEO HOOKE (C10 = E / (4 (1 + nu)), D1 = 6 (1 - 2 nu) / E); the volume\n"
        << "# from the corner nodes as trilinear cells. Made by tests/validation/test_self_weight_reference.cpp.\n"
        << "young_modulus_Pa,support,elements_per_side,top_centre_uz_m,volume_change\n";
  std::size_t row_index = 0;
  for (const bool floor : {false, true}) {
    for (const double modulus : kModuli) {
      for (const int elements : kMeshes) {
        const std::string work_dir = ::testing::TempDir() + "cubespring_ccx_self_weight_" + (floor ? "floor_" : "") +
                                     std::to_string(static_cast<int>(modulus)) + "_" + std::to_string(elements);
        const SelfWeightRow solved = solve_self_weight_with_calculix(modulus, floor, elements, work_dir);
        char line[160];
        std::snprintf(line, sizeof line, "%.0f,%s,%d,%.9e,%.9e\n", solved.young_modulus, floor ? "floor" : "bonded",
                      solved.elements, solved.top_centre_uz, solved.volume_change);
        fresh << line << std::flush;
        std::printf("%s", line);
        ASSERT_LT(row_index, committed.size()) << "more cases than committed rows: " << line;
        const SelfWeightRow& row = committed[row_index++];
        EXPECT_EQ(solved.elements, row.elements);
        EXPECT_EQ(solved.floor, row.floor);
        EXPECT_NEAR(solved.top_centre_uz, row.top_centre_uz, 1e-6 * std::abs(row.top_centre_uz)) << line;
        EXPECT_NEAR(solved.volume_change, row.volume_change, 1e-6 * std::abs(row.volume_change) + 1e-9) << line;
      }
    }
  }
  EXPECT_EQ(row_index, committed.size());
  std::printf("wrote %s\n", fresh_path.c_str());
}

}  // namespace
}  // namespace cubespring::validation
