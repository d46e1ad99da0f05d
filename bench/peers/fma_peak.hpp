// SPDX-License-Identifier: MIT
// The floor of calder's n-body benchmarks: this CPU's fused multiply-add
// throughput, measured, divided by the flops of one pair interaction of the
// kernels (calder/nbody.hpp). No kernel can sum pairs faster than that.
// One definition for bench_nbody, `calder bench` and their tests.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

namespace calder::peers {

// Flops of one interaction, counting an FMA as 2 and every other arithmetic
// instruction (add, sub, mul, div, sqrt, rsqrt estimate) as 1, as the
// kernels compile (objdump of kernels.cpp.o), Plummer law, eps > 0:
//   float32, rsqrt estimate + 1 Newton step:   2 sub, 4 FMA, 1 rsqrt, 5 mul  = 18
//   float64, avx512: rsqrt14 + 2 Newton steps: 2 sub, 6 FMA, 1 rsqrt, 8 mul  = 23
//   float64, avx2: float's rsqrt estimate (2 conversions) + 3 Newton steps:
//                                              2 sub, 7 FMA, 1 rsqrt, 2 cvt, 10 mul = 29
//   float64, sse2: sqrt + div:                 2 sub, 4 FMA, 1 sqrt, 1 mul, 1 div = 13
// The kernels now do less: the avx512 kernels take r^-3 from the estimate with one
// series correction (src/nbody/kernels.cpp, cube_scaled): float32 2 sub,
// 5 FMA, 1 rsqrt, 4 mul = 17; float64 one Newton step, 2 sub, 6 FMA, 1 rsqrt,
// 6 mul = 21; the avx2 float64 kernels one Newton step and a second-order
// series: 2 sub, 8 FMA, 1 rsqrt, 2 cvt, 5 mul = 26. The floors keep 18, 23
// and 29, the counts the targets were set against: a fixed yardstick
// (with the kernels' own counts the shares read 17/18, 21/23 and 26/29 of
// what the tables show).
inline constexpr double kFlopsPerPair32 = 18.0;
inline constexpr double kFlopsPerPair64Rsqrt = 23.0;
inline constexpr double kFlopsPerPair64FloatRsqrt = 29.0;
inline constexpr double kFlopsPerPair64Sqrt = 13.0;

// The vector widths (bits) whose FMA peak this build and CPU can measure,
// widest first: 512 (AVX-512F), 256 (AVX2 + FMA), 128 (FMA on xmm, or plain
// SSE mul + add where the CPU has no FMA).
std::vector<int> fma_widths();

// Runs 12 independent chains of `bits`-wide float FMAs for `rounds` rounds on
// each of `threads` threads (std::thread; the caller's is one of them) and
// returns the flops done by all of them. Time it to get flops/s. Throws
// std::invalid_argument for a width not in fma_widths().
double fma_flops(int bits, int threads, std::int64_t rounds);

// Runs 12 independent chains of `bits`-wide float reciprocal square root
// estimates (vrsqrt14ps at 512 bits, vrsqrtps below: what the n-body kernels
// use) for `rounds` rounds on one thread and returns how many it ran. Timed
// beside fma_flops(bits, 1, ...) / (2 x lanes), FMAs run, it gives the
// estimate's issue rate in FMAs: how much of the FMA units one takes (a
// 512-bit vrsqrt14ps is three micro-ops, two on the FMA port 0). Throws
// std::invalid_argument for a width not in fma_widths(), or 128 without SSE.
double rsqrt_estimates(int bits, std::int64_t rounds);

// The floor that matches a set of n-body kernels (calder::nbody::kernel_name():
// "avx512", "avx2+fma", "sse2", "generic"): the vector width they use (or,
// where fma_widths() can't measure that width, the widest it can) and the
// flops of one of their interactions in each precision.
struct PairFloor {
  int bits = 128;
  double flops_per_pair32 = kFlopsPerPair32;
  double flops_per_pair64 = kFlopsPerPair64Sqrt;

  // Pairs per second at a measured float FMA rate of this width: float64
  // vectors of the same width have half the lanes.
  double pairs32(double flops_per_second) const { return flops_per_second / flops_per_pair32; }
  double pairs64(double flops_per_second) const {
    return flops_per_second / 2.0 / flops_per_pair64;
  }
};
PairFloor pair_floor(std::string_view nbody_kernel_name);

}  // namespace calder::peers
