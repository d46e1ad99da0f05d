// SPDX-License-Identifier: MIT
// The law of Wind (calder/field_kinds/wind.hpp).
#pragma once

#include "calder/field_kinds/wind.hpp"
#include "law.hpp"

namespace calder {

template <>
struct FieldLaw<Wind> {
  template <class R>
  struct Law {
    R fx, fy;
  };
  template <class R>
  static Law<R> law(const Wind& f) {
    return {R(f.force.x), R(f.force.y)};
  }
  template <class P, class Each>
  static void run(Each&& each, const Law<typename P::R>& p, const lanes::Frame<typename P::R>&) {
    each([=](auto& b) CALDER_LANE_INLINE { lanes::add_uniform<P>(b, p.fx, p.fy); });
  }
};

}  // namespace calder
