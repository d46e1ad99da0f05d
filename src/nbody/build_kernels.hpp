// SPDX-License-Identifier: MIT
// calder::nbody's Barnes-Hut internals: Morton codes, the records that the
// build's sort moves, and the build's loops over every body (Morton codes,
// leaves' moments), compiled once per instruction set
// (src/nbody/build_kernels.cpp) and chosen at run time like the pair-sum
// kernels (dispatch.cpp). Every variant gives the same bits: a code is exact
// work, and each moment the same products summed in the same order.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>

namespace calder::nbody::bh {

inline constexpr int kBits = 24;  // per axis: 48-bit Morton codes, at most 24 levels
inline constexpr std::uint32_t kCells = std::uint32_t{1} << kBits;

// Interleaves the low 24 bits of v with zeros: bit k goes to bit 2k.
inline std::uint64_t spread(std::uint32_t v) {
  std::uint64_t x = v & (kCells - 1);
  x = (x | (x << 16)) & 0x0000FFFF0000FFFFull;
  x = (x | (x << 8)) & 0x00FF00FF00FF00FFull;
  x = (x | (x << 4)) & 0x0F0F0F0F0F0F0F0Full;
  x = (x | (x << 2)) & 0x3333333333333333ull;
  x = (x | (x << 1)) & 0x5555555555555555ull;
  return x;
}

// The inverse of spread: bits 0, 2, 4, ... of x.
inline std::uint32_t compact(std::uint64_t x) {
  x &= 0x5555555555555555ull;
  x = (x | (x >> 1)) & 0x3333333333333333ull;
  x = (x | (x >> 2)) & 0x0F0F0F0F0F0F0F0Full;
  x = (x | (x >> 4)) & 0x00FF00FF00FF00FFull;
  x = (x | (x >> 8)) & 0x0000FFFF0000FFFFull;
  x = (x | (x >> 16)) & 0x00000000FFFFFFFFull;
  return static_cast<std::uint32_t>(x);
}

inline int leading_zeros(std::uint64_t x) {  // x != 0 (no <bit>: Emscripten's libc++ 13 lacks it)
#if defined(__GNUC__) || defined(__clang__)
  return __builtin_clzll(x);
#else
  int n = 0;
  for (int step = 32; step > 0; step /= 2) {
    if ((x >> (64 - step)) == 0) {
      n += step;
      x <<= step;
    }
  }
  return n;
#endif
}

// The quadtree levels that Morton codes share, from the bits in which they
// differ: kBits where they are all one code.
inline int shared_levels(std::uint64_t differ) {
  return differ == 0 ? kBits : (leading_zeros(differ) - (64 - 2 * kBits)) / 2;
}

// The Morton code of a point in the root square [x0, x0 + side) x [y0, y0 + side).
struct MortonCoder {
  double x0;
  double y0;
  double to_cell;
  MortonCoder(double x0_, double y0_, double side)
      : x0(x0_), y0(y0_), to_cell(static_cast<double>(kCells) / side) {}
  std::uint32_t cell(double v, double origin) const {
    const double c = std::min((v - origin) * to_cell, static_cast<double>(kCells - 1));  // >= 0
    return static_cast<std::uint32_t>(static_cast<std::int32_t>(c));  // clamped first: no branch
  }
  std::uint64_t operator()(double x, double y) const {
    return spread(cell(x, x0)) | (spread(cell(y, y0)) << 1);
  }
};

// A body as the sort moves it: its position, mass and index (32 bytes: two
// to a cache line, none split between two). The radix passes carry the
// bodies, so that writing them in Morton order reads a range's records in
// cache instead of the caller's arrays at random; a key is worked out again
// from x and y where a pass needs it (cheaper than moving it).
struct alignas(32) Record {
  double x;
  double y;
  double m;
  std::uint32_t index;
};

// Elements that BuildKernels::leaf_moments may read past a leaf's bodies.
inline constexpr std::size_t kLeafPadding = 3;

// A leaf's sums, in the order of BuildKernels::leaf_moments' output.
enum LeafSum : int {
  kLeafMass,
  kLeafMx,  // centre of mass
  kLeafMy,
  kLeafQxx,  // about the centre of mass: sum m dx dx, sum m dx dy, sum m dy dy
  kLeafQxy,
  kLeafQyy,
  kLeafOxxx,  // sum m dx dx dx, ...
  kLeafOxxy,
  kLeafOxyy,
  kLeafOyyy,
  kLeafHxxxx,  // sum m dx dx dx dx, ...
  kLeafHxxxy,
  kLeafHxxyy,
  kLeafHxyyy,
  kLeafHyyyy,
  kLeafSums,
};

// The build's loops over every body.
struct BuildKernels {
  // The Morton codes of (x, y)[0, n) to keys.
  void (*morton_keys)(const double* x, const double* y, std::size_t n, const MortonCoder& code,
                      std::uint64_t* keys);
  // For the sort of one range of records: each record's code bits under
  // key_mask shifted up by place_bits, its place i in the low bits, to
  // packed[i].
  void (*packed_keys)(const Record* records, std::size_t n, const MortonCoder& code,
                      std::uint64_t key_mask, int place_bits, std::uint64_t* packed);
  // For each leaf k < count, bodies [begin[k], end[k]) of (x, y, m) (at
  // least one): its mass, centre of mass and moments, to sums[kLeafSums k +
  // LeafSum]. Each sum is four partial sums, the j-th over the leaf's bodies
  // j, j + 4, j + 8, ... in order, added as (0 + 1) + (2 + 3); each product
  // from the mass rightwards (m dx dx dy): the same bits in every variant.
  // x, y and m are read up to kLeafPadding elements past a leaf's end (not
  // used: they need only be readable).
  void (*leaf_moments)(const double* x, const double* y, const double* m,
                       const std::uint32_t* begin, const std::uint32_t* end, std::size_t count,
                       double* sums);
};

// The variant for the running CPU, chosen once (dispatch.cpp).
const BuildKernels& build_kernels();

}  // namespace calder::nbody::bh
