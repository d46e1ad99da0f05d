// SPDX-License-Identifier: MIT
#include "progress.hpp"

#include <semaphore.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <system_error>
#include <thread>
#include <utility>
#include <vector>

namespace calder::app {

namespace {

// Shown only for jobs that take longer than this, redrawn at most this often.
constexpr double kShowAfterSeconds = 0.3;
constexpr double kRedrawSeconds = 0.1;
constexpr int kBarWidth = 24;

volatile std::sig_atomic_t g_signal = 0;
// Posted by the handler (sem_post is async-signal-safe), waited on by the watchdog.
sem_t g_signal_posted;
std::once_flag g_semaphore_made;

extern "C" void note_signal(int signal_number) {
  g_signal = signal_number;
  ::sem_post(&g_signal_posted);
}

struct Temporary {
  std::size_t id;
  std::string path;
  bool folder;
};

std::mutex g_temporaries_mutex;
std::vector<Temporary> g_temporaries;  // guarded by g_temporaries_mutex
std::size_t g_next_temporary = 1;

// Removes every registered temporary; the caller holds the lock.
void remove_temporaries() {
  for (const Temporary& t : g_temporaries) {
    std::error_code ec;
    if (t.folder) {
      std::filesystem::remove_all(t.path, ec);
    } else {
      ::unlink(t.path.c_str());
    }
  }
}

std::string duration_text(double seconds) {
  const auto s = static_cast<long long>(std::lround(seconds));
  char text[32];
  if (s >= 3600) {
    std::snprintf(text, sizeof text, "%lldh%02lldm", s / 3600, (s / 60) % 60);
  } else if (s >= 60) {
    std::snprintf(text, sizeof text, "%lldm%02llds", s / 60, s % 60);
  } else {
    std::snprintf(text, sizeof text, "%llds", s);
  }
  return text;
}

}  // namespace

bool stderr_is_terminal() { return ::isatty(STDERR_FILENO) == 1; }

Progress::Progress(std::ostream& err, std::string label, std::int64_t total, bool enabled)
    : err_(err),
      label_(std::move(label)),
      total_(std::max<std::int64_t>(total, 1)),
      enabled_(enabled),
      start_(Clock::now()),
      last_draw_(start_) {}

Progress::~Progress() { finish(); }

std::string Progress::line(const std::string& label, std::int64_t done, std::int64_t total,
                           double elapsed_seconds) {
  total = std::max<std::int64_t>(total, 1);
  done = std::clamp<std::int64_t>(done, 0, total);
  const double fraction = static_cast<double>(done) / static_cast<double>(total);
  const auto filled = static_cast<int>(fraction * kBarWidth);
  std::string text = label;
  text += " [";
  text.append(static_cast<std::size_t>(filled), '#');
  text.append(static_cast<std::size_t>(kBarWidth - filled), '.');
  char numbers[96];
  std::snprintf(numbers, sizeof numbers, "] %3d%% %lld/%lld", static_cast<int>(fraction * 100.0),
                static_cast<long long>(done), static_cast<long long>(total));
  text += numbers;
  if (done > 0 && done < total) {
    const double left = elapsed_seconds / fraction - elapsed_seconds;
    text += ", ";
    text += duration_text(left);
    text += " left";
  }
  return text;
}

void Progress::update(std::int64_t done) {
  if (!enabled_) return;
  const Clock::time_point now = Clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  if (elapsed < kShowAfterSeconds) return;
  if (shown_ && std::chrono::duration<double>(now - last_draw_).count() < kRedrawSeconds &&
      done < total_) {
    return;
  }
  std::string text = line(label_, done, total_, elapsed);
  const std::size_t length = text.size();
  if (length < width_) text.append(width_ - length, ' ');  // covers a longer last line
  err_ << '\r' << text;
  err_.flush();
  width_ = length;
  shown_ = true;
  last_draw_ = now;
}

void Progress::finish() {
  if (!shown_) return;
  err_ << '\r' << std::string(width_, ' ') << '\r';
  err_.flush();
  shown_ = false;
}

std::mutex& temporaries_lock() { return g_temporaries_mutex; }

std::size_t register_temporary(const std::string& path, bool folder) {
  // The caller holds temporaries_lock() (a std::mutex is not recursive).
  const std::size_t id = g_next_temporary++;
  g_temporaries.push_back({id, path, folder});
  return id;
}

void unregister_temporary(std::size_t id) {
  const std::lock_guard<std::mutex> lock(g_temporaries_mutex);
  unregister_temporary_locked(id);
}

void unregister_temporary_locked(std::size_t id) {
  std::erase_if(g_temporaries, [id](const Temporary& t) { return t.id == id; });
}

// Waits for a signal; if the job has not stopped interrupt_grace_ms later,
// cleans up and ends the process itself.
struct InterruptGuard::Watchdog {
  std::atomic<bool> stop{false};
  std::thread thread;

  Watchdog() {
    thread = std::thread([this] { watch(); });
  }
  ~Watchdog() {
    stop.store(true);
    ::sem_post(&g_signal_posted);
    thread.join();
  }
  Watchdog(const Watchdog&) = delete;
  Watchdog& operator=(const Watchdog&) = delete;

  void watch() {
    while (::sem_wait(&g_signal_posted) != 0) {
    }
    if (stop.load()) return;
    const auto deadline =
        std::chrono::steady_clock::now() + std::chrono::milliseconds(interrupt_grace_ms);
    while (!stop.load() && std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    if (stop.load()) return;
    const int signal_number = g_signal;
    g_temporaries_mutex.lock();  // held to the end: nothing new is created
    remove_temporaries();
    static const char message[] = "calder: interrupted\n";
    (void)!::write(STDERR_FILENO, message, sizeof message - 1);
    ::_exit(128 + signal_number);
  }
};

InterruptGuard::InterruptGuard() {
  std::call_once(g_semaphore_made, [] { ::sem_init(&g_signal_posted, 0, 0); });
  while (::sem_trywait(&g_signal_posted) == 0) {
  }
  g_signal = 0;
  watchdog_ = std::make_unique<Watchdog>();
  struct sigaction action {};
  action.sa_handler = note_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = 0;
  // A signal ignored when we started (nohup, a background job of a script)
  // stays ignored.
  for (std::size_t i = 0; i < terminating_signals.size(); ++i) {
    ::sigaction(terminating_signals[i], nullptr, &old_[i]);
    if (old_[i].sa_handler != SIG_IGN) ::sigaction(terminating_signals[i], &action, nullptr);
  }
}

InterruptGuard::~InterruptGuard() {
  watchdog_.reset();
  for (std::size_t i = 0; i < terminating_signals.size(); ++i) {
    ::sigaction(terminating_signals[i], &old_[i], nullptr);
  }
}

void InterruptGuard::check() const {
  const int signal_number = g_signal;
  if (signal_number != 0) throw Interrupted(signal_number);
}

}  // namespace calder::app
