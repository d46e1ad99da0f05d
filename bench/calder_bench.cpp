// SPDX-License-Identifier: MIT
// calder-bench: calder's performance side by side with its peers, measured in
// one run (bench_command.hpp; docs/PERFORMANCE.md is its output). Built from
// bench/ with the peers (Box2D among them); not installed unless
// CALDER_INSTALL_BENCHMARKS is on.
//
//   calder-bench                                    the full run (a few minutes)
//   calder-bench --quick                            tiny sizes, a few seconds
//   calder-bench --only bulk --format markdown --output bulk.md
//
// Exit status: 0 success, 1 a write failed, 2 bad usage; every error is one
// line on stderr, "calder-bench: <message>".
#include <CLI/CLI.hpp>
#include <calder/version.hpp>
#include <iostream>
#include <sstream>
#include <string>

#include "bench_command.hpp"
#include "errors.hpp"

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
  return run_cli("calder-bench", std::cout, std::cerr, [&] {
    try {
      app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
      if (e.get_exit_code() != static_cast<int>(CLI::ExitCodes::Success)) {
        throw InputError(std::string(e.what()) + " (see 'calder-bench --help')");
      }
      std::ostringstream help_err;
      app.exit(e, std::cout, help_err);  // --help, --version: to stdout, exit 0
      return;
    }
    bench_command(options, std::cout, std::cerr);
  });
}
