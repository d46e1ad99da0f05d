// SPDX-License-Identifier: MIT
// calder: errors, by kind.
//
// Every error calder throws is a calder::Error (catch it to catch them all),
// with a one-line message. Its kind says whose fault it is, so that a program
// (the calder command) maps kinds to exit codes in one place:
//   InvalidArgument  a function refused an argument (mass <= 0, dt <= 0, NaN or
//                    infinite input, ...): the message names the function, the
//                    argument and the offending value;
//   InputError       bad input read from outside (a scene file, a --state file,
//                    a flag): the message names the file, line or field;
//   RunError         a run that failed after it started (a step left a
//                    non-finite state, a write failed).
// A plain Error is bad input or a bad argument too. Nothing is ever turned
// into NaN silently.
#pragma once

#include <cmath>
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

// A function refused one of its arguments.
class InvalidArgument : public Error {
 public:
  using Error::Error;
};

// Bad input from outside: a file, a line, a field or a flag.
class InputError : public Error {
 public:
  using Error::Error;
};

// A run that failed after it started (a non-finite state, a failed write).
class RunError : public Error {
 public:
  using Error::Error;
};

// Throws an error of the same kind as `error` (InvalidArgument, InputError,
// RunError or Error) whose message is `context` followed by error's: for a
// catch site that only adds where it happened, and leaves the kind alone.
[[noreturn]] void rethrow_with_context(const Error& error, std::string_view context);

namespace detail {

// Throws InvalidArgument("<where>: <what> must be <condition> (got <value>)").
[[noreturn]] void fail_requirement(const char* where, const char* what, const char* condition,
                                   double value);

// The checks below are inline, their failure out of line: a loop over many
// bodies (World::add_bodies) pays a compare and a branch per value, not a call.

// Throws InvalidArgument("<where>: <what> must be finite (got <value>)") unless value is finite.
inline void require_finite(double value, const char* where, const char* what) {
  if (!std::isfinite(value)) [[unlikely]]
    fail_requirement(where, what, "finite", value);
}
// Throws unless value is finite and > 0.
inline void require_positive(double value, const char* where, const char* what) {
  require_finite(value, where, what);
  if (!(value > 0.0)) [[unlikely]]
    fail_requirement(where, what, "> 0", value);
}
// Throws unless value is finite and >= 0.
inline void require_non_negative(double value, const char* where, const char* what) {
  require_finite(value, where, what);
  if (!(value >= 0.0)) [[unlikely]]
    fail_requirement(where, what, ">= 0", value);
}
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
