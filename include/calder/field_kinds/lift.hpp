// SPDX-License-Identifier: MIT
// The field kind Lift: perpendicular to the velocity (exercise 2.10).
#pragma once

#include "calder/field_kinds/kind.hpp"

namespace calder {

struct Lift {
  double coefficient = 0.01;
  bool enabled = true;
};

template <>
struct FieldKind<Lift> {
  static constexpr const char* name = "lift";
  static constexpr const char* summary =
      "Perpendicular to the velocity, coefficient * |v|^2, on the left of the motion (y down).";
  static constexpr auto parameters =
      std::tuple{Parameter<Lift, double>{"coefficient", &Lift::coefficient}};

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
