// SPDX-License-Identifier: MIT
// calder: errors.
//
// Every rejected argument (mass <= 0, dt <= 0, NaN or infinite input, ...)
// throws calder::Error with a one-line message naming the function, the
// argument and the offending value. Nothing is ever turned into NaN silently.
#pragma once

#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace calder {

class Error : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

namespace detail {

// Throws Error("<where>: <what> must be finite (got <value>)") unless value is finite.
void require_finite(double value, const char* where, const char* what);
// Throws unless value is finite and > 0.
void require_positive(double value, const char* where, const char* what);
// Throws unless value is finite and >= 0.
void require_non_negative(double value, const char* where, const char* what);
// Formats a double the way the messages show it (shortest round-trip form).
std::string format_number(double value);
// Text from input, fit for a one-line message: control characters (and DEL)
// shown as `\n`, `\t`, `\r` or `\xNN`, and cut after max_bytes bytes with "..."
// (never inside a UTF-8 sequence).
std::string printable(std::string_view text, std::size_t max_bytes = 60);
// The candidate closest to `word` when it is close enough to be a likely typo
// (differs only in case, or by one edit in a short word, two in a longer
// one); cost bounded by the candidates' lengths, whatever the word.
std::optional<std::string_view> closest(std::string_view word,
                                        const std::vector<std::string_view>& candidates);

}  // namespace detail
}  // namespace calder
