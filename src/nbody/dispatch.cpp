// calder::nbody: picks the kernel variant (kernels.cpp compiled per
// instruction set) for the running CPU, once.
//
// CMake defines CALDER_NBODY_HAS_<variant> for each variant it compiled:
// "native" alone (the default: -march=native), or with CALDER_PORTABLE=ON
// "baseline" plus, on x86-64, "x86v3" (AVX2 + FMA) and "x86v4" (AVX-512F).
#include <cstdlib>
#include <cstring>

#include "kernels.hpp"

namespace calder::nbody::detail {

#if defined(CALDER_NBODY_HAS_native)
const KernelTable& kernel_table_native();
#endif
#if defined(CALDER_NBODY_HAS_baseline)
const KernelTable& kernel_table_baseline();
#endif
#if defined(CALDER_NBODY_HAS_x86v3)
const KernelTable& kernel_table_x86v3();
#endif
#if defined(CALDER_NBODY_HAS_x86v4)
const KernelTable& kernel_table_x86v4();
#endif

namespace {

// CALDER_NBODY_KERNELS=avx512|avx2|baseline caps the choice (benchmarks).
int requested_level() {
  const char* env = std::getenv("CALDER_NBODY_KERNELS");
  if (env == nullptr) return 3;
  if (std::strcmp(env, "baseline") == 0) return 1;
  if (std::strcmp(env, "avx2") == 0) return 2;
  return 3;
}

const KernelTable& choose() {
  [[maybe_unused]] const int level = requested_level();
#if defined(CALDER_NBODY_HAS_native)
  return kernel_table_native();
#else
#if defined(CALDER_NBODY_HAS_x86v4) || defined(CALDER_NBODY_HAS_x86v3)
  __builtin_cpu_init();
#endif
#if defined(CALDER_NBODY_HAS_x86v4)
  if (level >= 3 && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx2") &&
      __builtin_cpu_supports("fma")) {
    return kernel_table_x86v4();
  }
#endif
#if defined(CALDER_NBODY_HAS_x86v3)
  if (level >= 2 && __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) {
    return kernel_table_x86v3();
  }
#endif
  return kernel_table_baseline();
#endif
}

}  // namespace

const KernelTable& kernels() {
  static const KernelTable& table = choose();
  return table;
}

}  // namespace calder::nbody::detail
