// SPDX-License-Identifier: MIT
// The field kind Fan: blows away from a point, falling off linearly to zero
// at its reach (exercise 2.5).
#pragma once

#include "calder/field_kinds/kind.hpp"

namespace calder {

struct Fan {
  Vec2 position{};
  double strength = 1.0;
  double reach = 200.0;
  bool enabled = true;
};

template <>
struct FieldKind<Fan> {
  static constexpr const char* name = "fan";
  static constexpr const char* summary =
      "Blows away from a point: strength * (1 - d / reach) within reach, zero beyond.";
  static constexpr auto parameters = std::tuple{
      Parameter<Fan, Vec2>{"position", &Fan::position},
      Parameter<Fan, double>{"strength", &Fan::strength},
      Parameter<Fan, double>{"reach", &Fan::reach, Range::positive},
  };
  static constexpr auto position = &Fan::position;
};

}  // namespace calder
