// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#pragma once

// The vectorised loops (grid passes) are built for AVX-512 and AVX2 beside the baseline, and the
// loader picks the one the CPU runs. Every variant gives the same bits: the loops are lane by
// lane, with no floating-point sums across lanes (only a max, a count and sums of (a - a), each
// +0 or NaN, which do not depend on the order) and no fused multiply-adds (-ffp-contract=off, CMakeLists.txt).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define CUBESPRING_VECTOR_CLONES __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define CUBESPRING_VECTOR_CLONES
#endif
