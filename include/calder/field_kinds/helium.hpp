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
};

}  // namespace calder
