// SPDX-License-Identifier: MIT
// The law of EdgeForce (calder/field_kinds/edge_force.hpp).
#pragma once

#include "calder/field_kinds/edge_force.hpp"
#include "law.hpp"

namespace calder {

template <>
struct FieldLaw<EdgeForce> {
  template <class R>
  struct Law {
    R strength, margin;
  };
  template <class R>
  static Law<R> law(const EdgeForce& f) {
    return {R(f.strength), R(f.margin)};
  }
  // The force at (x, y) on a width x height canvas: for each edge at distance
  // d within the margin, strength * (margin - d) / margin inward; the four add up.
  template <class P>
  CALDER_LANE_INLINE static lanes::Pair<typename P::L> force(const Law<typename P::R>& p,
                                                             typename P::L x, typename P::L y,
                                                             typename P::R width,
                                                             typename P::R height) {
    using L = typename P::L;
    const auto push = [&](L d) CALDER_LANE_INLINE {
      const L inward = p.strength * (p.margin - d) / p.margin;
      return d < p.margin ? inward : P::splat(typename P::R(0));
    };
    return {push(x) - push(width - x), push(y) - push(height - y)};
  }
  template <class P, class Each>
  static void run(Each&& each, const Law<typename P::R>& p,
                  const lanes::Frame<typename P::R>& frame) {
    each([=](auto& b) CALDER_LANE_INLINE {
      const auto f = force<P>(p, b.x, b.y, frame.width, frame.height);
      lanes::add_force<P>(b, P::all(), f.x, f.y);
    });
  }
};

}  // namespace calder
