// SPDX-License-Identifier: MIT
// calder: the names of an enumeration's values, as scene files, the command
// line, Python and the web page spell them (kIntegratorNames, ...).
#pragma once

#include <string_view>

namespace calder {

template <class E>
struct EnumName {
  std::string_view name;
  E value;
};

// The value's name in `table` ("?" when the table lacks it).
template <class E, class Table>
[[nodiscard]] constexpr std::string_view name_in(const Table& table, E value) {
  for (const EnumName<E>& entry : table) {
    if (entry.value == value) return entry.name;
  }
  return "?";
}

}  // namespace calder
