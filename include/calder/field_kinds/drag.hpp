// SPDX-License-Identifier: MIT
// The field kind Drag: quadratic drag everywhere (air). Liquid is the same
// law inside a region.
#pragma once

#include "calder/field_kinds/kind.hpp"

namespace calder {

struct Drag {
  double c = 0.01;
  bool never_reverse = false;
  bool enabled = true;
};

template <>
struct FieldKind<Drag> {
  static constexpr const char* name = "drag";
  static constexpr const char* summary =
      "Quadratic drag everywhere: (c * |v|) * |v| * drag_area against the velocity.";
  static constexpr auto parameters = std::tuple{
      Parameter<Drag, double>{"c", &Drag::c, Range::non_negative},
      Parameter<Drag, bool>{"never_reverse", &Drag::never_reverse},
  };
};

}  // namespace calder
