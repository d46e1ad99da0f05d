// SPDX-License-Identifier: MIT
// calder::nbody: the pair-sum kernels (see kernels.hpp).
//
// This file is compiled once per instruction-set variant (CMakeLists.txt,
// calder_nbody): CALDER_KERNEL_VARIANT names the variant and the function
// kernel_table_<variant>() that dispatch.cpp calls. It is the only code of
// calder built with -O3, -march=... and -ffp-contract=fast (fused multiply-
// adds): none of the book-fidelity code goes through it.
//
// Vectorisation is explicit, with GCC/Clang vector extensions: a block of
// R vectors of targets stays in registers while the sources stream past, one
// broadcast source at a time. Each target's sum runs over the sources in
// source order, in its own lane, so the result for a target does not depend
// on which block, lane or thread computes it. The pair kernels
// (pairs_between) take each pair once and turn a vector of sources through
// its lanes instead. The only intrinsics are the
// reciprocal square root estimates (vrsqrtps, vrsqrt14ps/pd), which have no
// portable spelling; the sqrt and the division of the other paths are plain
// per-lane code that the compiler turns into vsqrtp*/vdivp*.
#include <cstddef>
#include <cstring>
#include <type_traits>
#include <utility>

#include "kernels.hpp"

#if defined(__SSE__) || defined(__AVX__)
#include <immintrin.h>
#endif

#ifndef CALDER_KERNEL_VARIANT
#error "CALDER_KERNEL_VARIANT must name the variant (set by CMakeLists.txt)"
#endif

#define CALDER_NBODY_CAT2(a, b) a##b
#define CALDER_NBODY_CAT(a, b) CALDER_NBODY_CAT2(a, b)

namespace calder::nbody::detail {
namespace {

#if defined(__AVX512F__)
constexpr std::size_t kVectorBytes = 64;
// Targets per register block: R vectors (R = 1, 2 and 4 measure within 5%
// of each other; 4 uses the 32 zmm registers best).
constexpr std::size_t kBlockVectors64 = 4;
constexpr std::size_t kBlockVectors32 = 4;
constexpr const char* kName = "avx512";
#elif defined(__AVX__)
constexpr std::size_t kVectorBytes = 32;
constexpr std::size_t kBlockVectors64 = 2;  // 16 ymm registers
constexpr std::size_t kBlockVectors32 = 2;
#if defined(__FMA__)
constexpr const char* kName = "avx2+fma";
#else
constexpr const char* kName = "avx";
#endif
#elif defined(__SSE2__)
constexpr std::size_t kVectorBytes = 16;
constexpr std::size_t kBlockVectors64 = 4;
constexpr std::size_t kBlockVectors32 = 2;
constexpr const char* kName = "sse2";
#else
constexpr std::size_t kVectorBytes = 16;
constexpr std::size_t kBlockVectors64 = 2;
constexpr std::size_t kBlockVectors32 = 2;
constexpr const char* kName = "generic";
#endif
// Barnes-Hut groups (tens of targets): blocks of this many vectors, then
// single ones (run_group_blocks).
constexpr std::size_t kGroupBlockVectors = 2;
// Barnes-Hut, float64: a group's opened leaves re-tested for each block of
// this many targets (BarnesHutOptions::target_block). With AVX2 a float64
// multipole costs about four pairs and an opened leaf holds about 19
// bodies, so the blocks save work (at a little more error); with AVX-512
// pairs are cheap enough that they do not, so it keeps the group's list.
// The other sets keep it too.
#if defined(__AVX__) && !defined(__AVX512F__)
constexpr std::size_t kTargetBlock64 = 16;
#else
constexpr std::size_t kTargetBlock64 = 0;
#endif

using VD = double __attribute__((vector_size(kVectorBytes)));
using VF = float __attribute__((vector_size(kVectorBytes)));
// As many doubles as VF has floats: the float32 kernel's tile sums.
using VD2 = double __attribute__((vector_size(2 * kVectorBytes)));

template <typename V>
struct Scalar;
// Integer vectors of the same shapes (lane indices for __builtin_shuffle).
using VDI = long long __attribute__((vector_size(kVectorBytes)));
using VFI = int __attribute__((vector_size(kVectorBytes)));
template <>
struct Scalar<VD> {
  using type = double;
  using index = VDI;
};
template <>
struct Scalar<VF> {
  using type = float;
  using index = VFI;
};

// Pairs closer than this (r^2 below the smallest normal number) count as
// coincident where the kernels mask (see kernels.hpp).
template <typename V>
constexpr typename Scalar<V>::type kTiny = __FLT_MIN__;
template <>
constexpr double kTiny<VD> = __DBL_MIN__;

template <typename V>
constexpr std::size_t kLanes = sizeof(V) / sizeof(typename Scalar<V>::type);

// Every lane s: a broadcast (vbroadcastss/sd, from memory where s is), not
// V{} + s, which costs an addition (0 + s is not s for s = -0).
template <typename V>
[[gnu::always_inline]] inline V splat(typename Scalar<V>::type s) {
#if defined(__clang__)
  V v;
  for (std::size_t k = 0; k < sizeof(V) / sizeof(s); ++k) v[k] = s;
  return v;
#else
  const V v = {s};
  return __builtin_shuffle(v, typename Scalar<V>::index{});
#endif
}

template <typename V>
[[gnu::always_inline]] inline V load(const typename Scalar<V>::type* p) {
  V v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

// Lane l gets lane l + 1 (mod the lane count): one permute.
template <typename V, std::size_t... K>
[[gnu::always_inline]] inline V rotate_lanes(V v, std::index_sequence<K...>) {
  return __builtin_shufflevector(v, v, ((K + 1) % sizeof...(K))...);
}
template <typename V>
[[gnu::always_inline]] inline V rotate_lanes(V v) {
  return rotate_lanes(v, std::make_index_sequence<kLanes<V>>{});
}

// Lane by lane; GCC turns the loop into one vsqrtp* (with -fno-math-errno).
template <typename V>
[[gnu::always_inline]] inline V vsqrt(V v) {
  V r;
  for (std::size_t k = 0; k < kLanes<V>; ++k) {
    if constexpr (sizeof(typename Scalar<V>::type) == 4) {
      r[k] = __builtin_sqrtf(v[k]);
    } else {
      r[k] = __builtin_sqrt(v[k]);
    }
  }
  return r;
}

// Reciprocal square root estimates and how many Newton steps bring them to
// the type's precision; kSteps == 0: no estimate, use 1 / sqrt.
#if defined(__AVX512F__)
// (The zero-masking forms with a full mask: GCC 12 warns, wrongly, that the
// plain ones read an uninitialised register.)
[[gnu::always_inline]] inline VF rsqrt_estimate(VF v) {
  return _mm512_maskz_rsqrt14_ps(0xFFFF, v);  // relative error < 2^-14
}
[[gnu::always_inline]] inline VD rsqrt_estimate(VD v) { return _mm512_maskz_rsqrt14_pd(0xFF, v); }
template <typename V>
constexpr int kNewtonSteps = sizeof(typename Scalar<V>::type) == 4 ? 1 : 2;
#elif defined(__AVX__)
[[gnu::always_inline]] inline VF rsqrt_estimate(VF v) { return _mm256_rsqrt_ps(v); }  // 1.5*2^-12
[[gnu::always_inline]] inline VD rsqrt_estimate(VD v) { return v; }                   // unused
template <typename V>
constexpr int kNewtonSteps = sizeof(typename Scalar<V>::type) == 4 ? 1 : 0;
#elif defined(__SSE2__)
[[gnu::always_inline]] inline VF rsqrt_estimate(VF v) { return _mm_rsqrt_ps(v); }
[[gnu::always_inline]] inline VD rsqrt_estimate(VD v) { return v; }  // unused
template <typename V>
constexpr int kNewtonSteps = sizeof(typename Scalar<V>::type) == 4 ? 1 : 0;
#else
template <typename V>
[[gnu::always_inline]] inline V rsqrt_estimate(V v) {
  return v;  // unused
}
template <typename V>
constexpr int kNewtonSteps = 0;
#endif

// float64 without AVX-512 has no reciprocal square root estimate, and
// vsqrtpd + vdivpd (one of each per pair) bound the Plummer sum by the
// divider, not the FMAs. kFloatEstimate: where set, the Plummer sum of
// unmasked pairs (eps^2 > 0) takes float's estimate instead (vcvtpd2ps,
// vrsqrtps, vcvtps2pd: relative error < 1.5 * 2^-12), when every r^2 of the
// call is in float's normal range (LawParams::float_range); see
// cube_via_float. Error against the exact sum: tests/test_nbody.cpp and
// docs/PERFORMANCE.md (RMS ~1e-15).
#if defined(__AVX__) && !defined(__AVX512F__)
constexpr bool kFloatEstimate = true;
[[gnu::always_inline]] inline VD rsqrt_estimate_via_float(VD v) {
  return VD(_mm256_cvtps_pd(_mm_rsqrt_ps(_mm256_cvtpd_ps(__m256d(v)))));
}
#else
constexpr bool kFloatEstimate = false;
// (unused: kFloatEstimate is false)
[[maybe_unused, gnu::always_inline]] inline VD rsqrt_estimate_via_float(VD v) { return v; }
#endif

// 8 r^-3 from float's estimate (see kFloatEstimate): one Newton step
// without its factor 1/2 gives y = 2 / r within 3.4 2^-24 (2^-22.2), so
// e = r2 y^2 / 4 - 1 is within 2^-21.2, and the series
//   r^-3 = (y / 2)^3 (1 + e)^(-3/2) = (y / 2)^3 (1 - 1.5 e + 1.875 e^2 - ...)
// to second order leaves 2.19 e^3, below 2^-62. In e4 = 4 e = r2 y^2 - 4 the
// coefficients are exact: 1 - 0.375 e4 + 0.1171875 e4^2. Nine operations
// where three Newton steps and the cube took twelve.
[[maybe_unused, gnu::always_inline]] inline VD cube_via_float(VD r2) {
  const VD y0 = rsqrt_estimate_via_float(r2);
  const VD y = y0 * (3.0 - r2 * (y0 * y0));
  const VD y2 = y * y;
  const VD e4 = r2 * y2 - 4.0;
  const VD series = (e4 * 0.1171875 - 0.375) * e4 + 1.0;
  return (y * y2) * series;
}

// 1 / sqrt(r2) for r2 > 0, to the type's precision. With kNewtonSteps > 0 the
// result is (approximately) `scale` / sqrt(r2) with scale = 2^(kNewtonSteps'
// last step): the last Newton step y (3 - r2 y^2) leaves out its factor 1/2,
// which the caller folds into a constant (see kLastStepScale).
// (Unused where no kernel takes an estimate: clang for wasm32 says so.)
template <typename V>
[[maybe_unused]] constexpr typename Scalar<V>::type kLastStepScale = kNewtonSteps<V> > 0 ? 2 : 1;

template <typename V>
[[gnu::always_inline]] inline V rsqrt_scaled(V r2) {
  using T = typename Scalar<V>::type;
  if constexpr (kNewtonSteps<V> == 0) {
    return splat<V>(T(1)) / vsqrt(r2);
  } else {
    V y = rsqrt_estimate(r2);
    const V half_r2 = r2 * T(0.5);
    for (int step = 1; step < kNewtonSteps<V>; ++step) {
      y = y * (T(1.5) - half_r2 * (y * y));  // y (3/2 - r2 y^2 / 2)
    }
    return y * (T(3) - r2 * (y * y));  // 2 / sqrt(r2)
  }
}

// Plummer's r^-3 for r2 > 0, scaled: r^-3 = kCubeScale<V> cube_scaled(r2)
// (the caller folds the constant into the masses).
// With AVX-512 it comes from an estimate y of 1 / r and one correction:
// e = r2 y^2 - 1 is small, and
//   r^-3 = y^3 (1 + e)^(-3/2) = y^3 (1 - 1.5 e + 1.875 e^2 - ...)
//        ~ S y^3 (A - r2 y^2),  S (A - 1) = 1, slope -S = -1.5:
// four operations (y^2, y^3, one fnmadd, a product) where a Newton step and
// the cube take five. float32: y = rsqrt14(r2) is within 2^-14, so e is
// within 2^-13 and the dropped 1.875 e^2 below 2.8e-8 relative, under
// float's rounding (a Newton step's cube leaves 1.125 e^2). float64: y is
// rsqrt14 after one Newton step (within 1.5 2^-28, e within 2^-26.4), so
// the dropped term is below 2^-51.9, two of double's ulps (two Newton steps
// and the cube took nine operations, this takes seven). The Newton step
// leaves out its factor 1/2 (y' = 2 y), so the float64 form is
// y'^3 (4 A - r2 y'^2) = 32 y^3 (A - r2 y^2). A and S are the floats
// nearest 5/3 and 3/2 with S (A - 1) = 1 to the type's precision: float
// A = RN(5/3) - 1 ulp, S = 1.5 + 3 ulps (1 - 2^-44; RN(5/3) and 1.5 would
// bias every force by -6e-8); double A = RN(5/3) + 1 ulp, S = 1.5 - 3 ulps
// (1 + 2e-31). Elsewhere: the Newton steps' 2 / r, cubed (S = 1/8). A zmm
// vrsqrt14ps is three uops, two of them on port 0 (an FMA port), so each
// operation saved around it counts.
#if defined(__AVX512F__)
template <typename V>
constexpr bool kCubeFromEstimate = true;
#else
template <typename V>
constexpr bool kCubeFromEstimate = false;
#endif

template <typename V>
[[maybe_unused]] constexpr typename Scalar<V>::type kCubeScale = [] {
  using T = typename Scalar<V>::type;
  if constexpr (!kCubeFromEstimate<V>) {
    return T(1) / (kLastStepScale<V> * kLastStepScale<V> * kLastStepScale<V>);
  } else if constexpr (sizeof(T) == 4) {
    return 0x1.800006p+0f;
  } else {
    return 0x1.7fffffffffffdp-5;  // S / 32
  }
}();

template <typename V>
[[gnu::always_inline]] inline V cube_scaled(V r2) {
  using T = typename Scalar<V>::type;
  if constexpr (kCubeFromEstimate<V> && sizeof(T) == 4) {
    const V y = rsqrt_estimate(r2);
    const V y2 = y * y;
    return (y * y2) * (0x1.aaaaa8p+0f - r2 * y2);
  } else if constexpr (kCubeFromEstimate<V>) {
    const V y0 = rsqrt_estimate(r2);
    const V y = y0 * (T(3) - r2 * (y0 * y0));  // 2 / r, one Newton step
    const V y2 = y * y;
    return (y * y2) * (0x1.aaaaaaaaaaaacp+2 - r2 * y2);  // 4 A
  } else {
    const V y = rsqrt_scaled(r2);  // 2 / r
    return y * (y * y);
  }
}

// The law's weight times the source mass, for one vector of pairs: returns
// m w(r) with r^2 = dx^2 + dy^2 (see kernels.hpp). Masked: zero where
// r^2 < kTiny (the same place, to the type's precision).
template <Law kLaw, bool kMasked, typename V, bool kViaFloat = false>
[[gnu::always_inline]] inline V weight(V dx, V dy, V m, V eps2, V lo, V hi) {
  using T = typename Scalar<V>::type;
  V w;
  if constexpr (kLaw == Law::plummer && kViaFloat) {
    V r2 = dx * dx + eps2;
    r2 = dy * dy + r2;
    w = (m * T(0.125)) * cube_via_float(r2);
  } else if constexpr (kLaw == Law::plummer) {
    V r2 = dx * dx + eps2;
    r2 = dy * dy + r2;
    if constexpr (kNewtonSteps<V> == 0) {
      w = m / (r2 * vsqrt(r2));
    } else if constexpr (kCubeFromEstimate<V>) {
      const V scaled_m = m * kCubeScale<V>;
      w = scaled_m * cube_scaled(r2);
    } else {
      const V y = rsqrt_scaled(r2);  // 2 / r
      constexpr T k = T(1) / (kLastStepScale<V> * kLastStepScale<V> * kLastStepScale<V>);
      w = (m * k) * y * (y * y);
    }
    if constexpr (kMasked) w = r2 >= kTiny<V> ? w : V{};
  } else {
    const V r2 = dx * dx + dy * dy;
    V r;
    V inv_r;  // 1 / r (with the estimate)
    if constexpr (kNewtonSteps<V> == 0) {
      r = vsqrt(r2);
    } else {
      inv_r = rsqrt_scaled(r2) * (T(1) / kLastStepScale<V>);
      r = r2 * inv_r;
    }
    if constexpr (kLaw == Law::clamp_distance) {
      V d = r < lo ? lo : r;
      d = d > hi ? hi : d;
      if constexpr (kNewtonSteps<V> == 0) {
        w = m / (r * (d * d));
      } else {
        w = m * inv_r / (d * d);
      }
    } else {
      V q = r2 < lo ? lo : r2;
      q = q > hi ? hi : q;
      if constexpr (kNewtonSteps<V> == 0) {
        w = m / (r * q);
      } else {
        w = m * inv_r / q;
      }
    }
    w = r2 >= kTiny<V> ? w : V{};  // always masked: r == 0 has no direction
  }
  return w;
}

// Sources, one broadcast at a time: point masses under a law; kSplit:
// two-float positions (see Bodies).
template <typename V, Law kLaw, bool kMasked, bool kSplit, bool kViaFloat = false>
struct PointSources {
  using T = typename Scalar<V>::type;
  static constexpr bool kTwoFloat = kSplit;
  struct Source {
    V x, y, m, x_lo, y_lo;
  };
  const Bodies<T>& s;
  V eps2, lo, hi;

  std::size_t size() const { return s.n; }
  [[gnu::always_inline]] Source at(std::size_t j) const {
    if constexpr (kSplit) {
      return {splat<V>(s.x[j]), splat<V>(s.y[j]), splat<V>(s.m[j]), splat<V>(s.x_lo[j]),
              splat<V>(s.y_lo[j])};
    } else {
      return {splat<V>(s.x[j]), splat<V>(s.y[j]), splat<V>(s.m[j]), V{}, V{}};
    }
  }
  [[gnu::always_inline]] void add(const Source& src, V xi, V yi, V xi_lo, V yi_lo, V& ax,
                                  V& ay) const {
    V dx = src.x - xi;
    V dy = src.y - yi;
    if constexpr (kSplit) {
      dx = dx + (src.x_lo - xi_lo);
      dy = dy + (src.y_lo - yi_lo);
    }
    const V w = weight<kLaw, kMasked, V, kViaFloat>(dx, dy, src.m, eps2, lo, hi);
    ax = w * dx + ax;
    ay = w * dy + ay;
  }
};

// Sources: tree nodes with their moments (Plummer law; see kernels.hpp).
template <typename V>
struct MultipoleSources {
  using T = typename Scalar<V>::type;
  static constexpr bool kTwoFloat = false;
  static constexpr std::size_t K = Nodes<T>::kColumns;
  struct Source {
    V c[K];
  };
  const Nodes<T>& s;
  V eps2;

  std::size_t size() const { return s.n; }
  [[gnu::always_inline]] Source at(std::size_t j) const {
    Source src;
    for (std::size_t k = 0; k < K; ++k) src.c[k] = splat<V>(s.column[k][j]);
    return src;
  }
  [[gnu::always_inline]] void add(const Source& n, V xi, V yi, V, V, V& ax, V& ay) const {
    const V& m = n.c[2];
    const V& q3xx = n.c[3];
    const V& q3xy = n.c[4];
    const V& q3yy = n.c[5];
    const V& t15 = n.c[6];
    const V& o_xxx = n.c[7];
    const V& o_xxy = n.c[8];
    const V& o_xyy = n.c[9];
    const V& o_yyy = n.c[10];
    const V& p_x = n.c[11];
    const V& p_y = n.c[12];
    const V dx = n.c[0] - xi;
    const V dy = n.c[1] - yi;
    V r2 = dx * dx + eps2;
    r2 = dy * dy + r2;
    V y = rsqrt_scaled(r2);
    if constexpr (kNewtonSteps < V >> 0) y = y * T(0.5);
    const V y2 = y * y;
    const V y3 = y * y2;
    const V y5 = y3 * y2;
    const V y7 = y5 * y2;
    const V qx = q3xx * dx + (q3xy * dy + p_x);  // 3 Q d + 1.5 P
    const V qy = q3xy * dx + (q3yy * dy + p_y);
    const V pd = p_x * dx + p_y * dy;  // 1.5 P.d
    const V dqd = dx * qx + dy * qy;   // 3 d.Q d + 1.5 P.d
    const V xx = dx * dx;
    const V yy = dy * dy;
    const V xy2 = (dx + dx) * dy;
    const V vx = o_xxx * xx + (o_xxy * xy2 + o_xyy * yy);  // 7.5 O(d,d,.)
    const V vy = o_xxy * xx + (o_xyy * xy2 + o_yyy * yy);
    const V w = dx * vx + dy * vy;  // 7.5 O(d,d,d)
    // Fourth order: 17.5 H(d,d,d,.), 7.5 G d (G = tr H), 1.875 tr G.
    const V& h_xxxx = n.c[13];
    const V& h_xxxy = n.c[14];
    const V& h_xxyy = n.c[15];
    const V& h_xyyy = n.c[16];
    const V& h_yyyy = n.c[17];
    const V hdd_xx = h_xxxx * xx + (h_xxxy * xy2 + h_xxyy * yy);  // 17.5 H(d,d,.,.)
    const V hdd_xy = h_xxxy * xx + (h_xxyy * xy2 + h_xyyy * yy);
    const V hdd_yy = h_xxyy * xx + (h_xyyy * xy2 + h_yyyy * yy);
    const V hx = hdd_xx * dx + hdd_xy * dy;  // 17.5 H(d,d,d,.)
    const V hy = hdd_xy * dx + hdd_yy * dy;
    const V& g_xx = n.c[18];  // 7.5 G
    const V& g_xy = n.c[19];
    const V& g_yy = n.c[20];
    const V& tt = n.c[21];               // 1.875 tr G
    const V w4 = dx * hx + dy * hy;      // 17.5 H(d,d,d,d)
    const V tx = g_xx * dx + g_xy * dy;  // 7.5 G d
    const V ty = g_xy * dx + g_yy * dy;
    const V s2 = dx * tx + dy * ty;  // 7.5 d.G d
    const V even4 = y2 * (T(2.25) * y2 * w4 - T(3.5) * s2) + tt;
    const V c = m * y3 - t15 * y5 + y7 * (T(2.5) * (dqd + pd) + even4 - (T(7.0 / 3.0) * y2) * w);
    ax = c * dx + ax;
    ay = c * dy + ay;
    ax = y7 * (vx + tx - y2 * hx) - y5 * qx + ax;
    ay = y7 * (vy + ty - y2 * hy) - y5 * qy + ay;
  }
};

// Copies targets [first, first + B) into a full block, padding a short tail
// block with the block's first target (the padded lanes are discarded).
template <typename T, std::size_t B>
const T* block_of(const T* p, std::size_t first, std::size_t n, T (&buffer)[B]) {
  if (n - first >= B) return p + first;
  const std::size_t count = n - first;
  for (std::size_t k = 0; k < B; ++k) buffer[k] = p[first + (k < count ? k : 0)];
  return buffer;
}

// Blocks of R vectors of targets against all sources: each lane sums its
// target's pairs in source order. float64: one sum per lane. float32: float
// sums over tiles of kFloatTile sources, added in double. (tx_lo, ty_lo):
// the targets' low parts when Sources::kTwoFloat.
template <typename V, std::size_t R, typename Sources>
void run_blocks(const typename Scalar<V>::type* tx, const typename Scalar<V>::type* ty,
                const typename Scalar<V>::type* tx_lo, const typename Scalar<V>::type* ty_lo,
                std::size_t nt, const Sources& sources, double* out_x, double* out_y) {
  using T = typename Scalar<V>::type;
  constexpr std::size_t L = kLanes<V>;
  constexpr std::size_t B = R * L;
  constexpr bool kFloat = sizeof(T) == 4;
  using Sum = std::conditional_t<kFloat, VD2, VD>;
  const std::size_t ns = sources.size();
  const std::size_t tile = kFloat ? kFloatTile : (ns > 0 ? ns : 1);
  for (std::size_t i0 = 0; i0 < nt; i0 += B) {
    T bx[B];
    T by[B];
    T bx_lo[B];
    T by_lo[B];
    const T* px = block_of(tx, i0, nt, bx);
    const T* py = block_of(ty, i0, nt, by);
    const T* px_lo = Sources::kTwoFloat ? block_of(tx_lo, i0, nt, bx_lo) : nullptr;
    const T* py_lo = Sources::kTwoFloat ? block_of(ty_lo, i0, nt, by_lo) : nullptr;
    V xi[R];
    V yi[R];
    V xi_lo[R];
    V yi_lo[R];
    Sum sx[R];
    Sum sy[R];
    for (std::size_t r = 0; r < R; ++r) {
      xi[r] = load<V>(px + r * L);
      yi[r] = load<V>(py + r * L);
      xi_lo[r] = Sources::kTwoFloat ? load<V>(px_lo + r * L) : V{};
      yi_lo[r] = Sources::kTwoFloat ? load<V>(py_lo + r * L) : V{};
      sx[r] = Sum{};
      sy[r] = Sum{};
    }
    for (std::size_t j0 = 0; j0 < ns; j0 += tile) {
      const std::size_t j1 = ns - j0 < tile ? ns : j0 + tile;
      V ax[R];
      V ay[R];
      for (std::size_t r = 0; r < R; ++r) {
        ax[r] = V{};
        ay[r] = V{};
      }
      for (std::size_t j = j0; j < j1; ++j) {
        const auto src = sources.at(j);
        for (std::size_t r = 0; r < R; ++r) {
          sources.add(src, xi[r], yi[r], xi_lo[r], yi_lo[r], ax[r], ay[r]);
        }
      }
      for (std::size_t r = 0; r < R; ++r) {
        if constexpr (kFloat) {
          sx[r] += __builtin_convertvector(ax[r], VD2);
          sy[r] += __builtin_convertvector(ay[r], VD2);
        } else {
          sx[r] += ax[r];
          sy[r] += ay[r];
        }
      }
    }
    const std::size_t count = nt - i0 < B ? nt - i0 : B;
    for (std::size_t k = 0; k < count; ++k) {
      out_x[i0 + k] += sx[k / L][k % L];
      out_y[i0 + k] += sy[k / L][k % L];
    }
  }
}

// Barnes-Hut groups: blocks of R vectors while they are full, then single
// vectors, so that a group pads at most one vector. Each lane still sums its
// target's pairs in source order: the same bits as run_blocks<V, 1>.
template <typename V, std::size_t R, typename Sources>
void run_group_blocks(const typename Scalar<V>::type* tx, const typename Scalar<V>::type* ty,
                      const typename Scalar<V>::type* tx_lo, const typename Scalar<V>::type* ty_lo,
                      std::size_t nt, const Sources& sources, double* out_x, double* out_y) {
  constexpr std::size_t B = R * kLanes<V>;
  const std::size_t full = nt / B * B;
  if (full > 0) run_blocks<V, R>(tx, ty, tx_lo, ty_lo, full, sources, out_x, out_y);
  if (full == nt) return;
  const auto rest = [full](const auto* p) { return p == nullptr ? p : p + full; };
  run_blocks<V, 1>(rest(tx), rest(ty), rest(tx_lo), rest(ty_lo), nt - full, sources, out_x + full,
                   out_y + full);
}

template <typename T>
struct VectorOf;
template <>
struct VectorOf<double> {
  using type = VD;
};
template <>
struct VectorOf<float> {
  using type = VF;
};

// Pairs between two disjoint sets of bodies, each pair once (Newton's third
// law): a's sums over b added to (a_x, a_y), b's over a to (b_x, b_y). Both
// sizes are whole vectors, and at most kFloatTile (the caller pads with
// massless bodies). U vectors of b's bodies stay in registers and turn
// through their lanes, one permute a turn: at turn k, lane l pairs a's body l
// of each vector with b's body l + k (mod L), for every vector of a; b's
// sums turn with b's bodies (after L turns all are back in place), a's are
// in memory (the vector loop reads and writes them: loads and stores are not
// what bounds it). Each sum runs in a fixed order, in float for float32 and
// added in double at the end, as run_blocks' tiles.
//
// U = kPairVectors: three vectors of b a pass where the registers hold them
// (AVX-512's 32): a's loads and stores serve three, and three independent
// pair chains overlap; four would spill. A stripe's last vectors take a
// pass of two, then of one. AVX2 (16 registers) gains nothing from two: it
// keeps one.
#if defined(__AVX512F__)
constexpr std::size_t kPairVectors = 3;
#else
constexpr std::size_t kPairVectors = 1;
#endif

// What pairs_between's passes share: a's bodies with their masses times
// `scale` (mass), a's sums, and the law's constants.
template <typename V>
struct PairPass {
  using T = typename Scalar<V>::type;
  const Bodies<T>& a;
  const Bodies<T>& b;
  const T* mass;
  T* sum_x;
  T* sum_y;
  T scale;
  V eps2, lo, hi;
};

// pairs_between's weight of a pair, without the masses: Plummer's law with
// an estimate gives cube_scaled (the masses carry kCubeScale), the other laws
// weight() with unit mass.
template <Law kLaw, typename V, bool kViaFloat>
constexpr bool kPairCube = kLaw == Law::plummer && !kViaFloat && kNewtonSteps<V> != 0;

template <Law kLaw, bool kMasked, typename V, bool kViaFloat>
[[gnu::always_inline]] inline V pair_weight(V dx, V dy, V eps2, V lo, V hi) {
  if constexpr (kPairCube<kLaw, V, kViaFloat>) {
    V r2 = dx * dx + eps2;
    r2 = dy * dy + r2;
    const V w = cube_scaled(r2);
    if constexpr (kMasked) return r2 >= kTiny<V> ? w : V{};
    return w;
  } else {
    return weight<kLaw, kMasked, V, kViaFloat>(dx, dy, splat<V>(1), eps2, lo, hi);
  }
}

// One pass: b's vectors j0 to j0 + U L against all of a, L turns.
template <typename V, std::size_t U, Law kLaw, bool kMasked, bool kSplit, bool kViaFloat>
void pairs_pass(const PairPass<V>& p, std::size_t j0, double* b_x, double* b_y) {
  using T = typename Scalar<V>::type;
  constexpr std::size_t L = kLanes<V>;
  V xj[U], yj[U], xj_lo[U], yj_lo[U], mj[U], total_x[U], total_y[U];
  for (std::size_t u = 0; u < U; ++u) {
    const std::size_t j = j0 + u * L;
    xj[u] = load<V>(p.b.x + j);
    yj[u] = load<V>(p.b.y + j);
    xj_lo[u] = kSplit ? load<V>(p.b.x_lo + j) : V{};
    yj_lo[u] = kSplit ? load<V>(p.b.y_lo + j) : V{};
    mj[u] = load<V>(p.b.m + j) * p.scale;
    total_x[u] = total_y[u] = V{};
  }
  // (Locals: the stores to the sums could alias p's members.)
  const T* const x = p.a.x;
  const T* const y = p.a.y;
  const T* const x_lo = p.a.x_lo;
  const T* const y_lo = p.a.y_lo;
  const T* const mass = p.mass;
  T* const sum_x = p.sum_x;
  T* const sum_y = p.sum_y;
  const std::size_t n = p.a.n;
  const V eps2 = p.eps2;
  const V lo = p.lo;
  const V hi = p.hi;
  for (std::size_t turn = 0; turn < L; ++turn) {
    V jx[U], jy[U];
    for (std::size_t u = 0; u < U; ++u) jx[u] = jy[u] = V{};
    for (std::size_t i0 = 0; i0 < n; i0 += L) {
      const V xi = load<V>(x + i0);
      const V yi = load<V>(y + i0);
      const V xi_lo = kSplit ? load<V>(x_lo + i0) : V{};
      const V yi_lo = kSplit ? load<V>(y_lo + i0) : V{};
      const V mi = load<V>(mass + i0);
      V ax = load<V>(sum_x + i0);
      V ay = load<V>(sum_y + i0);
      for (std::size_t u = 0; u < U; ++u) {
        V dx = xj[u] - xi;
        V dy = yj[u] - yi;
        if constexpr (kSplit) {
          dx = dx + (xj_lo[u] - xi_lo);
          dy = dy + (yj_lo[u] - yi_lo);
        }
        const V w = pair_weight<kLaw, kMasked, V, kViaFloat>(dx, dy, eps2, lo, hi);
        const V wi = w * mj[u];
        const V wj = w * mi;
        ax = wi * dx + ax;
        ay = wi * dy + ay;
        jx[u] = jx[u] - wj * dx;
        jy[u] = jy[u] - wj * dy;
      }
      std::memcpy(sum_x + i0, &ax, sizeof ax);
      std::memcpy(sum_y + i0, &ay, sizeof ay);
    }
    for (std::size_t u = 0; u < U; ++u) {
      total_x[u] = rotate_lanes(total_x[u] + jx[u]);
      total_y[u] = rotate_lanes(total_y[u] + jy[u]);
      xj[u] = rotate_lanes(xj[u]);
      yj[u] = rotate_lanes(yj[u]);
      if constexpr (kSplit) {
        xj_lo[u] = rotate_lanes(xj_lo[u]);
        yj_lo[u] = rotate_lanes(yj_lo[u]);
      }
      mj[u] = rotate_lanes(mj[u]);
    }
  }
  for (std::size_t k = 0; k < U * L; ++k) {
    b_x[j0 + k] += static_cast<double>(total_x[k / L][k % L]);
    b_y[j0 + k] += static_cast<double>(total_y[k / L][k % L]);
  }
}

template <typename V, Law kLaw, bool kMasked, bool kSplit, bool kViaFloat = false>
void pairs_between(const Bodies<typename Scalar<V>::type>& a,
                   const Bodies<typename Scalar<V>::type>& b, V eps2, V lo, V hi, double* a_x,
                   double* a_y, double* b_x, double* b_y) {
  using T = typename Scalar<V>::type;
  constexpr std::size_t L = kLanes<V>;
  // Plummer's law with an estimate: both sides' masses carry kCubeScale, one
  // product a pair fewer.
  constexpr bool kCube = kPairCube<kLaw, V, kViaFloat>;
  alignas(64) T sum_x[kFloatTile];
  alignas(64) T sum_y[kFloatTile];
  alignas(64) T mass[kFloatTile];
  const PairPass<V> pass{a, b, mass, sum_x, sum_y, kCube ? kCubeScale<V> : T(1), eps2, lo, hi};
  for (std::size_t i = 0; i < a.n; ++i) {
    sum_x[i] = sum_y[i] = T(0);
    mass[i] = a.m[i] * pass.scale;
  }
  std::size_t j0 = 0;
  for (; b.n - j0 >= kPairVectors * L; j0 += kPairVectors * L) {
    pairs_pass<V, kPairVectors, kLaw, kMasked, kSplit, kViaFloat>(pass, j0, b_x, b_y);
  }
  if constexpr (kPairVectors > 2) {
    if (b.n - j0 >= 2 * L) {
      pairs_pass<V, 2, kLaw, kMasked, kSplit, kViaFloat>(pass, j0, b_x, b_y);
      j0 += 2 * L;
    }
  }
  for (; j0 < b.n; j0 += L) pairs_pass<V, 1, kLaw, kMasked, kSplit, kViaFloat>(pass, j0, b_x, b_y);
  for (std::size_t i = 0; i < a.n; ++i) {
    a_x[i] += static_cast<double>(sum_x[i]);
    a_y[i] += static_cast<double>(sum_y[i]);
  }
}

template <typename T>
T eps2_of(const LawParams& p) {
  if constexpr (sizeof(T) == 4) {
    return p.eps2_f;
  } else {
    return p.eps2;
  }
}

// Point sources under the law of p, R vectors of targets per block.
template <typename V, std::size_t R, bool kSplit, bool kGroup>
void accumulate_law(const typename Scalar<V>::type* tx, const typename Scalar<V>::type* ty,
                    const typename Scalar<V>::type* tx_lo, const typename Scalar<V>::type* ty_lo,
                    std::size_t nt, const Bodies<typename Scalar<V>::type>& s, const LawParams& p,
                    double* out_x, double* out_y) {
  using T = typename Scalar<V>::type;
  const T eps2 = eps2_of<T>(p);
  const V lo = splat<V>(sizeof(T) == 4 ? T(p.lo_f) : T(p.lo));
  const V hi = splat<V>(sizeof(T) == 4 ? T(p.hi_f) : T(p.hi));
  const V e = splat<V>(eps2);
  const auto run = [&](const auto& sources) {
    if constexpr (kGroup) {
      run_group_blocks<V, R>(tx, ty, tx_lo, ty_lo, nt, sources, out_x, out_y);
    } else {
      run_blocks<V, R>(tx, ty, tx_lo, ty_lo, nt, sources, out_x, out_y);
    }
  };
  switch (p.law) {
    case Law::plummer:
      if constexpr (kFloatEstimate && sizeof(T) == 8) {
        if (p.float_range) {
          run(PointSources<V, Law::plummer, false, kSplit, true>{s, e, lo, hi});
          break;
        }
      }
      if (eps2 >= kTiny<V>) {
        run(PointSources<V, Law::plummer, false, kSplit>{s, e, lo, hi});
      } else {
        run(PointSources<V, Law::plummer, true, kSplit>{s, e, lo, hi});
      }
      break;
    case Law::clamp_distance:
      run(PointSources<V, Law::clamp_distance, true, kSplit>{s, e, lo, hi});
      break;
    case Law::clamp_squared_distance:
      run(PointSources<V, Law::clamp_squared_distance, true, kSplit>{s, e, lo, hi});
      break;
  }
}

template <std::size_t R, bool kGroup>
void accumulate64(const double* tx, const double* ty, std::size_t nt, const Bodies<double>& s,
                  const LawParams& p, double* out_x, double* out_y) {
  accumulate_law<VD, R, false, kGroup>(tx, ty, nullptr, nullptr, nt, s, p, out_x, out_y);
}

template <std::size_t R, bool kGroup>
void accumulate32(const float* tx, const float* ty, const float* tx_lo, const float* ty_lo,
                  std::size_t nt, const Bodies<float>& s, const LawParams& p, double* out_x,
                  double* out_y) {
  if (tx_lo != nullptr && ty_lo != nullptr && s.x_lo != nullptr && s.y_lo != nullptr) {
    accumulate_law<VF, R, true, kGroup>(tx, ty, tx_lo, ty_lo, nt, s, p, out_x, out_y);
  } else {
    accumulate_law<VF, R, false, kGroup>(tx, ty, nullptr, nullptr, nt, s, p, out_x, out_y);
  }
}

// pairs_between under the law of p.
template <typename V, bool kSplit>
void pairs_law(const Bodies<typename Scalar<V>::type>& a, const Bodies<typename Scalar<V>::type>& b,
               const LawParams& p, double* a_x, double* a_y, double* b_x, double* b_y) {
  using T = typename Scalar<V>::type;
  const T eps2 = eps2_of<T>(p);
  const V lo = splat<V>(sizeof(T) == 4 ? T(p.lo_f) : T(p.lo));
  const V hi = splat<V>(sizeof(T) == 4 ? T(p.hi_f) : T(p.hi));
  const V e = splat<V>(eps2);
  switch (p.law) {
    case Law::plummer:
      if constexpr (kFloatEstimate && sizeof(T) == 8) {
        if (p.float_range) {
          pairs_between<V, Law::plummer, false, kSplit, true>(a, b, e, lo, hi, a_x, a_y, b_x, b_y);
          break;
        }
      }
      if (eps2 >= kTiny<V>) {
        pairs_between<V, Law::plummer, false, kSplit>(a, b, e, lo, hi, a_x, a_y, b_x, b_y);
      } else {
        pairs_between<V, Law::plummer, true, kSplit>(a, b, e, lo, hi, a_x, a_y, b_x, b_y);
      }
      break;
    case Law::clamp_distance:
      pairs_between<V, Law::clamp_distance, true, kSplit>(a, b, e, lo, hi, a_x, a_y, b_x, b_y);
      break;
    case Law::clamp_squared_distance:
      pairs_between<V, Law::clamp_squared_distance, true, kSplit>(a, b, e, lo, hi, a_x, a_y, b_x,
                                                                  b_y);
      break;
  }
}

void pairs64(const Bodies<double>& a, const Bodies<double>& b, const LawParams& p, double* a_x,
             double* a_y, double* b_x, double* b_y) {
  pairs_law<VD, false>(a, b, p, a_x, a_y, b_x, b_y);
}

void pairs32(const Bodies<float>& a, const Bodies<float>& b, const LawParams& p, double* a_x,
             double* a_y, double* b_x, double* b_y) {
  if (a.x_lo != nullptr && a.y_lo != nullptr && b.x_lo != nullptr && b.y_lo != nullptr) {
    pairs_law<VF, true>(a, b, p, a_x, a_y, b_x, b_y);
  } else {
    pairs_law<VF, false>(a, b, p, a_x, a_y, b_x, b_y);
  }
}

template <typename T>
void accumulate_multipole(const T* tx, const T* ty, std::size_t nt, const Nodes<T>& s,
                          const LawParams& p, double* out_x, double* out_y) {
  using V = typename VectorOf<T>::type;
  run_group_blocks<V, kGroupBlockVectors>(
      tx, ty, nullptr, nullptr, nt, MultipoleSources<V>{s, splat<V>(eps2_of<T>(p))}, out_x, out_y);
}

// A vector of targets at a time (a short tail padded with its first
// target): the basis along u and along v, the values contracted along v,
// then along u. Every lane does the same operations in the same order.
void interpolate_far(const double* tx, const double* ty, std::size_t nt, const FarField& far,
                     double* out_x, double* out_y) {
  constexpr std::size_t S = kFarStencil;
  constexpr std::size_t L = kLanes<VD>;
  for (std::size_t first = 0; first < nt; first += L) {
    double buffer_x[L];
    double buffer_y[L];
    const VD u = (load<VD>(block_of(tx, first, nt, buffer_x)) - far.cx) * far.inv_half;
    const VD v = (load<VD>(block_of(ty, first, nt, buffer_y)) - far.cy) * far.inv_half;
    VD lu[S];
    VD lv[S];
    for (std::size_t i = 0; i < S; ++i) {
      lu[i] = splat<VD>(far.weights[i]);
      lv[i] = lu[i];
      for (std::size_t j = 0; j < S; ++j) {
        if (j != i) {
          lu[i] *= u - far.nodes[j];
          lv[i] *= v - far.nodes[j];
        }
      }
    }
    VD ax = {};
    VD ay = {};
    for (std::size_t i = 0; i < S; ++i) {
      VD cx = {};
      VD cy = {};
      for (std::size_t j = 0; j < S; ++j) {
        cx += lv[j] * far.fx[i * S + j];
        cy += lv[j] * far.fy[i * S + j];
      }
      ax += lu[i] * cx;
      ay += lu[i] * cy;
    }
    const std::size_t count = nt - first < L ? nt - first : L;
    for (std::size_t k = 0; k < count; ++k) {
      out_x[first + k] += ax[k];
      out_y[first + k] += ay[k];
    }
  }
}

}  // namespace

const KernelTable& CALDER_NBODY_CAT(kernel_table_, CALDER_KERNEL_VARIANT)() {
  static const KernelTable table{kName,
                                 kBlockVectors64 * kLanes<VD>,
                                 kBlockVectors32 * kLanes<VF>,
                                 accumulate64<kBlockVectors64, false>,
                                 accumulate32<kBlockVectors32, false>,
                                 kLanes<VD>,
                                 kLanes<VF>,
                                 accumulate64<kGroupBlockVectors, true>,
                                 accumulate32<kGroupBlockVectors, true>,
                                 accumulate_multipole<double>,
                                 accumulate_multipole<float>,
                                 kTargetBlock64,
                                 interpolate_far,
                                 pairs64,
                                 pairs32};
  return table;
}

}  // namespace calder::nbody::detail
