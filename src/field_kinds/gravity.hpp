// SPDX-License-Identifier: MIT
// The law of Gravity (calder/field_kinds/gravity.hpp).
#pragma once

#include "calder/field_kinds/gravity.hpp"
#include "law.hpp"

namespace calder {

template <>
struct FieldLaw<Gravity> {
  template <class R>
  struct Law {
    R gx, gy;
    bool scaled;
  };
  template <class R>
  static Law<R> law(const Gravity& f) {
    return {R(f.g.x), R(f.g.y), f.scale_by_mass};
  }
  // g * mass: the book's p5.Vector.mult(gravity, mass), then divided by the
  // mass again; the fast arithmetic adds g (its kernels fold it into a
  // constant). gx = 0: the quotient is +-0, and adding it leaves an
  // acceleration (never -0) as it is, so it is skipped.
  template <class P, class B>
  CALDER_LANE_INLINE static void scaled(B& b, typename P::R gx, typename P::R gy) {
    if constexpr (P::book) {
      if (gx != typename P::R(0)) b.ax += P::quotient(b, gx * b.m());
      b.ay += P::quotient(b, gy * b.m());
    } else {
      b.ax += gx;
      b.ay += gy;
    }
  }
  template <class P, class Each>
  static void run(Each&& each, const Law<typename P::R>& p, const lanes::Frame<typename P::R>&) {
    if (p.scaled) return each([=](auto& b) CALDER_LANE_INLINE { scaled<P>(b, p.gx, p.gy); });
    each([=](auto& b) CALDER_LANE_INLINE { lanes::add_uniform<P>(b, p.gx, p.gy); });
  }
};

}  // namespace calder
