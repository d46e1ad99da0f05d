// SPDX-License-Identifier: MIT
// The field kind EdgeForce: pushes bodies back from the canvas edges
// (exercise 2.3).
#pragma once

#include "calder/field_kinds/kind.hpp"

namespace calder {

struct EdgeForce {
  double strength = 1.0;
  double margin = 50.0;
  bool enabled = true;
};

template <>
struct FieldKind<EdgeForce> {
  static constexpr const char* name = "edge_force";
  static constexpr const char* summary =
      "Pushes bodies back from the canvas edges: strength * (margin - d) / margin within margin.";
  static constexpr auto parameters = std::tuple{
      Parameter<EdgeForce, double>{"strength", &EdgeForce::strength},
      Parameter<EdgeForce, double>{"margin", &EdgeForce::margin, Range::positive},
  };
};

}  // namespace calder
