// SPDX-License-Identifier: MIT
#include "cli.hpp"

#include <CLI/CLI.hpp>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "calder/error.hpp"
#include "devices_command.hpp"
#include "errors.hpp"
#include "render_command.hpp"
#include "run_command.hpp"
#include "sweep_command.hpp"
#include "window_command.hpp"

#ifndef CALDER_VERSION
#define CALDER_VERSION "unknown"
#endif

namespace calder::app {

namespace {

// The commands, in the order --help lists them.
std::vector<std::string> command_names(const CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
    names.push_back(sub->get_name());
  }
  return names;
}

// "a, b, c <last> d".
std::string listed(const std::vector<std::string>& names, const char* last) {
  std::string text;
  for (std::size_t k = 0; k < names.size(); ++k) {
    if (k > 0) text += k + 1 == names.size() ? std::string(" ") + last + " " : ", ";
    text += names[k];
  }
  return text;
}

// Whether argv[1] is a word that names no command (a flag is not one).
bool unknown_command(const CLI::App& app, int argc, const char* const* argv) {
  if (argc <= 1 || argv[1][0] == '-') return false;
  for (const std::string& name : command_names(app)) {
    if (name == argv[1]) return false;
  }
  return true;
}

// The one-line error for an unknown command, naming every command.
std::string unknown_command_message(const CLI::App& app, const char* word) {
  const std::vector<std::string> names = command_names(app);
  const std::vector<std::string_view> commands(names.begin(), names.end());
  std::string what = "unknown command '" + detail::printable(word) + "'";
  if (const auto near = detail::closest(word, commands)) {
    what += " (did you mean '" + std::string(*near) + "'?)";
  }
  return what + "; the commands are " + listed(names, "and");
}

// A CLI11 parse error (not --help or --version) as the one-line message: what
// went wrong and which --help to read.
std::string usage_message(const CLI::ParseError& e, const CLI::App& app, int argc,
                          const char* const* argv) {
  const std::vector<std::string> verbs = {"run", "render", "window", "sweep"};
  std::string hint = "see 'calder --help'";
  bool no_command = !app.get_subcommand("list")->parsed();
  for (const std::string& verb : verbs) {
    if (app.get_subcommand(verb)->parsed()) {
      hint = "see 'calder " + verb + " --help'";
      no_command = false;
    }
  }
  std::string what = e.what();
  if (dynamic_cast<const CLI::RequiredError*>(&e) != nullptr && argc <= 1) {
    what = "a command is required: " + listed(command_names(app), "or");
  }
  if (no_command && unknown_command(app, argc, argv)) what = unknown_command_message(app, argv[1]);
  return what + " (" + hint + ")";
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
  SweepOptions sweep_options;
  CLI::App* run = nullptr;
  CLI::App* render = nullptr;
  CLI::App* window = nullptr;
  CLI::App* devices = nullptr;  // devices_command.hpp
  CLI::App* sweep = nullptr;    // sweep_command.hpp

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
    devices = add_devices_command(app);
    sweep = add_sweep_command(app, sweep_options);
  }
};

}  // namespace

int main(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
  static Parser parser;
  parser.run_options = {};
  parser.render_options = {};
  parser.window_options = {};
  parser.sweep_options = {};
  CLI::App& app = parser.app;
  const RunOptions& run_options = parser.run_options;
  CLI::App* run = parser.run;
  const RenderOptions& render_options = parser.render_options;
  CLI::App* render = parser.render;
  const WindowOptions& window_options = parser.window_options;
  CLI::App* window = parser.window;

  return run_cli("calder", out, err, [&] {
    try {
      app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
      if (e.get_exit_code() != static_cast<int>(CLI::ExitCodes::Success)) {
        throw InputError(usage_message(e, app, argc, argv));
      }
      // `calder nosuch --help`: no help for a command that doesn't exist.
      if (unknown_command(app, argc, argv)) {
        throw InputError(unknown_command_message(app, argv[1]) + " (see 'calder --help')");
      }
      std::ostringstream help_err;
      app.exit(e, out, help_err);  // --help, --help-all, --version: to `out`, exit 0
      return;
    }
    if (run->parsed()) {
      run_command(run_options, out, err);
    } else if (render->parsed()) {
      render_command(render_options, out, err);
    } else if (window->parsed()) {
      window_command(window_options, out, err);
    } else if (parser.sweep->parsed()) {
      sweep_command(parser.sweep_options, out, err);
    } else if (parser.devices->parsed()) {
      devices_command(out);
    } else {
      print_scene_list(out);
    }
  });
}

}  // namespace calder::app
