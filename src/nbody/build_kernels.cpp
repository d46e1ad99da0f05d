// SPDX-License-Identifier: MIT
// calder::nbody: the Barnes-Hut build's loops over every body (see
// build_kernels.hpp).
//
// Compiled once per instruction-set variant (CMakeLists.txt, calder_nbody),
// -O3 and -ffp-contract=off: the loops vectorise at the variant's width (the
// build's other code is compiled for the baseline), and no multiply is fused
// with an add, so every variant's moments have the same bits. CALDER_KERNEL_VARIANT names the
// variant and the function build_kernels_<variant>() that dispatch.cpp calls.
#include <algorithm>
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

// Four leaves at a time, one a lane (GCC/Clang vector extensions; a
// narrower machine splits the vectors), each lane's sums those of its own
// scalar loop. The lanes' bodies are first copied side by side, kSteps at a
// time; a lane whose leaf has ended gets copies of its last body with a
// mass of 0, whose products are zeros, which leave a sum as it was (a sum
// that starts at +0 is never -0).
using V4 = double __attribute__((vector_size(32)));
constexpr std::size_t kLanes = 4;
constexpr std::uint32_t kSteps = 32;

struct LeafLanes {
  std::uint32_t first[kLanes];
  std::uint32_t last[kLanes];
  std::uint32_t longest = 0;
  V4 x[kSteps];
  V4 y[kSteps];
  V4 m[kSteps];

  // Steps [from, from + steps) of the lanes' bodies to x, y, m.
  void copy(const double* bx, const double* by, const double* bm, std::uint32_t from,
            std::uint32_t steps) {
    for (std::size_t k = 0; k < kLanes; ++k) {
      for (std::uint32_t j = 0; j < steps; ++j) {
        const std::uint32_t body = first[k] + from + j;
        const std::uint32_t at = body <= last[k] ? body : last[k];
        x[j][k] = bx[at];
        y[j][k] = by[at];
        m[j][k] = body <= last[k] ? bm[at] : 0.0;
      }
    }
  }
};

// Leaves [0, lanes) of begin, end (lanes <= kLanes).
void leaf_lanes(const double* bx, const double* by, const double* bm, const std::uint32_t* begin,
                const std::uint32_t* end, std::size_t lanes, double* sums) {
  LeafLanes l;
  for (std::size_t k = 0; k < kLanes; ++k) {
    const std::size_t leaf = k < lanes ? k : lanes - 1;  // spare lanes repeat a leaf
    l.first[k] = begin[leaf];
    l.last[k] = end[leaf] - 1;
    l.longest = std::max(l.longest, end[leaf] - begin[leaf]);
  }
  V4 mass = {};
  V4 mx = {};
  V4 my = {};
  for (std::uint32_t from = 0; from < l.longest; from += kSteps) {
    const std::uint32_t steps = std::min(kSteps, l.longest - from);
    l.copy(bx, by, bm, from, steps);
    for (std::uint32_t j = 0; j < steps; ++j) {
      mass += l.m[j];
      mx += l.m[j] * l.x[j];
      my += l.m[j] * l.y[j];
    }
  }
  mx /= mass;
  my /= mass;
  V4 q[3] = {};  // xx xy yy
  V4 o[4] = {};  // xxx xxy xyy yyy
  V4 h[5] = {};  // xxxx xxxy xxyy xyyy yyyy
  for (std::uint32_t from = 0; from < l.longest; from += kSteps) {
    const std::uint32_t steps = std::min(kSteps, l.longest - from);
    if (l.longest > kSteps) l.copy(bx, by, bm, from, steps);  // else still there
    for (std::uint32_t j = 0; j < steps; ++j) {
      const V4 dx = l.x[j] - mx;
      const V4 dy = l.y[j] - my;
      const V4 mdx = l.m[j] * dx;
      const V4 mdy = l.m[j] * dy;
      const V4 xx = mdx * dx;
      const V4 xy = mdx * dy;
      const V4 yy = mdy * dy;
      const V4 xxx = xx * dx;
      const V4 xxy = xx * dy;
      const V4 xyy = xy * dy;
      const V4 yyy = yy * dy;
      q[0] += xx;
      q[1] += xy;
      q[2] += yy;
      o[0] += xxx;
      o[1] += xxy;
      o[2] += xyy;
      o[3] += yyy;
      h[0] += xxx * dx;
      h[1] += xxx * dy;
      h[2] += xxy * dy;
      h[3] += xyy * dy;
      h[4] += yyy * dy;
    }
  }
  for (std::size_t k = 0; k < lanes; ++k) {
    double* out = sums + kLeafSums * k;
    out[kLeafMass] = mass[k];
    out[kLeafMx] = mx[k];
    out[kLeafMy] = my[k];
    for (int s = 0; s < 3; ++s) out[kLeafQxx + s] = q[s][k];
    for (int s = 0; s < 4; ++s) out[kLeafOxxx + s] = o[s][k];
    for (int s = 0; s < 5; ++s) out[kLeafHxxxx + s] = h[s][k];
  }
}

void leaf_moments(const double* x, const double* y, const double* m, const std::uint32_t* begin,
                  const std::uint32_t* end, std::size_t count, double* sums) {
  for (std::size_t k = 0; k < count; k += kLanes) {
    leaf_lanes(x, y, m, begin + k, end + k, std::min(kLanes, count - k), sums + kLeafSums * k);
  }
}

}  // namespace

const BuildKernels& CALDER_BUILD_CAT(build_kernels_, CALDER_KERNEL_VARIANT)() {
  static const BuildKernels table{morton_keys, packed_keys, leaf_moments};
  return table;
}

}  // namespace calder::nbody::bh
