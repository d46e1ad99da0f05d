// SPDX-License-Identifier: MIT
// CustomForce (calder/field_kinds/custom_force.hpp) has no law: accumulate
// (src/fields.cpp) calls its function for each body.
#pragma once

#include <string>

#include "calder/field_kinds/custom_force.hpp"
#include "law.hpp"

namespace calder {

template <>
struct FieldLaw<CustomForce> {
  static std::string no_kernel(const CustomForce&) { return "field custom_force has no kernel"; }
};

}  // namespace calder
