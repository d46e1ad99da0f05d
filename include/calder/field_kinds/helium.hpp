// SPDX-License-Identifier: MIT
// The field kind Helium: a constant upward force, (0, -lift).
#pragma once

#include "calder/field_kinds/kind.hpp"

namespace calder {

struct Helium {
  double lift = 0.1;
  bool enabled = true;
};

template <>
struct FieldKind<Helium> {
  static constexpr const char* name = "helium";
  static constexpr const char* summary = "A constant upward force, (0, -lift).";
  static constexpr auto parameters = std::tuple{Parameter<Helium, double>{"lift", &Helium::lift}};

  // The law: (0, -lift), whatever the body.
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
