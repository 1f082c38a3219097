// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Compression between bonded plates at finite strain (issue 24): the 8 cm cube of
// bonded_compression.h (15.3 kPa, nu = 0.499) squeezed by 5, 12.5 and 18.25%, `cubespring measure
// bonded-compression`'s experiment, against the committed CalculiX NLGEOM neo-Hookean results,
// after checking that their meshes have converged, on 8 and 16 cells a side. About 75 s (16 cells a
// side: 3 solves of 16^3 cells at nu = 0.499): label validation. The assertions are
// expect_lattice_follows_calculix's (bonded_compression.cpp), which both sizes share.
#include <gtest/gtest.h>

#include "bonded_compression.h"

namespace cubespring {
namespace {

TEST(BondedCompressionFem, EightCellsAcrossFollowCalculixNeoHookean) {
  validation::expect_lattice_follows_calculix(8, CUBESPRING_TEST_DATA_DIR);
}

TEST(BondedCompressionFem, SixteenCellsAcrossFollowCalculixNeoHookean) {
  validation::expect_lattice_follows_calculix(16, CUBESPRING_TEST_DATA_DIR);
}

}  // namespace
}  // namespace cubespring
