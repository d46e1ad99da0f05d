// SPDX-License-Identifier: MIT
// MutualAttraction (calder/field_kinds/mutual_attraction.hpp) has no
// per-body law: accumulate (src/fields.cpp) sums its pairs, or calder::nbody.
#pragma once

#include <string>

#include "calder/field_kinds/mutual_attraction.hpp"
#include "law.hpp"

namespace calder {

template <>
struct FieldLaw<MutualAttraction> {
  static std::string no_kernel(const MutualAttraction&) {
    return "field mutual_attraction has no per-body kernel (calder::nbody sums it)";
  }
};

}  // namespace calder
