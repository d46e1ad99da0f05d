// SPDX-License-Identifier: MIT
// calder command: what long jobs share: a progress bar on a terminal, and
// Ctrl-C that stops a job cleanly (its destructors run, so temporary files
// and half-made output are removed).
//
//   Progress progress(err, "render example-2.7", 600, !quiet && stderr_is_terminal());
//   InterruptGuard interrupt;  // SIGINT, SIGTERM, SIGHUP, ... now set a flag
//   for (...) { interrupt.check(); ...; progress.update(done); }
//   progress.finish();
#pragma once

#include <chrono>
#include <cstdint>
#include <ostream>
#include <string>

#include "../../src/output/output.hpp"
#include "errors.hpp"

namespace calder::app {

// Whether standard error is a terminal (isatty).
bool stderr_is_terminal();

// One line on `err`, redrawn in place with '\r': the label, a bar, the
// percentage, done/total and the time left. Shown only when enabled, and only
// once the job has taken a moment (short jobs print nothing); at most ten
// redraws a second. finish() (or the destructor) erases the line.
class Progress {
 public:
  Progress(std::ostream& err, std::string label, std::int64_t total, bool enabled);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void update(std::int64_t done);
  void finish();

  // The line for `done` of `total` after `elapsed_seconds` (for tests).
  static std::string line(const std::string& label, std::int64_t done, std::int64_t total,
                          double elapsed_seconds);

 private:
  using Clock = std::chrono::steady_clock;
  std::ostream& err_;
  std::string label_;
  std::int64_t total_;
  bool enabled_;
  bool shown_ = false;
  std::size_t width_ = 0;  // characters of the last line drawn
  Clock::time_point start_;
  Clock::time_point last_draw_;
};

// The job was stopped by one of output::terminating_signals: exit 128 +
// signal, after the one-line message "interrupted" (none for SIGPIPE: the
// reader of a pipe went away, `calder run ... | head`).
class Interrupted : public RunError {
 public:
  explicit Interrupted(int signal_number)
      : RunError("interrupted"), signal_number_(signal_number) {}
  [[nodiscard]] int signal_number() const { return signal_number_; }
  [[nodiscard]] int exit_code() const { return 128 + signal_number_; }

 private:
  int signal_number_;
};

// While alive, the terminating signals only set a flag (calder's one handler,
// output::InterruptScope in src/output/output.hpp: its watchdog removes the
// registered temporaries and ends a job that doesn't stop in time); check()
// throws Interrupted once one arrived. The loops of a job call it once a frame.
class InterruptGuard {
 public:
  void check() const {
    if (const int signal_number = output::InterruptScope::signal(); signal_number != 0) {
      throw Interrupted(signal_number);
    }
  }

 private:
  output::InterruptScope scope_;
};

}  // namespace calder::app
