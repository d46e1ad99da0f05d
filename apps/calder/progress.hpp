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

#include <signal.h>

#include <array>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <memory>
#include <mutex>
#include <ostream>
#include <string>

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

// The signals that end a job and that can be caught: each removes what the
// run created (temporaries, staged frames) and exits 128 + the signal.
constexpr std::array<int, 9> terminating_signals = {SIGINT,  SIGTERM, SIGHUP,  SIGQUIT, SIGPIPE,
                                                    SIGXFSZ, SIGALRM, SIGUSR1, SIGUSR2};

// The job was stopped by one of terminating_signals: exit 128 + signal, after
// the one-line message "interrupted".
class Interrupted : public RunError {
 public:
  explicit Interrupted(int signal_number)
      : RunError("interrupted"), signal_number_(signal_number) {}
  [[nodiscard]] int signal_number() const { return signal_number_; }
  [[nodiscard]] int exit_code() const { return 128 + signal_number_; }

 private:
  int signal_number_;
};

// While alive, the terminating signals only set a flag (the previous handlers
// come back on destruction); check() throws Interrupted once one arrived. The
// loops of a job call check() once a frame; a frame, or a sum, that runs on
// for interrupt_grace_ms after the signal is cut short by the guard's
// watchdog thread: it removes the registered temporaries (below), prints
// "calder: interrupted" and ends the process with 128 + the signal.
class InterruptGuard {
 public:
  InterruptGuard();
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;

  void check() const;

 private:
  std::array<struct sigaction, terminating_signals.size()> old_{};
  struct Watchdog;
  std::unique_ptr<Watchdog> watchdog_;
};

// How long a job may take to stop by itself after a terminating signal.
constexpr int interrupt_grace_ms = 400;

// What a job created and must remove if it is stopped (a temporary file, a
// staging folder with what is inside it), for the watchdog. Register a path
// while holding temporaries_lock() across its creation, so that the watchdog
// never races a file being created; unregister it once renamed or removed.
std::mutex& temporaries_lock();
std::size_t register_temporary(const std::string& path, bool folder);
void unregister_temporary(std::size_t id);
// The same, for a caller that holds temporaries_lock().
void unregister_temporary_locked(std::size_t id);

}  // namespace calder::app
