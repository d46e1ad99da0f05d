// SPDX-License-Identifier: MIT
// calder internals: the vocabulary the field kinds' laws (src/field_kinds/)
// are written in, once for the World's plain loops and the kernels of
// calder::bulk.
//
// A law is a template over a lane policy P that says what one lane is and
// how its arithmetic goes:
//
//   P::R               the precision (double, float)
//   P::L               a lane: R itself (the plain loops, one body at a time)
//                      or a vector of R (the kernels, several bodies at once)
//   P::book            true: the book's operations in the book's order, the
//                      plain loops' bits (calder/forces.hpp's laws are these);
//                      false: the fast form of the same physics (fused
//                      multiply-adds, reciprocals)
//   P::sqrt(L)         correctly rounded square root
//   P::length<kTwice>(L sq)  |v| from |v|^2 (the fast float32 kernels: an
//                      estimate; kTwice: 2 |v|, when P::kLengthEstimate)
//   P::splat(R)        a lane with the value in every place
//   P::all()           a mask that is true in every lane
//   P::quotient(b, x)  x / mass of body lane b, the divide's bits
//
// and over a body lane B: x, y, vx, vy (the state), ax, ay (the accelerations
// the fields add to), and m(), inv_m(), r(), area(), mu() (mass, 1 / mass,
// radius, drag area, own friction coefficient or NaN). Conditions are
// computed in every lane and select results (`mask ? a : b`): a lane that
// must not change keeps its old value, which is the plain loops' skipped
// branch bit for bit.
//
// Every template here takes P, so that a kernel file, whose P has internal
// linkage, never shares an instantiation (and so its flags) with the core.
#pragma once

#include <cmath>
#include <cstddef>

#include "calder/vec2.hpp"

#if defined(__GNUC__)
// A law's per-lane function must be inlined into the kernels' vector loops.
#define CALDER_LANE_INLINE __attribute__((always_inline))
#else
#define CALDER_LANE_INLINE
#endif

namespace calder::lanes {

// A force or acceleration, one lane of each component.
template <class L>
struct Pair {
  L x, y;
};

// A force that applies only where `apply` is set (a mask, or a bool for one body).
template <class L, class M>
struct Masked {
  Pair<L> f;
  M apply;
};

// What a pass over the bodies knows besides them.
template <class R>
struct Frame {
  R width{}, height{}, dt{};
  int step = 0;  // the step of a kernel's batch (per-step forces)
};

// Internal linkage (as src/integrate.hpp): each translation unit has its own
// ScalarBook, so no instantiation of a law over it is shared with code built
// with other flags (a consumer's -ffp-contract=fast, say).
namespace {

// The plain loops' policy: one body, double, the book's arithmetic.
struct ScalarBook {
  using R = double;
  using L = double;
  static constexpr bool book = true;
  static constexpr bool kLengthEstimate = false;
  static L sqrt(L x) { return std::sqrt(x); }
  template <bool kTwice = false>
  static L length(L sq) {
    static_assert(!kTwice);
    return std::sqrt(sq);
  }
  static L splat(R x) { return x; }
  static bool all() { return true; }
  template <class B>
  static L quotient(const B& b, L x) {
    return x / b.m();
  }
};

}  // namespace

// acceleration += force / mass (book: the divide's bits) or force * (1 / mass)
// (fast), in the lanes where apply is set.
template <class P, class B, class M>
CALDER_LANE_INLINE inline void add_force(B& b, M apply, typename P::L fx, typename P::L fy) {
  using L = typename P::L;
  L ax, ay;
  if constexpr (P::book) {
    ax = b.ax + P::quotient(b, fx);
    ay = b.ay + P::quotient(b, fy);
  } else {
    ax = b.ax + fx * b.inv_m();
    ay = b.ay + fy * b.inv_m();
  }
  b.ax = apply ? ax : b.ax;
  b.ay = apply ? ay : b.ay;
}

// The same force (fx, fy) on every lane: Wind, Helium, NoiseWind, Gravity.
template <class P, class B>
CALDER_LANE_INLINE inline void add_uniform(B& b, typename P::R fx, typename P::R fy) {
  add_force<P>(b, P::all(), P::splat(fx), P::splat(fy));
}

// Vec2::set_mag(magnitude) on (x, y) whose length is len: normalize multiplies
// by 1 / len unless len = 0 (then the vector stays as it is), then by magnitude.
template <class P>
CALDER_LANE_INLINE inline Pair<typename P::L> set_mag(typename P::L x, typename P::L y,
                                                      typename P::L len, typename P::L magnitude) {
  using L = typename P::L;
  const L inv = typename P::R(1) / (len != typename P::R(0) ? len : P::splat(typename P::R(1)));
  return {x * inv * magnitude, y * inv * magnitude};
}

// Vec2::limit(max) on (x, y): if |f|^2 > max^2, f / |f| * max (p5's order).
template <class P>
CALDER_LANE_INLINE inline void limit(typename P::L& x, typename P::L& y, typename P::L max) {
  using L = typename P::L;
  const L m_sq = x * x + y * y;
  const L len = P::sqrt(m_sq);
  const auto over = m_sq > max * max;
  x = over ? x / len * max : x;
  y = over ? y / len * max : y;
}

// limit_drag: a resistive force limited so that, applied alone for one step of
// dt to a body of this mass, it never reverses the velocity: |F| <= m |v| / dt.
template <class P>
CALDER_LANE_INLINE inline void never_reverse(Pair<typename P::L>& f, typename P::L mass,
                                             typename P::L speed, typename P::R dt) {
  limit<P>(f.x, f.y, mass * speed / dt);
}

// The book's force against the motion (drag, friction): the velocity times
// -1, set to magnitude; speed is |v|.
template <class P>
CALDER_LANE_INLINE inline Pair<typename P::L> against_motion(typename P::L vx, typename P::L vy,
                                                             typename P::L speed,
                                                             typename P::L magnitude) {
  return set_mag<P>(-vx, -vy, speed, magnitude);
}

}  // namespace calder::lanes
