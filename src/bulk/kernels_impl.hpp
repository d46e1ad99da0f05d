// SPDX-License-Identifier: MIT
// calder::bulk: the tile kernels (see plan.hpp), as templates over the
// precision R and the arithmetic: kBook = true repeats the book's operations
// in its order (World's plain loops), kBook = false is the fast form of the
// same physics. The laws themselves are the field kinds'
// (src/field_kinds/), run here over vectors of bodies (KernelLanes).
//
// Included by kernels_book.cpp (compiled with -ffp-contract=off: no fused
// multiply-adds, so the book kernels give the plain loops' bits) and
// kernels_fast.cpp (-ffp-contract=fast), each compiled once per instruction
// set. A tile (kTile bodies at most) is copied into a Chunk, arrays of R that
// stay in the L1 cache through every step of the batch; each step runs over
// the chunk one vector of bodies at a time (GCC vector extensions): its
// position and velocity in registers, the constants an op uses (mass, radius,
// ...) read from the chunk by that op only. The out-of-order core overlaps
// consecutive vectors, so the steps cost arithmetic, not memory traffic, and
// the live registers stay few (x, y, vx, vy, ax, ay and an op's temporaries)
// whatever the target's register file: 16 with AVX2, 32 with AVX-512 (state
// kept in registers through a whole batch would not fit AVX2's and spill to
// the stack: lint.bulk_kernels_spills counts spills). Conditions
// are computed for every lane and select results, and lanes that must not
// change add exactly +0 or keep their old value. (A sum that is exactly zero is +0 in IEEE
// round-to-nearest unless both terms are -0, so accelerations, which start at +0, are never -0 and
// adding +0 leaves them unchanged: the book's skipped branches and the kernels' selects agree bit
// for bit.)
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

#include "../integrate.hpp"
#include "calder/bulk.hpp"
#include "plan.hpp"

// The kernels' lambdas (an op's force, a pass over a chunk) must be inlined
// into their vector loops: called, a Block goes through memory.
#define CALDER_BULK_INLINE __attribute__((always_inline))
// A pass over a chunk (one op's vector loop): in WebAssembly a function of its
// own, since V8 allocates registers function by function and, in the one large
// advance_chunk, keeps the loop's counter, bases and constants on the stack.
#if defined(__wasm__)
#define CALDER_BULK_PASS __attribute__((noinline))
#else
#define CALDER_BULK_PASS CALDER_BULK_INLINE
#endif
// A pass's vector loop two vectors an iteration (each_vector): native
// builds without AddressSanitizer. Under ASan the unrolled loops cost several
// times the compile time, and speed is not that build's point; WebAssembly
// keeps one vector.
#if defined(__wasm__) || defined(__SANITIZE_ADDRESS__)
#define CALDER_BULK_UNROLL
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define CALDER_BULK_UNROLL
#endif
#endif
#ifndef CALDER_BULK_UNROLL
#define CALDER_BULK_UNROLL _Pragma("GCC unroll 2")
#endif

namespace calder::bulk::detail {
// Internal linkage: each kernel file has its own copies, built with its own
// flags (see integrate.hpp).
namespace {

// One vector register of R: 64 bytes with AVX-512, 32 with AVX, 16 otherwise.
#if defined(__AVX512F__)
constexpr std::size_t kVectorBytes = 64;
#elif defined(__AVX__)
constexpr std::size_t kVectorBytes = 32;
#else
constexpr std::size_t kVectorBytes = 16;
#endif

template <class R>
struct Simd;
template <>
struct Simd<double> {
  using V = double __attribute__((vector_size(kVectorBytes)));
  using M = decltype(V{} < V{});  // comparison results: 0 or all ones per lane
  using U = std::uint64_t __attribute__((vector_size(kVectorBytes)));  // a lane's bits
};
template <>
struct Simd<float> {
  using V = float __attribute__((vector_size(kVectorBytes)));
  using M = decltype(V{} < V{});
  using U = std::uint32_t __attribute__((vector_size(kVectorBytes)));
};

// The range of quotient_by_mass's fused path: masses in [2^-200, 2^200],
// numerators 0 or in [2^-700, 2^700].
inline constexpr double kMassRange = 0x1p200;
inline constexpr int kNumeratorExponent = 700;

// What a batch's numerators (quotient_by_mass) were, lane by lane, in three
// instructions a quotient and no branch (a batch is checked once, after its
// last step): the sum of their magnitudes, above 2^700 if one was (or
// infinite, or NaN: NaN stays), and, in the sign bit of `tiny`, whether one
// was nonzero below 2^-700: |x|'s bits less 2^-700's are negative, |x|'s bits
// less 1 are not unless x = 0. (The sum of a batch's 2^15 numerators at most
// passes 2^700 from numerators above 2^685 too: those batches divide.)
template <class R>
struct Numerators {
  using V = typename Simd<R>::V;
  using U = typename Simd<R>::U;
  static constexpr std::uint64_t kLowBits = std::uint64_t{1023 - kNumeratorExponent} << 52;
  V magnitudes{};
  U tiny{};
  [[gnu::always_inline]] void add(V x) {
    const U bits = U(x) & ~((U{} + 1) << (8 * sizeof(R) - 1));  // |x|
    magnitudes += V(bits);
    tiny |= (bits - kLowBits) & ~(bits - 1);
  }
  [[nodiscard]] bool in_range() const {
    const auto high = !(magnitudes <= R(std::ldexp(1.0, kNumeratorExponent)));
    const U low = tiny >> (8 * sizeof(R) - 1);
    for (std::size_t l = 0; l < sizeof(U) / sizeof(R); ++l)
      if (high[l] != 0 || low[l] != 0) return false;
    return true;
  }
};

// Room for a tile padded to whole vectors, each column a whole number of
// 64-byte lines (so that every column of a 64-byte aligned Chunk is aligned).
template <class R>
inline constexpr std::size_t kChunkSize = kTile + 64 / sizeof(R);
static_assert(kChunkSize<float> * sizeof(float) % 64 == 0 &&
              kChunkSize<double> * sizeof(double) % 64 == 0 && 64 >= kVectorBytes);

// One column of a chunk, left uninitialised on purpose (BodyColumnsOf's
// `{}` would otherwise zero ~25 KB per tile and batch, measurable in the
// float64 kernels): each tile's load writes every value the kernels read.
template <class R>
struct ChunkColumn {
  R values[kChunkSize<R>];
  ChunkColumn() {}  // NOLINT(modernize-use-equals-default): = default would zero it under {}
};

// The tile's bodies in R, padded to whole vectors (lanes past the tile
// repeat its first body, a valid one, and are never stored back), with
// 1 / mass and the bounce's bounds on the radius beside them, 64-byte
// aligned.
template <class R>
struct alignas(64) Chunk : BodyColumnsOf<ChunkColumn<R>> {
  ChunkColumn<R> inv_m;
  ChunkColumn<R> x_min, x_max, y_min, y_max;  // fill_bounds
  // Every mass of the tile within kMassRange of 1: the book's quotients by the
  // mass come from its reciprocal (quotient_by_mass), and the batch's
  // numerators are checked after it (Numerators).
  bool masses_in_range = false;
  Numerators<R> numerators;
};

// One vector of a chunk's bodies: the state a step changes, in registers; the
// constants, loaded from the chunk by the ops that use them.
template <class R>
struct Block {
  using V = typename Simd<R>::V;
  static constexpr int kLanes = static_cast<int>(kVectorBytes / sizeof(R));
  V x, y, vx, vy, ax, ay;
  Numerators<R> numerators;  // the book's, kept in registers through a pass (each_vector)
  const Chunk<R>* chunk;
  std::size_t at;  // index of the first lane in the chunk's arrays

  [[gnu::always_inline]] static V load(const R* from) {
    V v;
    __builtin_memcpy(&v, from, sizeof v);
    return v;
  }
  [[gnu::always_inline]] V m() const { return load(chunk->mass.values + at); }
  [[gnu::always_inline]] V inv_m() const { return load(chunk->inv_m.values + at); }
  [[gnu::always_inline]] V r() const { return load(chunk->radius.values + at); }
  [[gnu::always_inline]] V x_min() const { return load(chunk->x_min.values + at); }
  [[gnu::always_inline]] V x_max() const { return load(chunk->x_max.values + at); }
  [[gnu::always_inline]] V y_min() const { return load(chunk->y_min.values + at); }
  [[gnu::always_inline]] V y_max() const { return load(chunk->y_max.values + at); }
  [[gnu::always_inline]] V area() const { return load(chunk->drag_area.values + at); }
  [[gnu::always_inline]] V mu() const { return load(chunk->friction.values + at); }
};

// Vector v of a chunk; its accelerations from the chunk (the tile's) or +0.
template <class R>
[[gnu::always_inline]] inline Block<R> load_block(Chunk<R>& chunk, std::size_t v,
                                                  bool accelerations) {
  Block<R> b;
  b.chunk = &chunk;
  b.at = v * static_cast<std::size_t>(Block<R>::kLanes);
  b.x = Block<R>::load(chunk.x.values + b.at);
  b.y = Block<R>::load(chunk.y.values + b.at);
  b.vx = Block<R>::load(chunk.vx.values + b.at);
  b.vy = Block<R>::load(chunk.vy.values + b.at);
  b.ax = accelerations ? Block<R>::load(chunk.ax.values + b.at) : typename Simd<R>::V{};
  b.ay = accelerations ? Block<R>::load(chunk.ay.values + b.at) : typename Simd<R>::V{};
  return b;
}

// Correctly rounded square roots, one instruction per vector. (A lane loop
// let GCC, tuned for 256-bit vectors, split a 512-bit sqrt into two halves
// through the stack: a failed store forwarding on every use. The maskz forms:
// the plain ones trip -Wmaybe-uninitialized in GCC 12's headers.)
template <class V>
[[gnu::always_inline]] inline V vsqrt(V v) {
  [[maybe_unused]] constexpr bool single = sizeof(v[0]) == 4;
#if defined(__AVX512F__)
  if constexpr (sizeof(V) == 64) {
    if constexpr (single) return V(_mm512_maskz_sqrt_ps(0xFFFF, __m512(v)));
    if constexpr (!single) return V(_mm512_maskz_sqrt_pd(0xFF, __m512d(v)));
  }
#endif
#if defined(__AVX__)
  if constexpr (sizeof(V) == 32) {
    if constexpr (single) return V(_mm256_sqrt_ps(__m256(v)));
    if constexpr (!single) return V(_mm256_sqrt_pd(__m256d(v)));
  }
#endif
#if defined(__wasm_simd128__)  // (clang leaves the lane loop below scalar)
  if constexpr (sizeof(V) == 16) {
    if constexpr (single) return V(__builtin_wasm_sqrt_f32x4(v));
    if constexpr (!single) return V(__builtin_wasm_sqrt_f64x2(v));
  }
#endif
  constexpr int lanes = static_cast<int>(sizeof(V) / sizeof(v[0]));
  V out = v;
  for (int l = 0; l < lanes; ++l) out[l] = std::sqrt(v[l]);
  return out;
}

// |v| for the fast float32 kernels: the hardware's reciprocal square root
// estimate (relative error < 2^-14 with AVX-512, 1.5 * 2^-12 with AVX) and one
// Newton step, about 2^-22, as -ffast-math compiles sqrtf; 0 where |v|^2 is
// below float's smallest normal number (|v| < 1.1e-19, whose drag or
// friction no float holds: the AVX and SSE estimates read such inputs as 0
// and give infinity). Elsewhere (float64, book) the correctly rounded vsqrt.
// kRsqrtEstimate: whether float32 |v| comes from the estimate (x86); where
// it does, kTwice asks for 2 |v|, the estimate's last multiplication by 1/2
// left to the caller's constants.
#if defined(__SSE__)
constexpr bool kRsqrtEstimate = true;
#else
constexpr bool kRsqrtEstimate = false;
#endif
template <class R, bool kBook, class V, bool kTwice = false>
[[gnu::always_inline]] inline V vlength(V sq) {
#if defined(__SSE__)
  if constexpr (!kBook && sizeof(R) == 4) {
    V estimate;
#if defined(__AVX512F__)
    if constexpr (sizeof(V) == 64) estimate = V(_mm512_maskz_rsqrt14_ps(0xFFFF, __m512(sq)));
#endif
#if defined(__AVX__)
    if constexpr (sizeof(V) == 32) estimate = V(_mm256_rsqrt_ps(__m256(sq)));
#endif
#if defined(__SSE__)
    if constexpr (sizeof(V) == 16) estimate = V(_mm_rsqrt_ps(__m128(sq)));
#endif
    // y' = y (3 - x y^2) / 2, |v| = x y' = t (3 - t y) / 2 with t = x y.
    const V t = sq * estimate;
    V length = t * (R(3) - t * estimate);
    if constexpr (!kTwice) length *= R(0.5);
    return sq >= std::numeric_limits<R>::min() ? length : V{};
  }
#endif
  static_assert(!kTwice || (kRsqrtEstimate && !kBook && sizeof(R) == 4));
  return vsqrt(sq);
}

template <class V, class R>
[[gnu::always_inline]] inline V splat(R value) {
  return V{} + value;
}

// mask ? a : b, lane by lane, for a comparison's mask (all ones or zero in
// each lane). WebAssembly: one v128.bitselect; clang compiles `?:` on a
// vector to `mask != 0` first (i64x2.eq, v128.not), which V8 keeps.
template <class M, class V>
[[gnu::always_inline]] inline V select_lanes(M mask, V a, V b) {
#if defined(__wasm_simd128__)
  if constexpr (sizeof(V) == 16) {
    using Bits = int __attribute__((vector_size(16)));
    return V(__builtin_wasm_bitselect(Bits(a), Bits(b), Bits(mask)));
  }
#endif
  return mask ? a : b;
}

// The book's quotient x / m by a body's mass, the same bits as the divide.
// Where the target has fused multiply-adds: from y = RN(1 / m), the chunk's
// inv_m, corrected twice, q1 = q0 + (x - m q0) y, q2 = q1 + (x - m q1) y, each
// correction rounded once. Markstein's theorem (P. Markstein, IBM J. Res. Dev.
// 34(1), 1990; Muller et al., Handbook of Floating-Point Arithmetic, on
// division with an FMA): if y is RN(1 / m) and q is within one ulp of x / m,
// then x - m q is exact and q + (x - m q) y rounds to RN(x / m). q0 = RN(x y)
// is within 1.5 ulps only; the first correction brings it within one. Why:
// the divider, not the FMA units, bounds the book arithmetic in float64, and
// the fused instructions and Numerators' checks issue beside other work
// (docs/PERFORMANCE.md has the rain scene's rates). The theorem needs no
// underflow or overflow on the way: masses in [2^-200, 2^200] (the tile's, checked when it is
// loaded) and numerators 0 or in [2^-700, 2^700] (checked after the batch, Numerators: a batch with
// any other is run again with the divides) keep every intermediate normal. Zeros keep their sign:
// the corrections are written q - (m q - x) y, whose residual is +0 for x = +-0 (q + (x - m q) y
// would turn -0 into +0). tests/test_movers.cpp (BookQuotients...) checks the bits against the
// divide on quotients that round near a midpoint.
#if defined(__FMA__) && defined(__AVX__)
inline constexpr bool kFusedQuotients = true;
#else
inline constexpr bool kFusedQuotients = false;
#endif

#if defined(__FMA__) && defined(__AVX__)
// x / m from y = RN(1 / m), the corrections above; float64 vectors.
template <class V>
[[gnu::always_inline]] inline V fused_quotient(V x, V m, V y) {
  // q - (m q - x) y: fmsub then fnmadd, one rounding each.
  const auto correct = [&](V q) CALDER_BULK_INLINE {
#if defined(__AVX512F__)
    if constexpr (sizeof(V) == 64) {
      const __m512d residual = _mm512_fmsub_pd(__m512d(q), __m512d(m), __m512d(x));
      return V(_mm512_fnmadd_pd(residual, __m512d(y), __m512d(q)));
    }
#endif
    if constexpr (sizeof(V) == 32) {
      const __m256d residual = _mm256_fmsub_pd(__m256d(q), __m256d(m), __m256d(x));
      return V(_mm256_fnmadd_pd(residual, __m256d(y), __m256d(q)));
    }
  };
  return correct(correct(x * y));
}
#endif

template <class R, class V>
[[gnu::always_inline]] inline V quotient_by_mass(Block<R>& b, V x) {
#if defined(__FMA__) && defined(__AVX__)
  if constexpr (std::is_same_v<R, double>) {
    if (b.chunk->masses_in_range) {
      b.numerators.add(x);
      return fused_quotient(x, b.m(), b.inv_m());
    }
  }
#endif
  return x / b.m();
}

// The kernels' lane policy (src/field_kinds/lanes.hpp): a vector of R in
// registers, the book's arithmetic (kBook) or the fast one. The field kinds'
// laws (src/field_kinds/) run over Blocks through it.
template <class Real, bool kBook>
struct KernelLanes {
  using R = Real;
  using L = typename Simd<R>::V;
  using M = typename Simd<R>::M;
  static constexpr bool book = kBook;
  static constexpr bool kLengthEstimate = kRsqrtEstimate;
  [[gnu::always_inline]] static L sqrt(L x) { return vsqrt(x); }
  template <bool kTwice = false>
  [[gnu::always_inline]] static L length(L sq) {
    return vlength<R, kBook, L, kTwice>(sq);
  }
  [[gnu::always_inline]] static L splat(R x) { return detail::splat<L>(x); }
  [[gnu::always_inline]] static M all() { return ~M{}; }
  [[gnu::always_inline]] static L quotient(Block<R>& b, L x) { return quotient_by_mass(b, x); }
};

// The bounce's parameters, converted once. An edge that doesn't bounce gets
// an infinite wall that no coordinate crosses, so that the bounce needs
// neither branches nor masks beyond the comparisons; one that bounces, the
// book's bounds exactly.
template <class R>
struct Walls {
  R right, bottom;  // the canvas's width and height, or +infinity
  R left, top;      // +0, or +infinity (the radius minus it: the bound, r exactly or -infinity)
  R reverse;
  bool before;
  explicit Walls(const Boundary& boundary, R width, R height)
      : right(boundary.edges.right ? width : std::numeric_limits<R>::infinity()),
        bottom(boundary.edges.bottom ? height : std::numeric_limits<R>::infinity()),
        left(boundary.edges.left ? R(0) : std::numeric_limits<R>::infinity()),
        top(boundary.edges.top ? R(0) : std::numeric_limits<R>::infinity()),
        reverse(R(-boundary.restitution)),
        before(boundary.timing == BoundaryTiming::before_update) {}
};

// World::boundary_one's bounce: right before left, bottom before top; clamp,
// then reverse.
template <class R, bool kUseRadius>
[[gnu::always_inline]] inline void bounce(Block<R>& b, const Walls<R>& walls) {
  using V = typename Simd<R>::V;
  const V x = b.x;
  const V y = b.y;
  V x_max, y_max, x_min, y_min;
  if constexpr (kUseRadius) {  // per body, once a batch (fill_bounds)
    x_max = b.x_max();
    y_max = b.y_max();
    x_min = b.x_min();
    y_min = b.y_min();
  } else {
    const V r = splat<V>(R(0));
    x_max = walls.right - r;
    y_max = walls.bottom - r;
    x_min = r - walls.left;  // r - (+0) is r, also for r = -0
    y_min = r - walls.top;
  }
  const auto right = x > x_max;
  const auto left = x < x_min;
  const auto bottom = y > y_max;
  const auto top = y < y_min;
  // The right (bottom) wall wins where a body touches both. (`x < x_min ?
  // x_min : x` is one f64x2.pmax in WebAssembly.)
  b.x = select_lanes(right, x_max, x < x_min ? x_min : x);
  b.y = select_lanes(bottom, y_max, y < y_min ? y_min : y);
  b.vx = select_lanes(right | left, b.vx * walls.reverse, b.vx);
  b.vy = select_lanes(bottom | top, b.vy * walls.reverse, b.vy);
}

// Whether the update bounces bodies on their radius: then its bounds are
// each body's (fill_bounds, bounce<R, true>).
inline bool bounces_on_radius(const Boundary& boundary) {
  return boundary.kind == BoundaryKind::bounce && boundary.use_radius;
}

// The bounce's bounds on the radius, each body's: the subtractions that
// World's bounce makes every step, made once a batch (the same in R).
template <class R>
void fill_bounds(const Plan& plan, Chunk<R>& chunk, std::size_t padded) {
  const Walls<R> walls(plan.boundary, R(plan.width), R(plan.height));
  for (std::size_t i = 0; i < padded; ++i) {
    const R r = chunk.radius.values[i];
    chunk.x_max.values[i] = walls.right - r;
    chunk.y_max.values[i] = walls.bottom - r;
    chunk.x_min.values[i] = r - walls.left;  // r - (+0) is r, also for r = -0
    chunk.y_min.values[i] = r - walls.top;
  }
}

// The update (semi-implicit Euler, acceleration cleared) and the bounce.
template <class R, bool kUseRadius, bool kBefore>
[[gnu::always_inline]] inline void update_bounce_at(Block<R>& b, const Walls<R>& walls, R dt) {
  if constexpr (kBefore) bounce<R, kUseRadius>(b, walls);
  calder::detail::kick_drift(b.x, b.y, b.vx, b.vy, b.ax, b.ay, splat<typename Simd<R>::V>(dt));
  if constexpr (!kBefore) bounce<R, kUseRadius>(b, walls);
}

// The periodic wrap, lane by lane (rare and branchy: not worth vectorising).
template <class R>
[[gnu::always_inline]] inline void wrap(Block<R>& b, const Boundary& boundary, R width, R height) {
  {
    for (int l = 0; l < Block<R>::kLanes; ++l) {
      const R r = boundary.use_radius ? b.r()[l] : R(0);
      if (boundary.edges.left || boundary.edges.right) {
        b.x[l] = calder::detail::wrap_coordinate(R(b.x[l]), -r, width + r);
      }
      if (boundary.edges.top || boundary.edges.bottom) {
        b.y[l] = calder::detail::wrap_coordinate(R(b.y[l]), -r, height + r);
      }
    }
  }
}

// The update and the boundary but the bounce on the radius (with_update
// gives that its own loops).
template <class R>
[[gnu::always_inline]] inline void update(Block<R>& b, const Boundary& boundary,
                                          const Walls<R>& walls, R width, R height, R dt) {
  using V = typename Simd<R>::V;
  if (boundary.kind == BoundaryKind::bounce) {
    if (walls.before) return update_bounce_at<R, false, true>(b, walls, dt);
    return update_bounce_at<R, false, false>(b, walls, dt);
  }
  const bool wrapping = boundary.kind == BoundaryKind::wrap;
  const bool before = boundary.timing == BoundaryTiming::before_update;
  if (wrapping && before) wrap(b, boundary, width, height);
  { calder::detail::kick_drift(b.x, b.y, b.vx, b.vy, b.ax, b.ay, splat<V>(dt)); }
  if (wrapping && !before) wrap(b, boundary, width, height);
}

// Hands `each` the force of one op: a function of a Block that adds it to
// the block's accelerations (its kind's law, FieldLaw<F>::run).
template <class R, bool kBook, class Each>
[[gnu::always_inline]] inline void apply_op(Each&& each, const Op& op, int step, R width, R height,
                                            R dt) {
  const lanes::Frame<R> frame{width, height, dt, step};
  std::visit(
      [&](const auto& kind_law) {
        if constexpr (requires { kind_law.law; }) {
          using Kind = typename std::decay_t<decltype(kind_law)>::Kind;
          Kind::template run<KernelLanes<R, kBook>>(each, kind_law.law, frame);
        }
      },
      op.template law<R>());
}

// The op's Gravity scaled by mass, or null.
template <class R>
[[gnu::always_inline]] inline const FieldLaw<Gravity>::Law<R>* scaled_gravity(const Op& op) {
  const auto* g = std::get_if<KindLaw<Gravity, R>>(&op.template law<R>());
  return g != nullptr && g->law.scaled ? &g->law : nullptr;
}

// The fast kernels fold the ops whose acceleration is the same for every body
// (gravity scaled by mass) into one constant: true, with it in (gx, gy), for
// such an op.
template <class R, bool kBook>
[[gnu::always_inline]] inline bool constant_op(const Op& op, R& gx, R& gy) {
  if constexpr (kBook) return false;
  if (const auto* g = scaled_gravity<R>(op)) {
    gx = g->gx;
    gy = g->gy;
    return true;
  }
  return false;
}

// Hands `last` (a function of an update) the update of the boundary's kind,
// with the bounce's timing chosen outside the vector loop.
template <class R, class Last>
[[gnu::always_inline]] inline void with_update(Last&& last, const Boundary& boundary,
                                               const Walls<R>& walls, R width, R height, R dt) {
  if (bounces_on_radius(boundary)) {
    if (walls.before) {
      return last([=](Block<R>& b)
                      CALDER_BULK_INLINE { update_bounce_at<R, true, true>(b, walls, dt); });
    }
    return last([=](Block<R>& b)
                    CALDER_BULK_INLINE { update_bounce_at<R, true, false>(b, walls, dt); });
  }
  last([=](Block<R>& b) CALDER_BULK_INLINE { update(b, boundary, walls, width, height, dt); });
}

// A book kernel's gravity_scaled op just before the last op runs in the
// last op's pass (its quotients beside the last op's), not in a pass of its
// own: WebAssembly, because V8's code for a pass costs more per vector than
// GCC's, in loads, stores and loop overhead; native, because its
// multiplications overlap the drag's square root and division. Same
// operations in the same order.
constexpr bool kFuseGravityTarget = true;

// Native book kernels run the update (velocity, position, bounce) in a pass
// of its own after the last op's, not in it: the drag's chain (square root,
// division, quotients by the mass) and the update's after it make the
// longest chain of a step, and in one loop the operations waiting on it fill
// the out-of-order window. The drag's square root and division stay with the
// other forces: alone in a pass they would wait on the divider instead of
// overlapping the rest. WebAssembly keeps one pass (V8's passes cost more,
// above). The fast float32 kernels with AVX2 too; not float64, whose chain
// is short, so that the pass's loads and stores cost more than they save, nor
// AVX-512, where it makes no difference.
#if defined(__wasm__)
template <class R, bool kBook>
constexpr bool kUpdatePass = false;
#else
template <class R, bool kBook>
constexpr bool kUpdatePass = kBook || (sizeof(R) == 4 && kVectorBytes == 32);
#endif

// How a step runs the ops: `passes` lists the ops that need a pass over the
// chunk, in order, the first `own` of them in a loop of their own; the fast
// kernels' constant accelerations are summed into (cx, cy), and a fused
// gravity (kFuseGravityTarget) runs in the last pass with (gx, gy).
template <class R>
struct Passes {
  R cx = 0, cy = 0, gx = 0, gy = 0;
  bool fused = false;
  std::size_t own = 0;
};

template <class R, bool kBook>
Passes<R> plan_passes(const Plan& plan, std::vector<std::size_t>& passes) {
  Passes<R> out;
  passes.clear();
  for (std::size_t k = 0; k < plan.ops.size(); ++k) {
    R gx, gy;
    if (constant_op<R, kBook>(plan.ops[k], gx, gy)) {
      out.cx += gx;
      out.cy += gy;
    } else {
      passes.push_back(k);
    }
  }
  out.own = passes.size();
  if (kBook && kFuseGravityTarget && passes.size() >= 2) {
    const Op& op = plan.ops[passes[passes.size() - 2]];
    const auto* g = scaled_gravity<R>(op);
    out.fused = g != nullptr;
    out.gx = out.fused ? g->gx : R(0);
    out.gy = out.fused ? g->gy : R(0);
    out.own -= out.fused ? 1 : 0;
  }
  return out;
}

// A pass's vector loop: `body` on every vector of the chunk, loaded by
// `first_load` in the step's first pass (`first`), else with the
// accelerations the earlier passes stored: a loop each, so that no vector
// tests which.
template <class R, class FirstLoad, class Body>
[[gnu::always_inline]] inline void each_vector(Chunk<R>& chunk, std::size_t vectors, bool first,
                                               FirstLoad first_load, Body body) {
  // Two vectors an iteration (CALDER_BULK_UNROLL): their chains side by side,
  // which the narrower vectors (SSE2, AVX2) need to keep the core busy.
  Numerators<R> seen = chunk.numerators;  // in registers through the loop
  if (first) {
    CALDER_BULK_UNROLL
    for (std::size_t v = 0; v < vectors; ++v) {
      Block<R> b = first_load(v);
      b.numerators = seen;
      body(b);
      seen = b.numerators;
    }
  } else {
    CALDER_BULK_UNROLL
    for (std::size_t v = 0; v < vectors; ++v) {
      Block<R> b = load_block(chunk, v, true);
      b.numerators = seen;
      body(b);
      seen = b.numerators;
    }
  }
  chunk.numerators = seen;
}

// A vector's accelerations, or its positions and velocities, back to the chunk.
template <class R>
[[gnu::always_inline]] inline void store_accelerations(Chunk<R>& to, const Block<R>& b) {
  __builtin_memcpy(to.ax.values + b.at, &b.ax, sizeof b.ax);
  __builtin_memcpy(to.ay.values + b.at, &b.ay, sizeof b.ay);
}
template <class R>
[[gnu::always_inline]] inline void store_state(Chunk<R>& to, const Block<R>& b) {
  __builtin_memcpy(to.x.values + b.at, &b.x, sizeof b.x);
  __builtin_memcpy(to.y.values + b.at, &b.y, sizeof b.y);
  __builtin_memcpy(to.vx.values + b.at, &b.vx, sizeof b.vx);
  __builtin_memcpy(to.vy.values + b.at, &b.vy, sizeof b.vy);
}

// The last pass of a step: the fused gravity (`before`), the last op
// (`force`) and the update, in one loop, or in two (kUpdatePass). The
// functions are parameters, so local copies: else the stores below (memcpy:
// may alias anything) make every vector read them again through closures
// (WebAssembly).
template <class R, bool kBook, class FirstLoad, class Before, class Force, class Update>
[[gnu::always_inline]] inline void last_pass(Chunk<R>& to, std::size_t vectors, bool alone,
                                             FirstLoad first_load, Before before, Force force,
                                             Update update) {
  if constexpr (kUpdatePass<R, kBook>) {
    each_vector(to, vectors, alone, first_load, [&](Block<R>& b) CALDER_BULK_INLINE {
      before(b);
      force(b);
      store_accelerations(to, b);
    });
    each_vector(to, vectors, false, first_load, [&](Block<R>& b) CALDER_BULK_INLINE {
      update(b);
      store_state(to, b);
    });
  } else {
    each_vector(to, vectors, alone, first_load, [&](Block<R>& b) CALDER_BULK_INLINE {
      before(b);
      force(b);
      update(b);
      store_state(to, b);
    });
  }
}

// Runs one step of the batch (step 0: kFirst) over a chunk of `vectors`
// vectors: one pass over the chunk per op, each adding its force to the
// accelerations in the chunk, but the last op's pass also runs the update, in
// registers, and stores only positions and velocities (the native book
// kernels: the update in a pass of its own, kUpdatePass). The accelerations are
// the tile's on the first step and +0 on the others (the update clears them),
// so the first pass of a later step doesn't read them; the two kinds of step
// are two copies of the loops, so that no vector tests which it is. (One pass
// for every op and the update together would store least, but then every
// vector goes through the ops' dispatch, which costs more than the stores.)
template <class R, bool kBook, bool kFirst>
void advance_step(const Plan& plan, Chunk<R>& chunk, std::size_t vectors,
                  const std::vector<std::size_t>& passes, const Passes<R>& how, int step) {
  using V = typename Simd<R>::V;
  const R width = R(plan.width);
  const R height = R(plan.height);
  const R dt = R(plan.dt);
  const Boundary boundary = plan.boundary;
  const Walls<R> walls(boundary, width, height);
  const V base_x = splat<V>(how.cx);  // never -0: a sum from +0
  const V base_y = splat<V>(how.cy);
  // Vector v as the first pass of the step sees it.
  const auto first_load = [=, &chunk](std::size_t v) CALDER_BULK_INLINE {
    Block<R> b = load_block(chunk, v, kFirst);
    if constexpr (!kBook) {
      if constexpr (kFirst) {
        b.ax += base_x;
        b.ay += base_y;
      } else {  // +0 + base
        b.ax = base_x;
        b.ay = base_y;
      }
    }
    return b;
  };
  for (std::size_t q = 0; q + 1 < how.own; ++q) {
    const std::size_t k = passes[q];
    const auto each = [&](auto force) CALDER_BULK_PASS {
      // Local copies: else the stores below (memcpy: may alias anything) make
      // every vector read them again through the closures (WebAssembly).
      const auto op = force;
      Chunk<R>& to = chunk;
      each_vector(to, vectors, q == 0, first_load, [&](Block<R>& b) CALDER_BULK_INLINE {
        op(b);
        store_accelerations(to, b);
      });
    };
    apply_op<R, kBook>(each, plan.ops[k], step, width, height, dt);
  }
  // The last pass: the fused gravity (`before`), the last op, the update, the boundary.
  const bool alone = how.own <= 1;
  const auto last = [&](auto update_one, auto before) CALDER_BULK_INLINE {
    const auto each = [&](auto force) CALDER_BULK_PASS {
      last_pass<R, kBook>(chunk, vectors, alone, first_load, before, force, update_one);
    };
    if (passes.empty()) return each([](Block<R>&) CALDER_BULK_INLINE {});
    const std::size_t k = passes.back();
    apply_op<R, kBook>(each, plan.ops[k], step, width, height, dt);
  };
  with_update(
      [&](auto update_one) CALDER_BULK_INLINE {
        if constexpr (kBook && kFuseGravityTarget) {
          if (how.fused) {
            return last(update_one, [=](Block<R>& b) CALDER_BULK_INLINE {
              FieldLaw<Gravity>::scaled<KernelLanes<R, kBook>>(b, how.gx, how.gy);
            });
          }
        }
        last(update_one, [](Block<R>&) CALDER_BULK_INLINE {});
      },
      boundary, walls, width, height, dt);
}

// Runs every step of the batch over a chunk of `vectors` vectors.
template <class R, bool kBook>
void advance_chunk(const Plan& plan, Chunk<R>& chunk, std::size_t vectors,
                   std::vector<std::size_t>& passes) {
  const Passes<R> how = plan_passes<R, kBook>(plan, passes);
  if (plan.steps > 0) advance_step<R, kBook, true>(plan, chunk, vectors, passes, how, 0);
  for (int step = 1; step < plan.steps; ++step) {
    advance_step<R, kBook, false>(plan, chunk, vectors, passes, how, step);
  }
}

// 1 / mass beside the masses (the fast kernels' factor, the book's y in
// quotient_by_mass), padded lanes from the first body; whether the book's
// quotients may come from it.
template <bool kBook, class R>
void fill_reciprocals(Chunk<R>& chunk, const double* mass, std::size_t n, std::size_t padded) {
  bool in_range = true;
  for (std::size_t i = 0; i < padded; ++i) {
    const double m = mass[i < n ? i : 0];
    in_range &= m >= 1 / kMassRange && m <= kMassRange;
    chunk.inv_m.values[i] = R(1.0 / m);
  }
  chunk.masses_in_range = kBook && kFusedQuotients && in_range;
}

// Runs `run` over the chunk (a batch), then, where a numerator fell outside
// quotient_by_mass's range (rare: a force near underflow or overflow, or not
// finite), `load`s the chunk again and runs it with the divides.
template <bool kBook, class R, class Load, class Run>
void run_checking_quotients(Chunk<R>& chunk, Load load, Run run) {
  chunk.numerators = {};
  run();
  if constexpr (kBook && kFusedQuotients) {
    if (chunk.masses_in_range && !chunk.numerators.in_range()) {
      load();
      chunk.masses_in_range = false;
      run();
    }
  }
}

template <class R, bool kBook>
void advance_tile(const Plan& plan, const Tile& tile) {
  if (plan.steps <= 0 || tile.n == 0) return;
  Chunk<R> chunk;  // on the stack: a thread_local's address costs a call per access here
  constexpr auto lanes = static_cast<std::size_t>(Block<R>::kLanes);
  const std::size_t vectors = (tile.n + lanes - 1) / lanes;
  const std::size_t padded = vectors * lanes;
  const auto load = [&] {
    for_each_column(
        [&](const char*, ChunkColumn<R>& to, const double* from) {
          for (std::size_t i = 0; i < tile.n; ++i) to.values[i] = R(from[i]);
          std::fill(to.values + tile.n, to.values + padded, R(from[0]));
        },
        chunk, tile.bodies);
  };
  load();
  if (!kBook || kFusedQuotients) fill_reciprocals<kBook>(chunk, tile.bodies.mass, tile.n, padded);
  if (bounces_on_radius(plan.boundary)) fill_bounds(plan, chunk, padded);
  thread_local std::vector<std::size_t> passes;
  run_checking_quotients<kBook>(chunk, load,
                                [&] { advance_chunk<R, kBook>(plan, chunk, vectors, passes); });
  // The last pass keeps the accelerations in registers: cleared by the update.
  std::fill_n(chunk.ax.values, tile.n, R(0));
  std::fill_n(chunk.ay.values, tile.n, R(0));
  for_each_state([&](const char*, const ChunkColumn<R>& from,
                     double* to) { std::copy_n(from.values, tile.n, to); },
                 chunk, tile.bodies);
}

inline void advance_book64(const Plan& plan, const Tile& tile) {
  advance_tile<double, true>(plan, tile);
}

// out[i] = x[i] / mass[i] as the book kernels divide (quotient_by_mass, its
// range check and fallback included), tile by tile: for the tests.
inline void book_quotients(const double* x, const double* mass, double* out, std::size_t n) {
  using V = Simd<double>::V;
  constexpr auto lanes = static_cast<std::size_t>(Block<double>::kLanes);
  Chunk<double> chunk;
  for (std::size_t start = 0; start < n; start += kTile) {
    const std::size_t count = std::min(kTile, n - start);
    const std::size_t vectors = (count + lanes - 1) / lanes;
    const auto load = [&] {
      for (std::size_t i = 0; i < vectors * lanes; ++i) {
        const std::size_t from = start + (i < count ? i : 0);
        chunk.mass.values[i] = mass[from];
        chunk.ax.values[i] = x[from];
      }
    };
    load();
    fill_reciprocals<true>(chunk, mass + start, count, vectors * lanes);
    run_checking_quotients<true>(chunk, load, [&] {
      Numerators<double> seen = chunk.numerators;
      for (std::size_t v = 0; v < vectors; ++v) {
        Block<double> b{};
        b.chunk = &chunk;
        b.at = v * lanes;
        b.numerators = seen;
        const V q = quotient_by_mass(b, Block<double>::load(chunk.ax.values + b.at));
        seen = b.numerators;
        __builtin_memcpy(chunk.ay.values + b.at, &q, sizeof q);
      }
      chunk.numerators = seen;
    });
    std::copy_n(chunk.ay.values, count, out + start);
  }
}
inline void advance_fast64(const Plan& plan, const Tile& tile) {
  advance_tile<double, false>(plan, tile);
}
inline void advance_fast32(const Plan& plan, const Tile& tile) {
  advance_tile<float, false>(plan, tile);
}

}  // namespace
}  // namespace calder::bulk::detail

// The kernel files define their entry points per variant:
// CALDER_BULK_CAT(advance_book64_, CALDER_KERNEL_VARIANT) is advance_book64_<variant>.
#ifndef CALDER_KERNEL_VARIANT
#error "CALDER_KERNEL_VARIANT must name the variant (set by CMakeLists.txt)"
#endif
#define CALDER_BULK_CAT2(a, b) a##b
#define CALDER_BULK_CAT(a, b) CALDER_BULK_CAT2(a, b)
