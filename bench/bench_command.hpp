// SPDX-License-Identifier: MIT
// calder-bench (bench/calder_bench.cpp): calder's performance side by side with its
// peers, measured in one run (docs/PERFORMANCE.md is its output):
//
//   nbody       direct summation (pairs/s; float32, float64; 1 and 2 threads)
//               against the book's example 2.9 written plainly in C++ and a
//               floor, this CPU's measured FMA peak / the flops of one pair
//   bulk        the "rain" scene through calder::bulk (body-steps/s; book,
//               float64, float32 arithmetic; 1 and 2 threads) against Box2D
//               2.4 running it ("movers" is accepted as its former name)
//   barnes-hut  steps/s and the force error against the direct float64 sum
//   scaling     each workload at every --threads count: rate, speedup,
//               efficiency, serial share, the threads' work balance
//
// then the targets, pass or miss. Each figure is the median of several
// repetitions of at least --min-time seconds, after one warm-up.
//
//   calder-bench                              the full run (several minutes)
//   calder-bench --quick                      tiny sizes, a few seconds (smoke test)
//   calder-bench --only bulk --format markdown --output bulk.md
//   calder-bench --only scaling --threads 1,2,4,8,16
#pragma once

#include <optional>
#include <ostream>
#include <string>

namespace CLI {
class App;
}

namespace calder::app {

struct BenchOptions {
  std::optional<std::string> only;      // "nbody,bulk,barnes-hut,scaling" (any of them)
  bool quick = false;                   // tiny sizes and times
  std::optional<std::string> format;    // "text" (default) or "markdown"
  std::optional<std::string> output;    // a path, or "-" for stdout (default)
  std::optional<std::string> min_time;  // seconds per repetition
  std::optional<std::string> threads;   // "1,2,4,8,16": the scaling table's thread counts
};

// Adds the flags (--only, --quick, --format, --output, --min-time, --threads) to `bench`.
void add_bench_flags(CLI::App& bench, BenchOptions& options);

// Measures and prints the tables to `out` (or --output, written atomically);
// progress lines go to `err` when it is a terminal. Throws InputError for bad
// flags (exit 2), Interrupted on SIGINT / SIGTERM, RunError when the output
// can't be written.
void bench_command(const BenchOptions& options, std::ostream& out, std::ostream& err);

}  // namespace calder::app
