// SPDX-License-Identifier: MIT
// The field kind NoiseWind: a horizontal wind from Perlin noise over
// simulation time (exercise 2.1).
#pragma once

#include "calder/field_kinds/kind.hpp"

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
};

}  // namespace calder
