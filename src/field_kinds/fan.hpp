// SPDX-License-Identifier: MIT
// The law of Fan (calder/field_kinds/fan.hpp).
#pragma once

#include "calder/field_kinds/fan.hpp"
#include "law.hpp"

namespace calder {

template <>
struct FieldLaw<Fan> {
  template <class R>
  struct Law {
    R px, py, strength, reach;
  };
  template <class R>
  static Law<R> law(const Fan& f) {
    return {R(f.position.x), R(f.position.y), R(f.strength), R(f.reach)};
  }
  // The force on a body at (x, y), where `apply` (zero at the fan itself, no
  // direction there, and from reach on): away from the fan, magnitude
  // strength * (1 - d / reach).
  template <class P>
  CALDER_LANE_INLINE static auto force(const Law<typename P::R>& p, typename P::L x,
                                       typename P::L y) {
    using L = typename P::L;
    using R = typename P::R;
    const L awx = x - p.px;
    const L awy = y - p.py;
    const L d = P::sqrt(awx * awx + awy * awy);
    const auto apply = (d != R(0)) & (d < p.reach);
    return lanes::Masked<L, decltype(apply)>{
        lanes::set_mag<P>(awx, awy, d, p.strength * (R(1) - d / p.reach)), apply};
  }
  template <class P, class Each>
  static void run(Each&& each, const Law<typename P::R>& p, const lanes::Frame<typename P::R>&) {
    each([=](auto& b) CALDER_LANE_INLINE {
      const auto fan = force<P>(p, b.x, b.y);
      lanes::add_force<P>(b, fan.apply, fan.f.x, fan.f.y);
    });
  }
};

}  // namespace calder
