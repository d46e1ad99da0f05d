// SPDX-License-Identifier: MIT
// calder output module: the registry of temporaries and the one handler of
// terminating signals (output.hpp, InterruptScope).
#include <semaphore.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <string>
#include <system_error>
#include <thread>
#include <utility>
#include <vector>

#include "output.hpp"

namespace calder::output {

namespace {

volatile std::sig_atomic_t g_signal = 0;
// Posted by the handler (sem_post is async-signal-safe), waited on by the watchdog.
sem_t g_signal_posted;
std::once_flag g_semaphore_made;
int g_depth = 0;  // InterruptScopes alive (the outermost installs the handler)

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

}  // namespace

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
  if (id == 0) return;
  std::erase_if(g_temporaries, [id](const Temporary& t) { return t.id == id; });
}

void remove_temporaries_locked() noexcept {
  for (const Temporary& t : g_temporaries) {
    std::error_code ec;
    if (t.folder) {
      std::filesystem::remove_all(t.path, ec);
    } else {
      ::unlink(t.path.c_str());
    }
  }
  g_temporaries.clear();
}

// Waits for a signal; if the job has not stopped interrupt_grace_ms later,
// cleans up and ends the process itself.
struct InterruptScope::Watchdog {
  std::string message;
  std::atomic<bool> stop{false};
  std::thread thread;

  explicit Watchdog(const std::string& program) : message(program + ": interrupted\n") {
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
    remove_temporaries_locked();
    // A reader that went away (SIGPIPE) is not an error worth a line.
    if (signal_number != SIGPIPE) (void)!::write(STDERR_FILENO, message.data(), message.size());
    ::_exit(128 + signal_number);
  }
};

InterruptScope::InterruptScope(std::string program) {
  if (g_depth++ > 0) return;  // an outer scope handles them
  std::call_once(g_semaphore_made, [] { ::sem_init(&g_signal_posted, 0, 0); });
  while (::sem_trywait(&g_signal_posted) == 0) {
  }
  g_signal = 0;
  watchdog_ = std::make_unique<Watchdog>(program);
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

InterruptScope::~InterruptScope() {
  --g_depth;
  if (!watchdog_) return;
  watchdog_.reset();
  for (std::size_t i = 0; i < terminating_signals.size(); ++i) {
    ::sigaction(terminating_signals[i], &old_[i], nullptr);
  }
}

int InterruptScope::signal() noexcept { return g_signal; }

}  // namespace calder::output
