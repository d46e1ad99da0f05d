// SPDX-License-Identifier: MIT
// Compiled with -ffp-contract=fast (bench/peers/CMakeLists.txt): acc * a + b
// must be one vfmadd. Each width has its own function with its own target
// attribute, so that a CALDER_PORTABLE build (no -march=native) measures the
// same peaks as a native one and picks the widths the CPU has at run time.
#include "peers/fma_peak.hpp"

#include <cstddef>
#include <stdexcept>
#include <string>
#include <thread>

namespace calder::peers {

namespace {

using Float128 = float __attribute__((vector_size(16)));
using Float256 = float __attribute__((vector_size(32)));
using Float512 = float __attribute__((vector_size(64)));

constexpr int kChains = 12;  // enough independent chains to hide the FMA latency on 2 ports

volatile float sink;  // where the chains' sum goes, so that they are computed

// kChains chains of FMAs on vectors V; returns the flops done. Always inlined
// into the width functions below, which give it their instruction set.
template <typename V>
[[gnu::always_inline]] inline double chains(std::int64_t rounds) {
  constexpr std::size_t kLanes = sizeof(V) / sizeof(float);
  // Every loop over the chains is unrolled, so that they live in registers:
  // one loop with a variable index keeps the whole array on the stack.
  const V zero = {};
  V acc[kChains];
#pragma GCC unroll 12
  for (std::size_t c = 0; c < kChains; ++c) acc[c] = zero + static_cast<float>(c) * 0.1f;
  V a = zero + 0.999999f;
  const V b = zero + 1e-7f;
  for (std::int64_t r = 0; r < rounds; ++r) {
#pragma GCC unroll 12
    for (std::size_t c = 0; c < kChains; ++c) acc[c] = acc[c] * a + b;  // one vfmadd each
    // Keep the loop from being folded: `a` may have changed. A memory operand,
    // not a register one: Clang checks a vector register's width against the
    // template's own (baseline) instruction set, not the caller's, and
    // rejects 256- and 512-bit ones; the reload is off the FMA chains' path.
    asm volatile("" : "+m"(a));
  }
  V sum = acc[0];
#pragma GCC unroll 12
  for (std::size_t c = 1; c < kChains; ++c) sum += acc[c];
  float total = 0.0f;
  for (std::size_t k = 0; k < kLanes; ++k) total += sum[k];
  sink = total;
  return 2.0 * kChains * static_cast<double>(kLanes) * static_cast<double>(rounds);
}

#if defined(__x86_64__) || defined(__i386__)
[[gnu::target("avx512f,avx2,fma")]] double chains512(std::int64_t rounds) {
  return chains<Float512>(rounds);
}
[[gnu::target("avx2,fma")]] double chains256(std::int64_t rounds) {
  return chains<Float256>(rounds);
}
[[gnu::target("fma")]] double chains128_fma(std::int64_t rounds) {
  return chains<Float128>(rounds);
}
#endif
double chains128(std::int64_t rounds) { return chains<Float128>(rounds); }

using Chains = double (*)(std::int64_t);

Chains chains_for(int bits) {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_cpu_init();
  const bool fma = __builtin_cpu_supports("fma");
  if (bits == 512 && __builtin_cpu_supports("avx512f") && fma) return chains512;
  if (bits == 256 && __builtin_cpu_supports("avx2") && fma) return chains256;
  if (bits == 128) return fma ? chains128_fma : chains128;
#else
  if (bits == 128) return chains128;
#endif
  throw std::invalid_argument("fma_flops: no " + std::to_string(bits) +
                              "-bit FMA on this CPU or build");
}

}  // namespace

std::vector<int> fma_widths() {
  std::vector<int> widths;
  for (int bits : {512, 256, 128}) {
    try {
      chains_for(bits);
      widths.push_back(bits);
    } catch (const std::invalid_argument&) {
    }
  }
  return widths;
}

double fma_flops(int bits, int threads, std::int64_t rounds) {
  const Chains run = chains_for(bits);
  if (threads < 1) throw std::invalid_argument("fma_flops: threads must be >= 1");
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back([run, rounds] { run(rounds); });
  double flops = run(rounds);
  for (auto& t : pool) t.join();
  return flops * threads;
}

PairFloor pair_floor(std::string_view nbody_kernel_name) {
  PairFloor floor;
  if (nbody_kernel_name == "avx512") {
    floor.bits = 512;
    floor.flops_per_pair64 = kFlopsPerPair64Rsqrt;
  } else if (nbody_kernel_name == "avx2+fma") {
    floor.bits = 256;
    floor.flops_per_pair64 = kFlopsPerPair64FloatRsqrt;
  }
  return floor;
}

}  // namespace calder::peers
