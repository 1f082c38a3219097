// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// A value one thread writes and another reads without either waiting on the other: a sequence
// lock over atomic words. The writer never blocks; a reader that meets a write in progress tries
// again a few times, then keeps its last whole value. One writer thread, one reader thread.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <cstring>
#include <type_traits>

namespace cubespring::haptics {

template <typename Words>
class Seqlock {
  static_assert(std::is_trivially_copyable_v<Words>, "a seqlock copies its value word by word");
  static constexpr std::size_t kWords = (sizeof(Words) + 7) / 8;

 public:
  void write(const Words& value) {
    std::array<std::uint64_t, kWords> words{};
    std::memcpy(words.data(), &value, sizeof(Words));
    const std::uint64_t sequence = sequence_.load(std::memory_order_relaxed);
    sequence_.store(sequence + 1, std::memory_order_relaxed);  // odd: a write in progress
    std::atomic_thread_fence(std::memory_order_release);
    for (std::size_t i = 0; i < kWords; ++i) words_[i].store(words[i], std::memory_order_relaxed);
    sequence_.store(sequence + 2, std::memory_order_release);
  }

  /// Copies the value into `out`; false, `out` left as it was, before the first write or when
  /// a few tries all met a write in progress (the writer preempted half-way): the caller then
  /// keeps its last value.
  bool read(Words& out) const {
    for (int attempt = 0; attempt < kAttempts; ++attempt) {
      const std::uint64_t before = sequence_.load(std::memory_order_acquire);
      if (before == 0) return false;
      if (before % 2 == 1) continue;
      std::array<std::uint64_t, kWords> words{};
      for (std::size_t i = 0; i < kWords; ++i) words[i] = words_[i].load(std::memory_order_relaxed);
      std::atomic_thread_fence(std::memory_order_acquire);
      if (sequence_.load(std::memory_order_relaxed) != before) continue;
      std::memcpy(&out, words.data(), sizeof(Words));
      return true;
    }
    return false;
  }

 private:
  static constexpr int kAttempts = 64;
  std::atomic<std::uint64_t> sequence_{0};
  std::array<std::atomic<std::uint64_t>, kWords> words_{};
};

}  // namespace cubespring::haptics
