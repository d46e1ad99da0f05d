// SPDX-License-Identifier: MIT
// calder::nbody: picks the kernel variant (kernels.cpp, build_kernels.cpp
// compiled per instruction set) for the running CPU, once.
//
// The variants are CMakeLists.txt's (CALDER_KERNEL_VARIANTS, generated):
// "native" alone (the default: -march=native), or with CALDER_PORTABLE=ON
// "baseline" plus, on x86-64, "x86v3" (AVX2 + FMA) and "x86v4" (AVX-512F);
// src/kernel_level.hpp chooses among them.
#include <string_view>
#include <utility>

#include "../kernel_level.hpp"
#include "build_kernels.hpp"
#include "calder_kernel_variants.hpp"
#include "kernels.hpp"

namespace calder::nbody::detail {

#define CALDER_NBODY_DECLARE(variant) const KernelTable& kernel_table_##variant();
CALDER_KERNEL_VARIANTS(CALDER_NBODY_DECLARE)

namespace {

#define CALDER_NBODY_CANDIDATE(variant) \
  std::pair<std::string_view, const KernelTable*>{#variant, &kernel_table_##variant()},

const KernelTable& choose() {
  const std::pair<std::string_view, const KernelTable*> compiled[] = {
      CALDER_KERNEL_VARIANTS(CALDER_NBODY_CANDIDATE)};
  return *calder::detail::best_variant(compiled);
}

}  // namespace

const KernelTable& kernels() {
  static const KernelTable& table = choose();
  return table;
}

}  // namespace calder::nbody::detail

namespace calder::nbody::bh {

#define CALDER_BUILD_DECLARE(variant) const BuildKernels& build_kernels_##variant();
CALDER_KERNEL_VARIANTS(CALDER_BUILD_DECLARE)

#define CALDER_BUILD_CANDIDATE(variant) \
  std::pair<std::string_view, const BuildKernels*>{#variant, &build_kernels_##variant()},

const BuildKernels& build_kernels() {
  static const BuildKernels& table = [] {
    const std::pair<std::string_view, const BuildKernels*> compiled[] = {
        CALDER_KERNEL_VARIANTS(CALDER_BUILD_CANDIDATE)};
    return *calder::detail::best_variant(compiled);
  }();
  return table;
}

}  // namespace calder::nbody::bh
