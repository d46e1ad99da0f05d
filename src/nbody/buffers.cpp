// SPDX-License-Identifier: MIT
// Memory for the n-body solvers' large arrays (bh::UnsetAllocator): on
// Linux, a block of 2 MiB or more starts on a 2 MiB boundary and asks for
// transparent huge pages. The build streams through these arrays, the
// first radix pass in a few hundred places at once: with 4 KiB pages that
// is more pages than the processor's first-level TLB maps, and its
// prefetchers stop at each page's end. The kernel may refuse (THP set to
// "never", or no free huge page): the memory is then as anywhere else.
#include <algorithm>
#include <cstddef>
#include <new>

#include "barnes_hut_tree.hpp"

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace calder::nbody::bh {

namespace {

#if defined(__linux__) && defined(MADV_HUGEPAGE)
constexpr std::size_t kHugePage = std::size_t{1} << 21;
void ask_for_huge_pages(void* block, std::size_t bytes) {
  madvise(block, bytes, MADV_HUGEPAGE);  // a hint; refused is fine
}
#else
constexpr std::size_t kHugePage = 0;  // none: every block as usual
void ask_for_huge_pages(void*, std::size_t) {}
#endif

bool huge(std::size_t bytes) { return kHugePage != 0 && bytes >= kHugePage; }

std::align_val_t alignment(std::size_t bytes, std::size_t align) {
  return std::align_val_t{huge(bytes) ? kHugePage : std::max(align, alignof(std::max_align_t))};
}

}  // namespace

void* allocate_buffer(std::size_t bytes, std::size_t align) {
  void* block = ::operator new(bytes, alignment(bytes, align));
  if (huge(bytes)) ask_for_huge_pages(block, bytes);
  return block;
}

void free_buffer(void* block, std::size_t bytes, std::size_t align) noexcept {
  ::operator delete(block, alignment(bytes, align));
}

}  // namespace calder::nbody::bh
