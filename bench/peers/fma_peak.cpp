// SPDX-License-Identifier: MIT
// Compiled with -ffp-contract=fast (bench/peers/CMakeLists.txt): acc * a + b
// must be one vfmadd. Each width has its own function with its own target
// attribute, so that a CALDER_PORTABLE build (no -march=native) measures the
// same peaks as a native one and picks the widths the CPU has at run time.
#include "peers/fma_peak.hpp"

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <thread>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

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
// 512-bit functions: Clang, tuned for a CPU that prefers 256-bit vectors (as
// -march=native does on AVX-512 Xeons), splits 512-bit vector code into
// halves unless the function asks for the width (GCC keeps it whole).
#if defined(__clang__)
#define CALDER_WIDE_512 __attribute__((min_vector_width(512)))
#else
#define CALDER_WIDE_512
#endif

// kChains chains of reciprocal square root estimates (their fixed point is
// 1: no denormals); returns how many ran. A macro, not a template: the
// intrinsics need their instruction set, which only a function with the
// target attribute has (a template's body is compiled without it).
#define CALDER_ESTIMATE_CHAINS(name, isa, V, estimate)                                \
  [[gnu::target(isa)]] CALDER_WIDE_512 double name(std::int64_t rounds) {             \
    const V zero = {};                                                                \
    V acc[kChains];                                                                   \
    _Pragma("GCC unroll 12") for (std::size_t c = 0; c < kChains; ++c) acc[c] =       \
        zero + (1.5f + static_cast<float>(c));                                        \
    for (std::int64_t r = 0; r < rounds; ++r) {                                       \
      _Pragma("GCC unroll 12") for (std::size_t c = 0; c < kChains; ++c) acc[c] =     \
          estimate(acc[c]);                                                           \
      asm volatile("" ::: "memory");                                                  \
    }                                                                                 \
    V sum = acc[0];                                                                   \
    _Pragma("GCC unroll 12") for (std::size_t c = 1; c < kChains; ++c) sum += acc[c]; \
    sink = sum[0];                                                                    \
    return static_cast<double>(kChains) * static_cast<double>(rounds);                \
  }
#define CALDER_RSQRT14_512(v) Float512(_mm512_maskz_rsqrt14_ps(0xFFFF, __m512(v)))
#define CALDER_RSQRT_256(v) Float256(_mm256_rsqrt_ps(__m256(v)))
#define CALDER_RSQRT_128(v) Float128(_mm_rsqrt_ps(__m128(v)))
CALDER_ESTIMATE_CHAINS(estimates512, "avx512f,avx2,fma", Float512, CALDER_RSQRT14_512)
CALDER_ESTIMATE_CHAINS(estimates256, "avx2,fma", Float256, CALDER_RSQRT_256)
CALDER_ESTIMATE_CHAINS(estimates128, "sse", Float128, CALDER_RSQRT_128)

[[gnu::target("avx512f,avx2,fma")]] CALDER_WIDE_512 double chains512(std::int64_t rounds) {
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

double rsqrt_estimates(int bits, std::int64_t rounds) {
  chains_for(bits);  // throws for a width this CPU or build hasn't
#if defined(__x86_64__) || defined(__i386__)
  if (bits == 512) return estimates512(rounds);
  if (bits == 256) return estimates256(rounds);
  return estimates128(rounds);
#else
  (void)rounds;
  throw std::invalid_argument("rsqrt_estimates: no x86 estimate on this CPU");
#endif
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
  const std::vector<int> widths = fma_widths();
  if (std::find(widths.begin(), widths.end(), floor.bits) == widths.end()) {
    floor.bits = widths.front();
  }
  return floor;
}

}  // namespace calder::peers
