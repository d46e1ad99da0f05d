// SPDX-License-Identifier: MIT
// calder::bulk: picks the tile kernels (kernels_book.cpp and
// kernels_fast.cpp, compiled per instruction set) for the running CPU, once.
// The variants are CMakeLists.txt's (CALDER_KERNEL_VARIANTS), chosen as
// calder::nbody chooses its own (src/kernel_level.hpp).
#include <cstddef>
#include <string_view>
#include <utility>

#include "../kernel_level.hpp"
#include "calder_kernel_variants.hpp"
#include "plan.hpp"

namespace calder::bulk::detail {

#define CALDER_BULK_DECLARE(variant)                       \
  const char* kernel_name_##variant();                     \
  void advance_book64_##variant(const Plan&, const Tile&); \
  void advance_fast64_##variant(const Plan&, const Tile&); \
  void advance_fast32_##variant(const Plan&, const Tile&); \
  void book_quotients_##variant(const double*, const double*, double*, std::size_t);
CALDER_KERNEL_VARIANTS(CALDER_BULK_DECLARE)

namespace {

#define CALDER_BULK_CANDIDATE(variant)                                                         \
  std::pair<std::string_view, KernelTable>{                                                    \
      #variant,                                                                                \
      KernelTable{kernel_name_##variant(), advance_book64_##variant, advance_fast64_##variant, \
                  advance_fast32_##variant, book_quotients_##variant}},

KernelTable choose() {
  const std::pair<std::string_view, KernelTable> compiled[] = {
      CALDER_KERNEL_VARIANTS(CALDER_BULK_CANDIDATE)};
  return calder::detail::best_variant(compiled);
}

}  // namespace

const KernelTable& kernels() {
  static const KernelTable table = choose();
  return table;
}

}  // namespace calder::bulk::detail
