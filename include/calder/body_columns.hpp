// SPDX-License-Identifier: MIT
// calder: the per-body quantities, written once.
//
// A world keeps one column (array) per quantity, body i at index i of each.
// Every place that holds or moves whole bodies - World's storage, add,
// clear, save and restore, the read-only BodyView, World::add_bodies' input,
// the batch handed to calder::bulk, its tiles and their load and store -
// is this one template with another column type, and walks the columns with
// for_each_column. A new quantity is a member here and a line in
// for_each_property, BodyDef's field and its row (src/world.cpp); see
// docs/DESIGN.md.
#pragma once

#include <cstddef>

namespace calder {

// State: what a step changes (position, velocity, the accumulated
// acceleration); Property: what it only reads. (The accelerations come last
// so that an input of the first eight columns can leave them out.)
template <class State, class Property = State>
struct BodyColumnsOf {
  State x{}, y{}, vx{}, vy{};
  Property mass{};       // > 0
  Property radius{};     // >= 0; 0: a point
  Property friction{};   // own friction coefficient; NaN: the Friction field's mu
  Property drag_area{};  // frontal area scaling drag (exercise 2.9)
  State ax{}, ay{};      // accumulated since the last update
};

// f(name, column of each argument...) for each state column, in the order
// of save_state's layout (x, y, vx, vy, ax, ay).
template <class F, class... Columns>
constexpr void for_each_state(F&& f, Columns&&... columns) {
  f("x", columns.x...);
  f("y", columns.y...);
  f("vx", columns.vx...);
  f("vy", columns.vy...);
  f("ax", columns.ax...);
  f("ay", columns.ay...);
}

// The same for each property column.
template <class F, class... Columns>
constexpr void for_each_property(F&& f, Columns&&... columns) {
  f("mass", columns.mass...);
  f("radius", columns.radius...);
  f("friction", columns.friction...);
  f("drag_area", columns.drag_area...);
}

// Every column: the state ones, then the properties.
template <class F, class... Columns>
constexpr void for_each_column(F&& f, Columns&&... columns) {
  for_each_state(f, columns...);
  for_each_property(f, columns...);
}

namespace detail {
template <class Visit>
constexpr std::size_t count_columns(Visit visit) {
  std::size_t n = 0;
  BodyColumnsOf<char> columns{};
  visit([&n](const char*, char) { ++n; }, columns);
  return n;
}
}  // namespace detail

inline constexpr std::size_t kStateColumns =
    detail::count_columns([](auto f, auto& c) { for_each_state(f, c); });
// A member above that the lists miss is caught here.
static_assert(sizeof(BodyColumnsOf<char>) ==
                  detail::count_columns([](auto f, auto& c) { for_each_column(f, c); }),
              "every member of BodyColumnsOf must be in for_each_state or for_each_property");

}  // namespace calder
