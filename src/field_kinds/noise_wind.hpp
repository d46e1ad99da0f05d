// SPDX-License-Identifier: MIT
// The law of NoiseWind (calder/field_kinds/noise_wind.hpp).
#pragma once

#include <cstddef>

#include "calder/field_kinds/noise_wind.hpp"
#include "calder/random.hpp"
#include "law.hpp"

namespace calder {

template <>
struct FieldLaw<NoiseWind> {
  // The force at a time: map(noise(offset + time * rate), 0, 1, -strength,
  // strength) along x.
  template <class P>
  static Vec2 force(const Noise& noise, double time, double strength, double rate, double offset) {
    const double n = noise.noise(offset + time * rate);
    return {map_range(n, 0.0, 1.0, -strength, strength), 0.0};
  }

  // The same force on every body, changing with time: the plain loops give
  // the force of their step, a kernel's batch the force of each of its steps
  // (per_step: x, y pairs).
  template <class R>
  struct Law {
    R fx{}, fy{};
    const double* per_step = nullptr;
  };
  template <class R>
  static Law<R> law(const NoiseWind&) {
    return {};
  }
  template <class P, class Each>
  static void run(Each&& each, const Law<typename P::R>& p,
                  const lanes::Frame<typename P::R>& frame) {
    using R = typename P::R;
    if (p.per_step == nullptr) {
      return each([=](auto& b) CALDER_LANE_INLINE { lanes::add_uniform<P>(b, p.fx, p.fy); });
    }
    const auto s = static_cast<std::size_t>(frame.step);
    const R fx = R(p.per_step[2 * s]);
    const R fy = R(p.per_step[2 * s + 1]);
    each([=](auto& b) CALDER_LANE_INLINE { lanes::add_uniform<P>(b, fx, fy); });
  }
};

}  // namespace calder
