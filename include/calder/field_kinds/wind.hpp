// SPDX-License-Identifier: MIT
// The field kind Wind: the same force on every body.
#pragma once

#include "calder/field_kinds/kind.hpp"

namespace calder {

struct Wind {
  Vec2 force{0.1, 0.0};
  bool enabled = true;
};

template <>
struct FieldKind<Wind> {
  static constexpr const char* name = "wind";
  static constexpr const char* summary = "The same force on every body.";
  static constexpr auto parameters = std::tuple{Parameter<Wind, Vec2>{"force", &Wind::force}};
};

}  // namespace calder
