// SPDX-License-Identifier: MIT
// calder::nbody: the Barnes-Hut build's loops over every body (see
// build_kernels.hpp).
//
// Compiled once per instruction-set variant (CMakeLists.txt, calder_nbody),
// -O3: the loops vectorise at the variant's width (the build's other code is
// compiled for the baseline). CALDER_KERNEL_VARIANT names the variant and
// the function build_kernels_<variant>() that dispatch.cpp calls.
#include <cstddef>
#include <cstdint>

#include "build_kernels.hpp"

#ifndef CALDER_KERNEL_VARIANT
#error "CALDER_KERNEL_VARIANT must name the variant (set by CMakeLists.txt)"
#endif

#define CALDER_BUILD_CAT2(a, b) a##b
#define CALDER_BUILD_CAT(a, b) CALDER_BUILD_CAT2(a, b)

namespace calder::nbody::bh {
namespace {

void morton_keys(const double* x, const double* y, std::size_t n, const MortonCoder& code,
                 std::uint64_t* keys) {
  for (std::size_t i = 0; i < n; ++i) keys[i] = code(x[i], y[i]);
}

void packed_keys(const Record* records, std::size_t n, const MortonCoder& code,
                 std::uint64_t key_mask, int place_bits, std::uint64_t* packed) {
  for (std::size_t i = 0; i < n; ++i) {
    packed[i] = ((code(records[i].x, records[i].y) & key_mask) << place_bits) | i;
  }
}

}  // namespace

const BuildKernels& CALDER_BUILD_CAT(build_kernels_, CALDER_KERNEL_VARIANT)() {
  static const BuildKernels table{morton_keys, packed_keys};
  return table;
}

}  // namespace calder::nbody::bh
