// SPDX-License-Identifier: MIT
#include "errors.hpp"

#include <cerrno>
#include <csignal>
#include <exception>
#include <new>
#include <string>

#include "progress.hpp"

namespace calder::app {

std::string one_line(std::string message) {
  for (char& c : message) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  while (!message.empty() && message.back() == ' ') message.pop_back();
  // Whatever reached the message: no control characters reach the terminal.
  return detail::printable(message, 1000);
}

void throw_run_failure(const Error& error, const std::string& source, std::int64_t frame) {
  throw RunError(source + ": frame " + std::to_string(frame) + ": " + error.what());
}

int report(std::ostream& err, std::string_view program, std::string message, int code) {
  const std::string prefix = std::string(program) + ": ";
  while (message.starts_with(prefix)) message.erase(0, prefix.size());
  err << prefix << one_line(message) << '\n';
  err.flush();
  return code;
}

int run_cli(std::string_view program, std::ostream& out, std::ostream& err,
            const std::function<void()>& command) {
  try {
    command();
    out.flush();
    if (!out) {
      // The reader of a pipe went away: the end it asked for, not an error.
      if (errno == EPIPE || output::InterruptScope::signal() == SIGPIPE) return 128 + SIGPIPE;
      return report(err, program, "standard output: write failed", exit_failure);
    }
    return exit_success;
  } catch (const Interrupted& e) {
    // The reader of a pipe went away (`calder run ... | head`): nothing to report.
    if (e.signal_number() == SIGPIPE) return e.exit_code();
    return report(err, program, e.what(), e.exit_code());
  } catch (const RunError& e) {
    return report(err, program, e.what(), exit_failure);
  } catch (const Error& e) {  // InputError, InvalidArgument, SceneFileError: bad input
    return report(err, program, e.what(), exit_usage);
  } catch (const std::bad_alloc&) {
    return report(err, program, "out of memory", exit_failure);
  } catch (const std::exception& e) {
    return report(err, program, e.what(), exit_failure);
  }
}

}  // namespace calder::app
