// SPDX-License-Identifier: MIT
// The field kind NoiseWind: a horizontal wind from Perlin noise over
// simulation time (exercise 2.1).
#pragma once

#include "calder/field_kinds/kind.hpp"
#include "calder/random.hpp"

namespace calder {

struct NoiseWind {
  double strength = 0.1;
  double rate = 0.01;
  double offset = 0.0;
  bool enabled = true;
  // false: the wind at time t is noise(offset + t * rate). true: offset is
  // where the noise is read now, and the world adds rate to it after every
  // step, as a sketch's `noiseX += 0.01` (the sum drifts from offset + t * rate
  // in the last bits; exercise 2.1).
  bool accumulate = false;
};

template <>
struct FieldKind<NoiseWind> {
  static constexpr const char* name = "noise_wind";
  static constexpr const char* summary =
      "A horizontal wind from Perlin noise over time: map(noise(offset + t * rate), 0, 1, "
      "-strength, strength).";
  static constexpr auto parameters = std::tuple{
      Parameter<NoiseWind, double>{"strength", &NoiseWind::strength},
      Parameter<NoiseWind, double>{"rate", &NoiseWind::rate},
      Parameter<NoiseWind, double>{"offset", &NoiseWind::offset},
      Parameter<NoiseWind, bool>{"accumulate", &NoiseWind::accumulate, Range::finite,
                                 differs<&NoiseWind::accumulate>},
  };

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
