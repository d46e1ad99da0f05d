// SPDX-License-Identifier: MIT
// The law of Friction (calder/field_kinds/friction.hpp).
#pragma once

#include "calder/field_kinds/friction.hpp"
#include "law.hpp"

namespace calder {

namespace laws {

// Kinetic friction: -mu * N * v-hat (the book: copy v, multiply by -1,
// set_mag(mu * N)); zero at rest. speed is |v|.
template <class P>
CALDER_LANE_INLINE inline lanes::Pair<typename P::L> friction(typename P::L vx, typename P::L vy,
                                                              typename P::L speed, typename P::L mu,
                                                              typename P::R normal) {
  return lanes::against_motion<P>(vx, vy, speed, mu * normal);
}

// Whether a circle of radius r at (x, y) touches the edge within tolerance
// (touches_edge; the book's 2.4: y > height - radius - 1).
template <class P>
CALDER_LANE_INLINE inline auto touches(Edge edge, typename P::L x, typename P::L y, typename P::L r,
                                       typename P::R tolerance, typename P::R width,
                                       typename P::R height) {
  switch (edge) {
    case Edge::left:
      return x < r + tolerance;
    case Edge::right:
      return x > width - r - tolerance;
    case Edge::top:
      return y < r + tolerance;
    case Edge::bottom:
      break;
  }
  return y > height - r - tolerance;
}

}  // namespace laws

template <>
struct FieldLaw<Friction> {
  template <class R>
  struct Law {
    R mu, normal, tolerance;
    Edge surface;
    bool never_reverse;
  };
  template <class R>
  static Law<R> law(const Friction& f) {
    return {R(f.mu), R(f.normal), R(f.tolerance), f.surface, f.never_reverse};
  }
  // On body lane b where it touches the surface; the fast form a = -k v with
  // k = mu N / (m |v|) (0 at rest), k dt <= 1 when never reversing.
  template <class P, bool kNeverReverse, class B>
  CALDER_LANE_INLINE static void apply(B& b, const Law<typename P::R>& p,
                                       const lanes::Frame<typename P::R>& frame) {
    using L = typename P::L;
    using R = typename P::R;
    const L vx = b.vx;
    const L vy = b.vy;
    const auto touching =
        laws::touches<P>(p.surface, b.x, b.y, b.r(), p.tolerance, frame.width, frame.height);
    const L own = b.mu();
    const L mu = own != own ? P::splat(p.mu) : own;  // NaN: no coefficient of its own
    const L speed = P::length(vx * vx + vy * vy);
    if constexpr (P::book) {
      lanes::Pair<L> f = laws::friction<P>(vx, vy, speed, mu, p.normal);
      if constexpr (kNeverReverse) lanes::never_reverse<P>(f, b.m(), speed, frame.dt);
      lanes::add_force<P>(b, touching, f.x, f.y);
    } else {
      const L moving = speed != R(0) ? speed : P::splat(R(1));
      L k = speed != R(0) ? mu * p.normal * b.inv_m() / moving : P::splat(R(0));
      if constexpr (kNeverReverse) k = k < R(1) / frame.dt ? k : P::splat(R(1) / frame.dt);
      b.ax = touching ? b.ax - k * vx : b.ax;
      b.ay = touching ? b.ay - k * vy : b.ay;
    }
  }
  template <class P, class Each>
  static void run(Each&& each, const Law<typename P::R>& p,
                  const lanes::Frame<typename P::R>& frame) {
    if (p.never_reverse) {
      return each([=](auto& b) CALDER_LANE_INLINE { apply<P, true>(b, p, frame); });
    }
    each([=](auto& b) CALDER_LANE_INLINE { apply<P, false>(b, p, frame); });
  }
};

}  // namespace calder
