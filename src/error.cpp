// SPDX-License-Identifier: MIT
// calder: errors (see calder/error.hpp).
#include "calder/error.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#if __has_include(<version>)
#include <version>
#endif
#if defined(__cpp_lib_to_chars) && __cpp_lib_to_chars >= 201611L
#include <charconv>
#include <system_error>
#define CALDER_HAVE_FLOAT_TO_CHARS 1
#endif

namespace calder {

void rethrow_with_context(const Error& error, std::string_view context) {
  std::string message(context);
  message += error.what();
  if (dynamic_cast<const RunError*>(&error) != nullptr) throw RunError(message);
  if (dynamic_cast<const InputError*>(&error) != nullptr) throw InputError(message);
  if (dynamic_cast<const InvalidArgument*>(&error) != nullptr) throw InvalidArgument(message);
  throw Error(message);
}

}  // namespace calder

namespace calder::detail {

[[noreturn]] void fail_requirement(const char* where, const char* what, const char* condition,
                                   double value) {
  std::string message;
  message += where;
  message += ": ";
  message += what;
  message += " must be ";
  message += condition;
  message += " (got ";
  message += format_number(value);
  message += ")";
  throw InvalidArgument(message);
}

std::string format_number(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0.0 ? "inf" : "-inf";
#ifdef CALDER_HAVE_FLOAT_TO_CHARS
  // Shortest form that reads back to the same double.
  std::array<char, 64> buffer{};
  const std::to_chars_result result =
      std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  if (result.ec == std::errc{}) return {buffer.data(), result.ptr};
#endif
  // Fallback for standard libraries without floating-point std::to_chars
  // (libc++ before 14, e.g. Emscripten's libc++ 13): integers of moderate size
  // in fixed notation, otherwise the shortest %g precision that round-trips.
  std::array<char, 64> text{};
  if (value == std::trunc(value) && std::fabs(value) < 1e15) {
    std::snprintf(text.data(), text.size(), "%.0f", value);
    return text.data();
  }
  for (int precision = 1; precision <= 17; ++precision) {
    std::snprintf(text.data(), text.size(), "%.*g", precision, value);
    if (std::strtod(text.data(), nullptr) == value) break;
  }
  return text.data();
}

std::string printable(std::string_view text, std::size_t max_bytes) {
  std::string out;
  std::size_t i = 0;
  for (; i < text.size() && i < max_bytes; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c == '\n') {
      out += "\\n";
    } else if (c == '\t') {
      out += "\\t";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c < 0x20 || c == 0x7F) {
      static const char* digits = "0123456789abcdef";
      out += "\\x";
      out += digits[c >> 4];
      out += digits[c & 0xF];
    } else {
      out += static_cast<char>(c);
    }
  }
  if (i < text.size()) {
    // Don't cut a UTF-8 sequence: drop its lead and continuation bytes.
    while (!out.empty() && (static_cast<unsigned char>(out.back()) & 0xC0) == 0x80) out.pop_back();
    if (!out.empty() && static_cast<unsigned char>(out.back()) >= 0xC0) out.pop_back();
    out += "...";
  }
  return out;
}

namespace {

// Optimal string alignment distance (Levenshtein plus adjacent
// transpositions), keeping three rows of the table: one allocation a call.
std::size_t edit_distance(std::string_view a, std::string_view b) {
  const std::size_t width = b.size() + 1;
  std::vector<std::size_t> rows(3 * width);
  std::size_t* two_back = rows.data();  // row i - 2
  std::size_t* previous = two_back + width;
  std::size_t* current = previous + width;
  for (std::size_t j = 0; j < width; ++j) previous[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    current[0] = i;
    for (std::size_t j = 1; j < width; ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      current[j] = std::min({previous[j] + 1, current[j - 1] + 1, previous[j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) {
        current[j] = std::min(current[j], two_back[j - 2] + 1);
      }
    }
    std::swap(two_back, previous);  // the old i - 2 row becomes the next current
    std::swap(previous, current);
  }
  return previous[b.size()];
}

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

}  // namespace

std::optional<std::string_view> closest(std::string_view word,
                                        const std::vector<std::string_view>& candidates) {
  // A word much longer than every candidate is no typo of one; this also
  // bounds the distance tables' cost whatever the input.
  std::size_t longest = 0;
  for (const std::string_view c : candidates) longest = std::max(longest, c.size());
  if (word.size() > longest + 2) return std::nullopt;
  const std::string word_lower = lower(word);
  const std::size_t limit = word.size() <= 3 ? 1 : 2;
  std::optional<std::string_view> best;
  std::size_t best_distance = std::numeric_limits<std::size_t>::max();
  for (const std::string_view c : candidates) {
    // The distance is at least the difference in length: such a candidate can't be the answer.
    if (std::max(c.size(), word.size()) - std::min(c.size(), word.size()) > limit) continue;
    const std::string c_lower = lower(c);
    const std::size_t d = c_lower == word_lower ? 0 : edit_distance(word_lower, c_lower);
    if (d < best_distance) {
      best_distance = d;
      best = c;
    }
  }
  if (best && best_distance <= limit && best_distance < word.size()) return best;
  return std::nullopt;
}

}  // namespace calder::detail
