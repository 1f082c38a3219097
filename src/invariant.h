// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Internal invariants: what the library's own code guarantees, never what a user's input can break
// (that comes back as a Status or StepStatus::kInvalidInput, result.h). Checked in builds
// configured with CUBESPRING_ASSERTIONS=ON (the dev and asan presets), compiled out otherwise, so
// release builds keep their speed whether or not NDEBUG is defined.
#pragma once

#include <cstdio>
#include <cstdlib>

namespace cubespring {

[[noreturn]] inline void invariant_failed(const char* condition, const char* file, int line) {
  std::fprintf(stderr, "%s:%d: cubespring's internal invariant failed: %s\n", file, line, condition);
  std::abort();
}

}  // namespace cubespring

#ifdef CUBESPRING_ASSERTIONS
#define CUBESPRING_ASSERT(condition) \
  ((condition) ? static_cast<void>(0) : ::cubespring::invariant_failed(#condition, __FILE__, __LINE__))
#else
#define CUBESPRING_ASSERT(condition) static_cast<void>(0)
#endif
