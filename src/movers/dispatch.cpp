// SPDX-License-Identifier: MIT
// calder::movers: picks the tile kernels (kernels_book.cpp and
// kernels_fast.cpp, compiled per instruction set) for the running CPU, once.
// The same variants and the same choice as calder::nbody (src/nbody/dispatch.cpp):
// "native" alone by default, or with CALDER_PORTABLE=ON "baseline", "x86v3"
// (AVX2 + FMA) and "x86v4" (AVX-512F), lowered by CALDER_NBODY_KERNELS.
#include "../kernel_level.hpp"
#include "plan.hpp"

namespace calder::movers::detail {

#define CALDER_MOVERS_DECLARE(variant)                     \
  const char* kernel_name_##variant();                     \
  void advance_book64_##variant(const Plan&, const Tile&); \
  void advance_fast64_##variant(const Plan&, const Tile&); \
  void advance_fast32_##variant(const Plan&, const Tile&);

#if defined(CALDER_MOVERS_HAS_native)
CALDER_MOVERS_DECLARE(native)
#endif
#if defined(CALDER_MOVERS_HAS_baseline)
CALDER_MOVERS_DECLARE(baseline)
#endif
#if defined(CALDER_MOVERS_HAS_x86v3)
CALDER_MOVERS_DECLARE(x86v3)
#endif
#if defined(CALDER_MOVERS_HAS_x86v4)
CALDER_MOVERS_DECLARE(x86v4)
#endif

namespace {

#define CALDER_MOVERS_TABLE(variant)                                             \
  KernelTable {                                                                  \
    kernel_name_##variant(), advance_book64_##variant, advance_fast64_##variant, \
        advance_fast32_##variant                                                 \
  }

KernelTable choose() {
#if defined(CALDER_MOVERS_HAS_native)
  return CALDER_MOVERS_TABLE(native);
#else
  [[maybe_unused]] const int level = calder::detail::kernel_level();
#if defined(CALDER_MOVERS_HAS_x86v4)
  if (level >= 3) return CALDER_MOVERS_TABLE(x86v4);
#endif
#if defined(CALDER_MOVERS_HAS_x86v3)
  if (level >= 2) return CALDER_MOVERS_TABLE(x86v3);
#endif
  return CALDER_MOVERS_TABLE(baseline);
#endif
}

}  // namespace

const KernelTable& kernels() {
  static const KernelTable table = choose();
  return table;
}

}  // namespace calder::movers::detail
