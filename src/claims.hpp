// SPDX-License-Identifier: MIT
// Claims on chunks of work that threads share out as they go. The work is
// cut into one share per thread (by rules of the thread count alone) and
// each share into chunks; thread t walks its own share's chunks first to
// last, then takes the last unclaimed chunks of the others' shares. On a
// machine whose cores differ in speed (hybrid processors, a busy core, a
// virtual machine's shared ones) the fast threads then finish what the slow
// ones have not started, instead of waiting for them. Which thread works a
// chunk must change nothing but the time: each chunk writes its own results.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>

#if defined(_OPENMP)
#include <omp.h>
#endif

namespace calder::detail {

// Chunks a share is cut into: enough that a slow thread's share can be
// taken over in good part, few enough that claiming costs nothing.
inline constexpr std::uint32_t kChunksPerShare = 8;

// The calling thread's number in its OpenMP team (0 without OpenMP).
inline std::size_t team_thread() {
#if defined(_OPENMP)
  return static_cast<std::size_t>(omp_get_thread_num());
#else
  return 0;
#endif
}

// Chunk `chunk` of a share of `count` items from `first`: [begin, end).
inline std::pair<std::size_t, std::size_t> chunk_of(std::size_t first, std::size_t count,
                                                    std::uint32_t chunk) {
  return {first + count * chunk / kChunksPerShare, first + count * (chunk + 1) / kChunksPerShare};
}

class Claims {
 public:
  // `shares` shares of `chunks` chunks each, all unclaimed: before the
  // threads start. A share whose thread does not come (a team smaller than
  // asked for) is taken by the others.
  void reset(std::size_t shares, std::uint32_t chunks) {
    if (shares > capacity_) {
      slots_ = std::make_unique<Slot[]>(shares);
      capacity_ = shares;
    }
    shares_ = shares;
    for (std::size_t k = 0; k < shares; ++k) {
      slots_[k].ends.store(std::uint64_t{chunks} << 32, std::memory_order_relaxed);
    }
  }

  // The next chunk for thread t (< shares): its own share's first unclaimed
  // one, else another share's last. False when every chunk is claimed.
  bool next(std::size_t t, std::size_t& share, std::uint32_t& chunk) {
    if (take(t, false, chunk)) {
      share = t;
      return true;
    }
    for (std::size_t step = 1; step < shares_; ++step) {
      const std::size_t k = (t + step) % shares_;
      if (take(k, true, chunk)) {
        share = k;
        return true;
      }
    }
    return false;
  }

 private:
  // Share k's unclaimed chunks: [front, back), front in the low 32 bits.
  struct alignas(64) Slot {
    std::atomic<std::uint64_t> ends{0};
  };

  bool take(std::size_t k, bool from_back, std::uint32_t& chunk) {
    std::atomic<std::uint64_t>& ends = slots_[k].ends;
    std::uint64_t seen = ends.load(std::memory_order_relaxed);
    for (;;) {
      const auto front = static_cast<std::uint32_t>(seen);
      const auto back = static_cast<std::uint32_t>(seen >> 32);
      if (front >= back) return false;
      const std::uint64_t want = from_back ? (std::uint64_t{back - 1} << 32) | front : seen + 1;
      if (ends.compare_exchange_weak(seen, want, std::memory_order_relaxed)) {
        chunk = from_back ? back - 1 : front;
        return true;
      }
    }
  }

  std::unique_ptr<Slot[]> slots_;
  std::size_t capacity_ = 0;
  std::size_t shares_ = 0;
};

}  // namespace calder::detail
