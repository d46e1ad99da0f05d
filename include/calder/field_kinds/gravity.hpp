// SPDX-License-Identifier: MIT
// The field kind Gravity: a uniform pull, g, or g * mass (example 2.3).
#pragma once

#include "calder/field_kinds/kind.hpp"

namespace calder {

struct Gravity {
  Vec2 g{0.0, 0.1};
  bool scale_by_mass = false;  // true: force g * mass, same fall for every mass (example 2.3)
  bool enabled = true;
};

template <>
struct FieldKind<Gravity> {
  static constexpr const char* name = "gravity";
  static constexpr const char* summary = "A uniform pull g, or g * mass (scale_by_mass).";
  static constexpr auto parameters = std::tuple{
      Parameter<Gravity, Vec2>{"g", &Gravity::g},
      Parameter<Gravity, bool>{"scale_by_mass", &Gravity::scale_by_mass},
  };
};

}  // namespace calder
