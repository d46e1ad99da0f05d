// SPDX-License-Identifier: MIT
// The field kind Liquid: quadratic drag, Drag's law, on bodies strictly
// inside a region (example 2.5).
#pragma once

#include "calder/field_kinds/kind.hpp"

namespace calder {

struct Liquid {
  Rect region{0.0, 120.0, 640.0, 120.0};
  double c = 0.1;
  bool never_reverse = false;  // limit the drag so it never reverses a velocity in one step
  bool enabled = true;

  [[nodiscard]] bool contains(Vec2 position) const { return region.contains(position); }
  // The drag on a body with this velocity and frontal area (book: calculateDrag).
  [[nodiscard]] Vec2 calculate_drag(Vec2 velocity, double area = 1.0) const;
};

template <>
struct FieldKind<Liquid> {
  static constexpr const char* name = "liquid";
  static constexpr const char* summary =
      "Quadratic drag, as drag, on bodies strictly inside a region.";
  static constexpr auto parameters = std::tuple{
      Parameter<Liquid, Rect>{"region", &Liquid::region},  // w and h >= 0
      Parameter<Liquid, double>{"c", &Liquid::c, Range::non_negative},
      Parameter<Liquid, bool>{"never_reverse", &Liquid::never_reverse},
  };
};

}  // namespace calder
