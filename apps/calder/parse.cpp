// SPDX-License-Identifier: MIT
#include "parse.hpp"

#include <charconv>
#include <cmath>
#include <limits>
#include <string_view>
#include <system_error>

#include "errors.hpp"

namespace calder::app {

namespace {

[[noreturn]] void bad(const std::string& flag, const std::string& expected,
                      const std::string& text) {
  throw InputError(flag + ": expected " + expected + ", got '" + text + "'");
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

}  // namespace

std::optional<std::int64_t> to_int64(std::string_view text) {
  std::string_view digits = text;
  if (!digits.empty() && digits.front() == '+') {
    digits.remove_prefix(1);
    if (!digits.empty() && digits.front() == '-') return std::nullopt;
  }
  if (digits.empty()) return std::nullopt;
  std::int64_t value = 0;
  const char* end = digits.data() + digits.size();
  const auto [ptr, ec] = std::from_chars(digits.data(), end, value);
  if (ec != std::errc() || ptr != end) return std::nullopt;
  return value;
}

std::optional<double> to_double(std::string_view text) {
  std::string_view digits = text;
  if (!digits.empty() && digits.front() == '+') {
    digits.remove_prefix(1);
    if (!digits.empty() && digits.front() == '-') return std::nullopt;
  }
  if (digits.empty()) return std::nullopt;
  double value = 0.0;
  const char* end = digits.data() + digits.size();
  const auto [ptr, ec] = std::from_chars(digits.data(), end, value);
  // Out of range (1e400, 1e-400) is not a number a run can use.
  if (ec != std::errc() || ptr != end) return std::nullopt;
  return value;
}

std::int64_t parse_frames(const std::string& flag, const std::string& text) {
  const std::string expected = "an integer from 0 to " + std::to_string(max_frames);
  const auto value = to_int64(text);
  if (!value || *value < 0 || *value > max_frames) bad(flag, expected, text);
  return *value;
}

double parse_dt(const std::string& flag, const std::string& text) {
  const auto value = to_double(text);
  if (!value || !std::isfinite(*value) || *value <= 0.0) bad(flag, "a finite number > 0", text);
  return *value;
}

Integrator parse_integrator(const std::string& flag, const std::string& text) {
  for (const IntegratorName& i : kIntegratorNames) {
    if (text == i.name) return i.value;
  }
  bad(flag, "semi_implicit_euler, velocity_verlet, rk4, ias15, yoshida4 or yoshida6", text);
}

std::uint32_t parse_seed(const std::string& flag, const std::string& text) {
  const auto value = to_int64(text);
  if (!value || *value < 0 || *value > std::numeric_limits<std::uint32_t>::max()) {
    bad(flag, "an integer from 0 to 4294967295", text);
  }
  return static_cast<std::uint32_t>(*value);
}

std::vector<FrameRange> parse_frame_range(const std::string& flag, const std::string& text) {
  const std::string expected =
      "FIRST-LAST (draw numbers, 1 <= FIRST <= LAST, e.g. 100-160) or none";
  if (trim(text) == "none") return {};
  const std::string_view s = text;
  // The dash between the two numbers; a leading '-' belongs to a (bad) negative FIRST.
  const std::size_t dash = s.find('-', 1);
  if (dash == std::string_view::npos) bad(flag, expected, text);
  const auto first = to_int64(trim(s.substr(0, dash)));
  const auto last = to_int64(trim(s.substr(dash + 1)));
  if (!first || !last || *first < 1 || *last < *first || *last > max_frames) {
    bad(flag, expected, text);
  }
  return {FrameRange{*first, *last}};
}

Vec2 parse_point(const std::string& flag, const std::string& text) {
  const std::string expected = "X,Y (two finite numbers, e.g. 320,120)";
  const std::string_view s = text;
  const std::size_t comma = s.find(',');
  if (comma == std::string_view::npos) bad(flag, expected, text);
  const auto x = to_double(trim(s.substr(0, comma)));
  const auto y = to_double(trim(s.substr(comma + 1)));
  if (!x || !y || !std::isfinite(*x) || !std::isfinite(*y)) bad(flag, expected, text);
  return {*x, *y};
}

}  // namespace calder::app
