// SPDX-License-Identifier: MIT
// calder command: the kinds of failure and their exit codes.
//
//   0  success
//   1  the run itself failed (calder::RunError: a step left a non-finite
//      state; a write failed; 128 + N: interrupted by signal N)
//   2  bad usage or bad input (calder::InputError, calder::InvalidArgument and
//      any other calder::Error: flags, scene names, scene files, --state
//      files, output paths that can't be created)
//
// Code below the top level throws by kind and adds context with
// calder::rethrow_with_context; only run_cli maps kinds to exit codes. Every
// failure is reported as one line on stderr: "<program>: <message>".
#pragma once

#include <cstdint>
#include <functional>
#include <ostream>
#include <string>
#include <string_view>

#include "calder/error.hpp"

namespace calder::app {

constexpr int exit_success = 0;
constexpr int exit_failure = 1;
constexpr int exit_usage = 2;

// Bad usage or bad input: exit 2.
using calder::InputError;
// The run failed after it started: exit 1.
using calder::RunError;

// The message on one line: line breaks become spaces, control characters shown.
std::string one_line(std::string message);

// Throws `error`, which a step or a drawing of frame `frame` of `source`
// threw, as RunError "<source>: frame <frame>: <message>": once a run started,
// what a step throws is the run failing (its input was checked before).
[[noreturn]] void throw_run_failure(const Error& error, const std::string& source,
                                    std::int64_t frame);

// Reports `message` as one line "<program>: <message>" on `err` (one prefix,
// however the message was put together) and returns `code`.
int report(std::ostream& err, std::string_view program, std::string message, int code);

// The top level of a command: runs `command` (which parses and runs), then
// flushes `out`; maps what it throws to the exit status (above) and reports it
// on `err`. Returns 0 when it succeeded. Never throws.
int run_cli(std::string_view program, std::ostream& out, std::ostream& err,
            const std::function<void()>& command);

}  // namespace calder::app
