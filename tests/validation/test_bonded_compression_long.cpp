// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The bonded-plates compression (bonded_compression.h) on 16 cells a side: minutes (about two a
// strain on two cores), label long, which CI does not run; its figures are in the README's
// accuracy section. Run it with
//   ctest --test-dir build/release -L long --output-on-failure
#include <gtest/gtest.h>

#include "bonded_compression.h"

namespace cubespring {
namespace {

TEST(BondedCompressionLong, SixteenCellsAcrossFollowCalculixNeoHookean) {
  validation::expect_lattice_follows_calculix(16, CUBESPRING_TEST_DATA_DIR);
}

}  // namespace
}  // namespace cubespring
