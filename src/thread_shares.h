// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#pragma once

#ifdef _OPENMP
#include <omp.h>
#endif

namespace cubespring {

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
