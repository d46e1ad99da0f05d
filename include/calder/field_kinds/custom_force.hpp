// SPDX-License-Identifier: MIT
// The field kind CustomForce: any force of the user's, a function called once
// per body (C++ and Python only: no scene-file form, no kernel).
#pragma once

#include <cstddef>
#include <functional>
#include <string>

#include "calder/field_kinds/kind.hpp"

namespace calder {

// Any force of the user's: called once per body, returns the force on body i.
using CustomForceFunction =
    std::function<Vec2(const FieldContext& context, std::size_t body_index)>;
struct CustomForce {
  CustomForceFunction force;
  bool enabled = true;
};

template <>
struct FieldKind<CustomForce> {
  static constexpr const char* name = "custom_force";
  static constexpr const char* summary =
      "Any force: a function of the field context and the body's index, called for each body.";
  static constexpr auto parameters = std::tuple{};
  static constexpr bool in_scene_files = false;
  // The force function is not empty.
  static void check(const CustomForce& field, const std::string& where);
};

}  // namespace calder
