// SPDX-License-Identifier: MIT
// calder::bulk: the book-arithmetic tile kernel (kernels_impl.hpp).
//
// Compiled once per instruction set (CMakeLists.txt, calder_bulk) with
// -ffp-contract=off: no fused multiply-adds, so that every operation rounds
// as in the plain loops and the results are the same bits. Vector
// instructions don't change a bit: IEEE +, -, *, / and sqrt are correctly
// rounded lane by lane.
#include "kernels_impl.hpp"

namespace calder::bulk::detail {

void CALDER_BULK_CAT(advance_book64_, CALDER_KERNEL_VARIANT)(const Plan& plan, const Tile& tile) {
  advance_book64(plan, tile);
}

}  // namespace calder::bulk::detail
