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
#include <cstring>

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

// Each leaf on its own, four of its bodies a step (GCC/Clang vector
// extensions; a narrower machine splits the vectors): lane j sums the
// leaf's bodies j, j + 4, j + 8, ... in order, and each sum is then (lane 0
// + lane 1) + (lane 2 + lane 3). A leaf's bodies are contiguous, so a step
// is three plain loads. The last step's lanes past the leaf (which read the
// next bodies, or the arrays' padding) count as a mass of 0 at offset 0,
// whose products are +0, which leave a sum as it was (a sum that starts at
// +0 is never -0).
using V4 = double __attribute__((vector_size(32)));
using M4 = std::int64_t __attribute__((vector_size(32)));
constexpr std::uint32_t kLanes = 4;

// The helpers below pass V4 by value; they are internal and inlined, so
// the compilers' note that a narrower variant passes 32-byte vectors
// differently does not apply.
#if defined(__clang__)
#if __has_warning("-Wpsabi")
#pragma clang diagnostic ignored "-Wpsabi"
#endif
#elif defined(__GNUC__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

inline V4 load4(const double* p) {
  V4 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

inline void store4(double* p, const V4& v) { std::memcpy(p, &v, sizeof v); }

// Lanes a[i] where keep[i], else +0 (keep: all ones or all zeros).
inline V4 keep_lanes(const M4& keep, const V4& a) {
  M4 bits;
  std::memcpy(&bits, &a, sizeof bits);
  bits &= keep;
  V4 kept;
  std::memcpy(&kept, &bits, sizeof kept);
  return kept;
}

#if defined(__clang__)
#define CALDER_SHUFFLE(a, b, i, j, k, l) __builtin_shufflevector(a, b, i, j, k, l)
#else
#define CALDER_SHUFFLE(a, b, i, j, k, l) __builtin_shuffle(a, b, M4{i, j, k, l})
#endif

// The sums of four vectors' lanes, (lane 0 + lane 1) + (lane 2 + lane 3),
// as one vector.
inline V4 lane_sums(const V4& a, const V4& b, const V4& c, const V4& d) {
  const V4 ab = CALDER_SHUFFLE(a, b, 0, 4, 2, 6) + CALDER_SHUFFLE(a, b, 1, 5, 3, 7);
  const V4 cd = CALDER_SHUFFLE(c, d, 0, 4, 2, 6) + CALDER_SHUFFLE(c, d, 1, 5, 3, 7);
  return CALDER_SHUFFLE(ab, cd, 0, 1, 4, 5) + CALDER_SHUFFLE(ab, cd, 2, 3, 6, 7);
}

// The second to fourth moments' lanes.
struct Sums {
  V4 q[3] = {};  // xx xy yy
  V4 o[4] = {};  // xxx xxy xyy yyy
  V4 h[5] = {};  // xxxx xxxy xxyy xyyy yyyy

  void add(const V4& m, const V4& dx, const V4& dy) {
    const V4 mdx = m * dx;
    const V4 mdy = m * dy;
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
};

void leaf_sums(const double* x, const double* y, const double* m, std::uint32_t begin,
               std::uint32_t end, double* out) {
  const std::uint32_t whole = begin + (end - begin) / kLanes * kLanes;
  const auto rest = static_cast<std::int64_t>(end - whole);
  const M4 lane = {0, 1, 2, 3};
  const M4 in_leaf = lane < M4{rest, rest, rest, rest};
  V4 mass = {};
  V4 mx = {};
  V4 my = {};
  for (std::uint32_t i = begin; i < whole; i += kLanes) {
    const V4 mi = load4(m + i);
    mass += mi;
    mx += mi * load4(x + i);
    my += mi * load4(y + i);
  }
  V4 m_last = {};
  if (rest > 0) {
    m_last = keep_lanes(in_leaf, load4(m + whole));
    mass += m_last;
    mx += m_last * keep_lanes(in_leaf, load4(x + whole));
    my += m_last * keep_lanes(in_leaf, load4(y + whole));
  }
  const V4 centre = lane_sums(mass, mx, my, V4{});
  const double total = centre[0];
  const double cx = centre[1] / total;
  const double cy = centre[2] / total;
  Sums s;
  for (std::uint32_t i = begin; i < whole; i += kLanes) {
    s.add(load4(m + i), load4(x + i) - cx, load4(y + i) - cy);
  }
  if (rest > 0) {
    s.add(m_last, keep_lanes(in_leaf, load4(x + whole) - cx),
          keep_lanes(in_leaf, load4(y + whole) - cy));
  }
  out[kLeafMass] = total;
  out[kLeafMx] = cx;
  out[kLeafMy] = cy;
  store4(out + kLeafQxx, lane_sums(s.q[0], s.q[1], s.q[2], s.o[0]));
  store4(out + kLeafOxxy, lane_sums(s.o[1], s.o[2], s.o[3], s.h[0]));
  store4(out + kLeafHxxxy, lane_sums(s.h[1], s.h[2], s.h[3], s.h[4]));
}

void leaf_moments(const double* x, const double* y, const double* m, const std::uint32_t* begin,
                  const std::uint32_t* end, std::size_t count, double* sums) {
  for (std::size_t k = 0; k < count; ++k) {
    leaf_sums(x, y, m, begin[k], end[k], sums + kLeafSums * k);
  }
}

}  // namespace

const BuildKernels& CALDER_BUILD_CAT(build_kernels_, CALDER_KERNEL_VARIANT)() {
  static const BuildKernels table{morton_keys, packed_keys, leaf_moments};
  return table;
}

}  // namespace calder::nbody::bh
