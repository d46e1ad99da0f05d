// SPDX-License-Identifier: MIT
// The law of Helium (calder/field_kinds/helium.hpp): (0, -lift), whatever the body.
#pragma once

#include "calder/field_kinds/helium.hpp"
#include "law.hpp"

namespace calder {

template <>
struct FieldLaw<Helium> {
  template <class R>
  struct Law {
    R fx, fy;
  };
  template <class R>
  static Law<R> law(const Helium& f) {
    return {R(0.0), R(-f.lift)};
  }
  template <class P, class Each>
  static void run(Each&& each, const Law<typename P::R>& p, const lanes::Frame<typename P::R>&) {
    each([=](auto& b) CALDER_LANE_INLINE { lanes::add_uniform<P>(b, p.fx, p.fy); });
  }
};

}  // namespace calder
