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
};

}  // namespace calder
