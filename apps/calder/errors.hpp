// SPDX-License-Identifier: MIT
// calder command: the two kinds of failure and their exit codes.
//
//   0  success
//   1  the run itself failed (a step threw: NaN, overflow; a write failed)
//   2  bad usage or bad input (flags, scene names, scene files, --state files,
//      output paths that can't be created)
//
// Every failure is reported as one line on stderr: "calder: <message>".
#pragma once

#include <stdexcept>
#include <string>

namespace calder::app {

constexpr int exit_success = 0;
constexpr int exit_failure = 1;
constexpr int exit_usage = 2;

// Bad usage or bad input: exit 2.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The run failed after it started: exit 1.
class RunError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The message on one line: line breaks become spaces.
std::string one_line(std::string message);

}  // namespace calder::app
