// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The library's internal invariants (src/invariant.h) are checked in the builds configured with
// CUBESPRING_ASSERTIONS (the dev and asan presets): a failed one stops the program, naming itself.
#include <gtest/gtest.h>

#include "invariant.h"

namespace cubespring {
namespace {

TEST(Invariant, AFailedOneStopsTheProgramNamingIt) {
#ifdef CUBESPRING_ASSERTIONS
  const int two = 2;
  CUBESPRING_ASSERT(two == 2);  // a kept one goes on
  EXPECT_DEATH(CUBESPRING_ASSERT(two + 1 == 4),
               "test_invariant.cpp:[0-9]+: cubespring's internal invariant failed: two \\+ 1 == 4");
#else
  GTEST_SKIP() << "built without CUBESPRING_ASSERTIONS: CUBESPRING_ASSERT is compiled out";
#endif
}

}  // namespace
}  // namespace cubespring
