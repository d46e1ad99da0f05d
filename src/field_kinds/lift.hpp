// SPDX-License-Identifier: MIT
// The law of Lift (calder/field_kinds/lift.hpp).
#pragma once

#include "calder/field_kinds/lift.hpp"
#include "law.hpp"

namespace calder {

template <>
struct FieldLaw<Lift> {
  template <class R>
  struct Law {
    R coefficient;
  };
  template <class R>
  static Law<R> law(const Lift& f) {
    return {R(f.coefficient)};
  }
  // (vy, -vx), on the left of the motion with y down, set to coefficient * |v|^2.
  template <class P>
  CALDER_LANE_INLINE static lanes::Pair<typename P::L> force(typename P::L vx, typename P::L vy,
                                                             typename P::R coefficient) {
    using L = typename P::L;
    const L magnitude = coefficient * (vx * vx + vy * vy);
    return lanes::set_mag<P>(vy, -vx, P::sqrt(vy * vy + vx * vx), magnitude);
  }
  template <class P, class Each>
  static void run(Each&& each, const Law<typename P::R>& p, const lanes::Frame<typename P::R>&) {
    each([=](auto& b) CALDER_LANE_INLINE {
      const auto f = force<P>(b.vx, b.vy, p.coefficient);
      lanes::add_force<P>(b, P::all(), f.x, f.y);
    });
  }
};

}  // namespace calder
