// SPDX-License-Identifier: MIT
// What calder's GoogleTest files share: readable Vec2 values in failure
// messages, and expect_error for calder::Error messages.
#pragma once

#include <gtest/gtest.h>

#include <initializer_list>
#include <ostream>
#include <string>
#include <string_view>

#include "calder/error.hpp"
#include "calder/vec2.hpp"

namespace calder {

// GoogleTest prints a Vec2 in a failure message as Vec2{x, y}.
inline void PrintTo(const Vec2& v, std::ostream* os) {
  *os << "Vec2{" << v.x << ", " << v.y << "}";
}

namespace test {

// Asserts that f throws calder::Error whose message contains every needle.
template <typename F>
void expect_error(F f, std::initializer_list<std::string_view> needles) {
  try {
    f();
    ADD_FAILURE() << "expected calder::Error";
  } catch (const Error& e) {
    const std::string message = e.what();
    for (const std::string_view needle : needles) {
      EXPECT_NE(message.find(needle), std::string::npos)
          << "message \"" << message << "\" lacks \"" << needle << "\"";
    }
  }
}

// Asserts that f throws calder::Error whose message contains `needle`.
template <typename F>
void expect_error(F f, std::string_view needle) {
  expect_error(f, {needle});
}

}  // namespace test
}  // namespace calder
