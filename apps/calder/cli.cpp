// SPDX-License-Identifier: MIT
#include "cli.hpp"

#include <CLI/CLI.hpp>
#include <csignal>
#include <exception>
#include <new>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "calder/error.hpp"
#include "errors.hpp"
#include "progress.hpp"
#include "render_command.hpp"
#include "run_command.hpp"
#include "window_command.hpp"

#ifndef CALDER_VERSION
#define CALDER_VERSION "unknown"
#endif

namespace calder::app {

std::string one_line(std::string message) {
  for (char& c : message) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  while (!message.empty() && message.back() == ' ') message.pop_back();
  // Whatever reached the message: no control characters reach the terminal.
  return detail::printable(message, 1000);
}

namespace {

int report(std::ostream& err, std::string message, int code) {
  // One "calder: " prefix, however the message was put together.
  while (message.rfind("calder: ", 0) == 0) message.erase(0, 8);
  err << "calder: " << one_line(message) << '\n';
  err.flush();
  return code;
}

}  // namespace

namespace {

// The verbs and their flags, bound to one set of option structs. Built once
// per process: building CLI11's options is most of a short call's time (3/4
// of the command-line fuzz target's), and the tests and the fuzz target call
// main many times. CLI11 clears its results at each parse; main resets the
// structs.
struct Parser {
  CLI::App app{"calder: forces in 2D, after chapter 2 of The Nature of Code", "calder"};
  RunOptions run_options;
  RenderOptions render_options;
  WindowOptions window_options;
  CLI::App* run = nullptr;
  CLI::App* render = nullptr;
  CLI::App* window = nullptr;

  Parser() {
    app.set_version_flag("--version", std::string("calder ") + CALDER_VERSION);
    app.require_subcommand(1);
    app.footer(
        "Run `calder COMMAND --help` for a command's flags.\n"
        "Exit status: 0 success, 1 the run failed, 2 bad usage or bad input.\n");
    app.add_subcommand("list", "List the built-in scenes with one line on each");
    run = add_run_command(app, run_options);
    render = add_render_command(app, render_options);
    window = add_window_command(app, window_options);
  }
};

}  // namespace

int main(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
  static Parser parser;
  parser.run_options = {};
  parser.render_options = {};
  parser.window_options = {};
  CLI::App& app = parser.app;
  const RunOptions& run_options = parser.run_options;
  CLI::App* run = parser.run;
  const RenderOptions& render_options = parser.render_options;
  CLI::App* render = parser.render;
  const WindowOptions& window_options = parser.window_options;
  CLI::App* window = parser.window;

  try {
    try {
      app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
      if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) {
        // --help, --help-all, --version: to `out`, exit 0.
        std::ostringstream help_err;
        app.exit(e, out, help_err);
        out.flush();
        if (!out) return report(err, "standard output: write failed", exit_failure);
        return exit_success;
      }
      std::string hint = "see 'calder --help'";
      if (run->parsed()) hint = "see 'calder run --help'";
      if (render->parsed()) hint = "see 'calder render --help'";
      if (window->parsed()) hint = "see 'calder window --help'";
      std::string what = e.what();
      if (dynamic_cast<const CLI::RequiredError*>(&e) != nullptr && argc <= 1) {
        what = "a command is required: list, run, render or window";
      }
      const bool no_command = !run->parsed() && !render->parsed() && !window->parsed() &&
                              !app.get_subcommand("list")->parsed();
      if (no_command && argc > 1 && argv[1][0] != '-') {
        const std::vector<std::string_view> commands = {"list", "run", "render", "window"};
        what = "unknown command '" + detail::printable(argv[1]) + "'";
        if (const auto near = detail::closest(argv[1], commands)) {
          what += " (did you mean '" + std::string(*near) + "'?)";
        }
        what += "; the commands are list, run, render and window";
      }
      return report(err, what + " (" + hint + ")", exit_usage);
    }

    if (run->parsed()) {
      run_command(run_options, out, err);
    } else if (render->parsed()) {
      render_command(render_options, out, err);
    } else if (window->parsed()) {
      window_command(window_options, out, err);
    } else {
      print_scene_list(out);
    }
    out.flush();
    if (!out) return report(err, "standard output: write failed", exit_failure);
    return exit_success;
  } catch (const InputError& e) {
    return report(err, e.what(), exit_usage);
  } catch (const Error& e) {  // calder::SceneFileError and other bad input
    return report(err, e.what(), exit_usage);
  } catch (const Interrupted& e) {
    // The reader of a pipe went away (`calder run ... | head`): nothing to report.
    if (e.signal_number() == SIGPIPE) return e.exit_code();
    return report(err, e.what(), e.exit_code());
  } catch (const RunError& e) {
    return report(err, e.what(), exit_failure);
  } catch (const std::bad_alloc&) {
    return report(err, "out of memory", exit_failure);
  } catch (const std::exception& e) {
    return report(err, e.what(), exit_failure);
  }
}

}  // namespace calder::app
