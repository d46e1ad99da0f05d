// SPDX-License-Identifier: MIT
// calder-bench: calder's performance side by side with its peers, measured in
// one run (bench_command.hpp; docs/PERFORMANCE.md is its output). Built from
// bench/ with the peers (Box2D among them); not installed unless
// CALDER_INSTALL_BENCHMARKS is on.
//
//   calder-bench                                    the full run (a few minutes)
//   calder-bench --quick                            tiny sizes, a few seconds
//   calder-bench --only movers --format markdown --output movers.md
//
// Exit status: 0 success, 1 a write failed, 2 bad usage; every error is one
// line on stderr, "calder-bench: <message>".
#include <CLI/CLI.hpp>
#include <calder/version.hpp>
#include <exception>
#include <iostream>
#include <new>
#include <sstream>
#include <string>

#include "bench_command.hpp"
#include "errors.hpp"
#include "progress.hpp"

namespace {

int report(const std::string& message, int code) {
  std::cerr << "calder-bench: " << calder::app::one_line(message) << '\n';
  std::cerr.flush();
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace calder::app;
  std::ios::sync_with_stdio(false);
  CLI::App app(
      "calder-bench: calder measured against its peers (the learner's n-body, the FMA "
      "floor, Box2D)",
      "calder-bench");
  app.set_version_flag("--version", std::string("calder-bench ") + CALDER_VERSION_STRING);
  BenchOptions options;
  add_bench_flags(app, options);
  try {
    try {
      app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
      if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) {
        std::ostringstream help_err;
        app.exit(e, std::cout, help_err);  // --help, --version: to stdout, exit 0
        return exit_success;
      }
      return report(std::string(e.what()) + " (see 'calder-bench --help')", exit_usage);
    }
    bench_command(options, std::cout, std::cerr);
    std::cout.flush();
    if (!std::cout) return report("standard output: write failed", exit_failure);
    return exit_success;
  } catch (const InputError& e) {
    return report(e.what(), exit_usage);
  } catch (const Interrupted& e) {
    return report(e.what(), e.exit_code());
  } catch (const RunError& e) {
    return report(e.what(), exit_failure);
  } catch (const std::bad_alloc&) {
    return report("out of memory", exit_failure);
  } catch (const std::exception& e) {
    return report(e.what(), exit_failure);
  }
}
