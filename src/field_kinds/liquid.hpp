// SPDX-License-Identifier: MIT
// The law of Liquid (calder/field_kinds/liquid.hpp): Drag's (drag.hpp)
// inside the region.
#pragma once

#include "calder/field_kinds/liquid.hpp"
#include "drag.hpp"
#include "law.hpp"

namespace calder {

template <>
struct FieldLaw<Liquid> {
  // The region as Rect::contains reads it: x < p.x < x + w, y < p.y < y + h
  // (the sums in double).
  template <class R>
  struct Law {
    R c;
    bool never_reverse;
    R x_min, x_max, y_min, y_max;
  };
  template <class R>
  static Law<R> law(const Liquid& f) {
    return {R(f.c),        f.never_reverse,           R(f.region.x), R(f.region.x + f.region.w),
            R(f.region.y), R(f.region.y + f.region.h)};
  }
  template <class P, class Each>
  static void run(Each&& each, const Law<typename P::R>& p,
                  const lanes::Frame<typename P::R>& frame) {
    const auto dt = frame.dt;
    const auto inside = [=](const auto& b) CALDER_LANE_INLINE {
      return (b.x > p.x_min) & (b.x < p.x_max) & (b.y > p.y_min) & (b.y < p.y_max);
    };
    if (p.never_reverse) {
      return each([=](auto& b)
                      CALDER_LANE_INLINE { laws::add_drag<P, true>(b, inside(b), p.c, dt); });
    }
    each([=](auto& b) CALDER_LANE_INLINE { laws::add_drag<P, false>(b, inside(b), p.c, dt); });
  }
};

}  // namespace calder
