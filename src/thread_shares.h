// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#pragma once

#ifdef _OPENMP
#include <omp.h>
#endif

namespace cubespring {

/// Below this many nodes a thread's share of node-by-node work (the implicit step's assembly and
/// set-up) costs more in entering a parallel region than it saves.
inline constexpr int kMinNodesPerThread = 1024;

/// Items [begin, end) of `items` cut into `shares` equal ranges: range `share`.
struct ShareRange {
  int begin = 0, end = 0;
};
inline ShareRange equal_share(int items, int share, int shares) {
  const auto bound = [&](int k) { return static_cast<int>(static_cast<long long>(items) * k / shares); };
  return {bound(share), bound(share + 1)};
}

/// Runs work(share, shares, barrier) on `threads` threads, share in [0, shares), where barrier()
/// waits for every share. One thread runs it outside any parallel region, with a barrier that
/// does nothing: entering a region, even for one thread, and its barriers cost about 9 us a step,
/// as much as the force passes of a 16x4x4 body. (The barrier is an orphaned `omp barrier`: it
/// binds to the region this function opens.)
template <typename Work>
void run_shares(int threads, const Work& work) {
  if (threads <= 1) {
    work(0, 1, [] {});
    return;
  }
#pragma omp parallel num_threads(threads)
  {
    int share = 0, shares = 1;
#ifdef _OPENMP
    share = omp_get_thread_num();
    shares = omp_get_num_threads();
#endif
    work(share, shares, [] {
#pragma omp barrier
    });
  }
}

}  // namespace cubespring
