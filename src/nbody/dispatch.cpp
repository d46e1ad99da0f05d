// SPDX-License-Identifier: MIT
// calder::nbody: picks the kernel variant (kernels.cpp compiled per
// instruction set) for the running CPU, once.
//
// CMake defines CALDER_NBODY_HAS_<variant> for each variant it compiled:
// "native" alone (the default: -march=native), or with CALDER_PORTABLE=ON
// "baseline" plus, on x86-64, "x86v3" (AVX2 + FMA) and "x86v4" (AVX-512F).
#include "../kernel_level.hpp"
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

const KernelTable& choose() {
#if defined(CALDER_NBODY_HAS_native)
  return kernel_table_native();
#else
  [[maybe_unused]] const int level = calder::detail::kernel_level();
#if defined(CALDER_NBODY_HAS_x86v4)
  if (level >= 3) return kernel_table_x86v4();
#endif
#if defined(CALDER_NBODY_HAS_x86v3)
  if (level >= 2) return kernel_table_x86v3();
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
