// SPDX-License-Identifier: MIT
// Internal: which instruction-set variant of the kernel files (calder::nbody,
// calder::bulk) a portable build (CALDER_PORTABLE=ON) should run, decided
// once by both libraries' dispatch.cpp in the same way.
#pragma once

#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <string_view>
#include <utility>

namespace calder::detail {

// 1: baseline, 2: AVX2 + FMA (x86v3), 3: AVX-512F (x86v4).
//
// The best level this CPU supports, capped by the environment variable
// CALDER_KERNELS=avx512|avx2|baseline (benchmarks force the AVX2
// kernels on an AVX-512 machine with it; it names both libraries' kernels).
inline int kernel_level() {
  int level = 3;
  if (const char* env = std::getenv("CALDER_KERNELS")) {
    if (std::strcmp(env, "baseline") == 0) level = 1;
    if (std::strcmp(env, "avx2") == 0) level = 2;
  }
#if defined(__x86_64__) || defined(__i386__)
  __builtin_cpu_init();
  const bool avx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  const bool avx512 = avx2 && __builtin_cpu_supports("avx512f");
  const int supported = avx512 ? 3 : (avx2 ? 2 : 1);
#else
  const int supported = 1;
#endif
  return level < supported ? level : supported;
}

// The level a variant of CMakeLists.txt's calder_kernel_variants needs
// ("native" and "baseline" run on the machine they were built for).
constexpr int required_level(std::string_view variant) {
  if (variant == "x86v4") return 3;
  if (variant == "x86v3") return 2;
  return 1;
}

// The variant to run among those compiled ({name, table} pairs, from
// CALDER_KERNEL_VARIANTS): the one of the highest level this CPU allows.
template <class Table, std::size_t N>
Table best_variant(const std::pair<std::string_view, Table> (&compiled)[N]) {
  const int level = kernel_level();
  std::size_t best = 0;
  for (std::size_t k = 0; k < N; ++k) {
    const int need = required_level(compiled[k].first);
    if (need <= level && need >= required_level(compiled[best].first)) best = k;
  }
  return compiled[best].second;
}

}  // namespace calder::detail
