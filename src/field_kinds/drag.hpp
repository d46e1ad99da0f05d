// SPDX-License-Identifier: MIT
// The law of Drag (calder/field_kinds/drag.hpp), which is also Liquid's
// (liquid.hpp), inside a region.
#pragma once

#include "calder/field_kinds/drag.hpp"
#include "law.hpp"

namespace calder {

namespace laws {

// Quadratic drag: magnitude (c * |v|) * |v| * area against the velocity (the
// book: -v set to c * speed * speed; area brings the frontal area back,
// exercise 2.9). speed is |v|.
template <class P>
CALDER_LANE_INLINE inline lanes::Pair<typename P::L> drag(typename P::L vx, typename P::L vy,
                                                          typename P::L speed, typename P::R c,
                                                          typename P::L area) {
  return lanes::against_motion<P>(vx, vy, speed, c * speed * speed * area);
}

// Drag on body lane b where `inside`, never reversing the velocity within dt
// when kNeverReverse. The fast form: a = -k v with k = c area |v| / m, and
// k dt <= 1 when never reversing; float32 computes (c / 2) (2 |v|), a
// multiplication fewer.
template <class P, bool kNeverReverse, class B, class M>
CALDER_LANE_INLINE inline void add_drag(B& b, M inside, typename P::R c, typename P::R dt) {
  using L = typename P::L;
  using R = typename P::R;
  const L vx = b.vx;
  const L vy = b.vy;
  if constexpr (P::book) {
    const L speed = P::length(vx * vx + vy * vy);
    lanes::Pair<L> f = drag<P>(vx, vy, speed, c, b.area());
    if constexpr (kNeverReverse) lanes::never_reverse<P>(f, b.m(), speed, dt);
    lanes::add_force<P>(b, inside, f.x, f.y);
  } else {
    constexpr bool kTwice = P::kLengthEstimate && sizeof(R) == 4;
    const L speed = P::template length<kTwice>(vx * vx + vy * vy);
    L k = (kTwice ? c * R(0.5) : c) * b.area() * speed * b.inv_m();
    if constexpr (kNeverReverse) k = k < R(1) / dt ? k : P::splat(R(1) / dt);
    b.ax = inside ? b.ax - k * vx : b.ax;
    b.ay = inside ? b.ay - k * vy : b.ay;
  }
}

}  // namespace laws

template <>
struct FieldLaw<Drag> {
  template <class R>
  struct Law {
    R c;
    bool never_reverse;
  };
  template <class R>
  static Law<R> law(const Drag& f) {
    return {R(f.c), f.never_reverse};
  }
  template <class P, class Each>
  static void run(Each&& each, const Law<typename P::R>& p,
                  const lanes::Frame<typename P::R>& frame) {
    const auto dt = frame.dt;
    if (p.never_reverse) {
      return each([=](auto& b)
                      CALDER_LANE_INLINE { laws::add_drag<P, true>(b, P::all(), p.c, dt); });
    }
    each([=](auto& b) CALDER_LANE_INLINE { laws::add_drag<P, false>(b, P::all(), p.c, dt); });
  }
};

}  // namespace calder
