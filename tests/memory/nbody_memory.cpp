// SPDX-License-Identifier: MIT
// What the Barnes-Hut solver holds between calls, in bytes a body: this
// program replaces the global operator new and delete (so it is an
// executable of its own) and counts the bytes the solver allocates.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <new>
#include <sstream>
#include <string>
#include <vector>

#include "calder/nbody.hpp"
#include "support/nbody_systems.hpp"

namespace {

std::atomic<std::int64_t> live_bytes{0};
std::atomic<std::int64_t> peak_bytes{0};
std::atomic<std::int64_t> allocations{0};
// Blocks of 2 MiB or more, and those of them not on a 2 MiB boundary.
constexpr std::size_t kHugePage = std::size_t{1} << 21;
std::atomic<std::int64_t> large_blocks{0};
std::atomic<std::int64_t> large_off_boundary{0};

// Each block carries its size and its header's length just before it.
void* counted(std::size_t bytes, std::size_t align) {
  const std::size_t head = std::max<std::size_t>(align, 64);
  const std::size_t total = (bytes + 2 * head - 1) / head * head;
  auto* raw = static_cast<unsigned char*>(std::aligned_alloc(head, total));
  if (raw == nullptr) throw std::bad_alloc();
  ++allocations;
  unsigned char* block = raw + head;
  if (bytes >= kHugePage) {
    ++large_blocks;
    if (reinterpret_cast<std::uintptr_t>(block) % kHugePage != 0) ++large_off_boundary;
  }
  auto* sizes = reinterpret_cast<std::size_t*>(block);
  sizes[-1] = bytes;
  sizes[-2] = head;
  const std::int64_t now = live_bytes += static_cast<std::int64_t>(bytes);
  std::int64_t peak = peak_bytes.load();
  while (now > peak && !peak_bytes.compare_exchange_weak(peak, now)) {
  }
  return block;
}

void release(void* block) noexcept {
  if (block == nullptr) return;
  const auto* sizes = static_cast<const std::size_t*>(block);
  live_bytes -= static_cast<std::int64_t>(sizes[-1]);
  std::free(static_cast<unsigned char*>(block) - sizes[-2]);
}

}  // namespace

void* operator new(std::size_t bytes) { return counted(bytes, 16); }
void* operator new[](std::size_t bytes) { return counted(bytes, 16); }
void* operator new(std::size_t bytes, std::align_val_t align) {
  return counted(bytes, static_cast<std::size_t>(align));
}
void* operator new[](std::size_t bytes, std::align_val_t align) {
  return counted(bytes, static_cast<std::size_t>(align));
}
void operator delete(void* block) noexcept { release(block); }
void operator delete[](void* block) noexcept { release(block); }
void operator delete(void* block, std::size_t) noexcept { release(block); }
void operator delete[](void* block, std::size_t) noexcept { release(block); }
void operator delete(void* block, std::align_val_t) noexcept { release(block); }
void operator delete[](void* block, std::align_val_t) noexcept { release(block); }
void operator delete(void* block, std::size_t, std::align_val_t) noexcept { release(block); }
void operator delete[](void* block, std::size_t, std::align_val_t) noexcept { release(block); }

namespace {

namespace nb = calder::nbody;

// Bytes a body that a solver holds after three calls, and at its peak.
struct Held {
  double after = 0.0;
  double peak = 0.0;
};

Held held_by_solver(const calder::test::System& d, nb::Precision precision, int threads) {
  const std::size_t n = d.x.size();
  std::vector<double> ax(n);
  std::vector<double> ay(n);
  const std::int64_t before = live_bytes.load();
  peak_bytes = before;
  Held held;
  {
    nb::BarnesHut solver;
    nb::BarnesHutOptions options;
    options.precision = precision;
    options.threads = threads;
    options.softening = 1e-3;
    for (int call = 0; call < 3; ++call) solver.accelerations(d.x, d.y, d.m, ax, ay, options);
    held.after = static_cast<double>(live_bytes.load() - before) / static_cast<double>(n);
  }
  held.peak = static_cast<double>(peak_bytes.load() - before) / static_cast<double>(n);
  EXPECT_EQ(live_bytes.load(), before) << "the solver gives back all it allocated";
  return held;
}

// The solver keeps its buffers (two copies of the bodies as the sort moves
// them, the bodies in tree order, their sums) and a tree of about one node
// for every 15 bodies: about 180 bytes a body for 2e5 bodies. Room for
// nodes reserved by the body (two a body, the most a tree can have) would
// be about 600 bytes a body more.
TEST(NbodyMemory, BarnesHutHoldsAFewHundredBytesABody) {
  const calder::test::System d = calder::test::disk(200000, 3);
  for (const nb::Precision precision : {nb::Precision::float64, nb::Precision::float32}) {
    for (const int threads : {1, 2, 7}) {
      const Held held = held_by_solver(d, precision, threads);
      EXPECT_GT(held.after, 96.0) << "it keeps at least its copies of the bodies";
      EXPECT_LT(held.after, 320.0) << "threads " << threads;
      EXPECT_LT(held.peak, 320.0) << "threads " << threads;
    }
  }
}

// Once its buffers have grown, a call allocates nothing: not its checks
// (their messages are built only to be thrown), not its stats (their lists
// keep their storage), not its tree.
TEST(NbodyMemory, BarnesHutCallsAllocateNothingOnceGrown) {
  const calder::test::System d = calder::test::disk(20000, 3);
  std::vector<double> ax(d.x.size());
  std::vector<double> ay(d.x.size());
  for (const nb::Precision precision : {nb::Precision::float64, nb::Precision::float32}) {
    nb::BarnesHut solver;
    nb::BarnesHutOptions options;
    options.precision = precision;
    options.threads = 1;
    options.softening = 1e-3;
    solver.accelerations(d.x, d.y, d.m, ax, ay, options);
    const nb::BarnesHutStats first = solver.stats();
    for (int call = 0; call < 2; ++call) solver.accelerations(d.x, d.y, d.m, ax, ay, options);
    const std::int64_t before = allocations.load();
    for (int call = 0; call < 4; ++call) solver.accelerations(d.x, d.y, d.m, ax, ay, options);
    EXPECT_EQ(allocations.load() - before, 0);
    // The stats are the last call's, as the first call's were: reused, not added to.
    const nb::BarnesHutStats& last = solver.stats();
    EXPECT_EQ(last.build_phases.size(), first.build_phases.size());
    ASSERT_EQ(last.work.size(), first.work.size());
    ASSERT_FALSE(last.work.empty());
    EXPECT_EQ(last.work.front().per_thread, std::vector<std::uint64_t>{d.x.size()});
    EXPECT_EQ(last.interactions, first.interactions);
  }
}

#if defined(__linux__)
// The system's transparent huge pages setting: "always", "madvise" or
// "never" (the bracketed word), empty without the file.
std::string huge_pages_setting() {
  std::ifstream file("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  std::getline(file, line);
  const std::size_t open = line.find('[');
  const std::size_t close = line.find(']');
  return open == std::string::npos || close < open ? "" : line.substr(open + 1, close - open - 1);
}

// This process's anonymous memory on huge pages, in bytes.
std::int64_t anon_huge_bytes() {
  std::ifstream file("/proc/self/smaps_rollup");
  std::string line;
  while (std::getline(file, line)) {
    if (line.rfind("AnonHugePages:", 0) != 0) continue;
    std::istringstream fields(line.substr(14));
    std::int64_t kib = 0;
    fields >> kib;
    return kib * 1024;
  }
  return 0;
}

// The solver's large arrays (the bodies as the sort moves them, in tree
// order, the nodes' moments) start on 2 MiB boundaries and ask the kernel
// for huge pages: where the system allows them (THP "madvise" or "always"),
// they get some: fewer pages for the build's passes to translate.
TEST(NbodyMemory, BarnesHutLargeArraysGoOnHugePages) {
  const calder::test::System d = calder::test::disk(300000, 5);
  std::vector<double> ax(d.x.size());
  std::vector<double> ay(d.x.size());
  const std::int64_t blocks_before = large_blocks.load();
  const std::int64_t off_before = large_off_boundary.load();
  const std::int64_t huge_before = anon_huge_bytes();
  nb::BarnesHut solver;
  nb::BarnesHutOptions options;
  options.threads = 2;
  options.softening = 1e-3;
  solver.accelerations(d.x, d.y, d.m, ax, ay, options);
  EXPECT_GE(large_blocks.load() - blocks_before, 4) << "records, their copy, keys, positions";
  EXPECT_EQ(large_off_boundary.load() - off_before, 0);
  const std::string setting = huge_pages_setting();
  if (setting == "madvise" || setting == "always") {
    EXPECT_GE(anon_huge_bytes() - huge_before, static_cast<std::int64_t>(kHugePage))
        << "THP setting " << setting;
  }
}
#endif

}  // namespace
