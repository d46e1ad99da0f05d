// SPDX-License-Identifier: MIT
// calder::bulk: the book-arithmetic tile kernel (kernels_impl.hpp).
//
// Compiled once per instruction set (CMakeLists.txt, calder_bulk) with
// -ffp-contract=off: no fused multiply-adds, so that every operation rounds
// as in the plain loops and the results are the same bits. Vector
// instructions don't change a bit: IEEE +, -, *, / and sqrt are correctly
// rounded lane by lane, and the quotients by the mass that come from fused
// multiply-adds are the divide's bits (quotient_by_mass): they are written
// with intrinsics, which the flag leaves as they are.
#include "kernels_impl.hpp"

namespace calder::bulk::detail {

void CALDER_BULK_CAT(advance_book64_, CALDER_KERNEL_VARIANT)(const Plan& plan, const Tile& tile) {
  advance_book64(plan, tile);
}

void CALDER_BULK_CAT(book_quotients_, CALDER_KERNEL_VARIANT)(const double* x, const double* mass,
                                                             double* out, std::size_t n) {
  book_quotients(x, mass, out, n);
}

}  // namespace calder::bulk::detail
