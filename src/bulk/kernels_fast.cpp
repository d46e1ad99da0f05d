// SPDX-License-Identifier: MIT
// calder::bulk: the float64 and float32 tile kernels (kernels_impl.hpp).
//
// Compiled once per instruction set (CMakeLists.txt, calder_bulk) with
// -ffp-contract=fast: fused multiply-adds are welcome here; none of the
// book-fidelity code goes through this file.
#include "kernels_impl.hpp"

namespace calder::bulk::detail {

// The instruction set this file was compiled for.
const char* CALDER_BULK_CAT(kernel_name_, CALDER_KERNEL_VARIANT)() {
#if defined(__AVX512F__)
  return "avx512";
#elif defined(__AVX2__) && defined(__FMA__)
  return "avx2+fma";
#elif defined(__SSE2__)
  return "sse2";
#elif defined(__wasm_simd128__)
  return "wasm-simd128";
#else
  return "generic";
#endif
}

void CALDER_BULK_CAT(advance_fast64_, CALDER_KERNEL_VARIANT)(const Plan& plan, const Tile& tile) {
  advance_fast64(plan, tile);
}

void CALDER_BULK_CAT(advance_fast32_, CALDER_KERNEL_VARIANT)(const Plan& plan, const Tile& tile) {
  advance_fast32(plan, tile);
}

}  // namespace calder::bulk::detail
