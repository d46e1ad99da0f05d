// SPDX-License-Identifier: MIT
// calder-bench's parts (bench_command.cpp runs them): what to measure
// (bench_plan.cpp), numbers and tables as text (bench_format.cpp), timing
// (bench_timing.cpp), one file per section (bench_direct.cpp, bench_bulk.cpp,
// bench_barnes_hut.cpp, bench_scaling.cpp, bench_targets.cpp) and the
// machine (bench_machine.cpp: /proc, the compiler, the date).
#pragma once

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <optional>
#include <ostream>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "calder/bulk.hpp"
#include "calder/nbody.hpp"
#include "calder/world.hpp"
#include "peers/nbody_systems.hpp"
#include "progress.hpp"

namespace calder::app::bench {

namespace nb = calder::nbody;
namespace peers = calder::peers;
using Clock = std::chrono::steady_clock;

// --- what to measure (bench_plan.cpp) ------------------------------------------------

struct Plan {
  bool quick = false;
  bool nbody = true;
  bool bulk = true;
  bool barnes_hut = true;
  bool scaling = true;
  // The scaling section's thread counts (--threads) and sizes: the direct
  // sums, Barnes-Hut (both precisions) and the rain scene (float32, book).
  std::vector<int> threads{1, 2};
  std::vector<std::size_t> scaling_direct32_n{16384, 131072};
  std::vector<std::size_t> scaling_direct64_n{16384};
  std::vector<std::size_t> scaling_bh64_n{1000000};
  std::vector<std::size_t> scaling_bh32_n{1000000, 10000000};
  std::vector<std::size_t> scaling_rain_n{1000000};
  std::vector<std::size_t> direct_n{1000, 4000, 16000};
  std::vector<std::size_t> bulk_n{1000, 100000, 1000000};
  std::vector<std::size_t> bh_n{10000, 100000, 1000000};
  std::size_t theta_table_n = 10000;
  std::size_t error_sample = 1000;  // bodies whose Barnes-Hut error is measured
  double min_time = 0.5;            // seconds per repetition
  int repetitions = 5;
  // A row whose single call takes longer than min_time (Box2D's 10^6
  // circles) repeats one call at a time, for about this long in all.
  double slow_budget = 10.0;
  std::int64_t fma_rounds = 4'000'000;          // ~10 ms a call
  std::size_t learner_slice_pairs = 1'000'000;  // ~25 ms a call
  double max_rms = 1e-3;                        // the Barnes-Hut accuracy target
  // Below calder::kDefaultTheta in steps of 0.05.
  std::vector<double> finer_thetas{calder::kDefaultTheta - 0.05, calder::kDefaultTheta - 0.1,
                                   calder::kDefaultTheta - 0.15};
};

Plan quick_plan();

// The targets. The n-body ones are ratios against a floor or peer measured
// in the same run: the share of the FMA floor, and Barnes-Hut's steps/s at
// N = 10^6 in the learner's time (steps/s x N^2 / the learner's pairs/s at
// the largest direct N): 2x the baseline, a tree code at RMS error < 1e-3
// that took 2.59 steps/s on 2 threads where the learner took 4.04e7 pairs/s
// (6.4e4). The learner's loop is the fixed yardstick.
inline constexpr std::size_t kTargetDirectN = 16000;
inline constexpr double kTargetDirect32 = 0.75;
inline constexpr double kTargetDirect64 = 0.5;
inline constexpr std::size_t kTargetBulkN = 100000;
inline constexpr double kTargetBulk32 = 2e9;
inline constexpr double kTargetBulk64 = 1e9;
inline constexpr std::size_t kTargetBarnesHutN = 1000000;
inline constexpr double kTargetBarnesHut = 2.0 * 2.59e12 / 4.04e7;
inline constexpr double kTargetScaling = 1.8;
inline constexpr double kTargetScalingBarnesHut = 1.85;
inline constexpr std::size_t kScalingMinN = 10000;
inline constexpr std::size_t kScalingMinNBarnesHut = 100000;  // N = 10^5 and 10^6

std::string arithmetic_text(int a);

// Flags: --only's sections, --min-time's seconds, --threads' list.
void parse_only(const std::string& text, Plan& plan);
double parse_min_time(const std::string& text);
std::vector<int> parse_threads(const std::string& text);

// --- numbers and tables as text (bench_format.cpp) -----------------------------------

std::string printf_text(const char* format, double value);
std::string rate_text(double value);     // three significant digits: 3.90, 50.8, 691, 3.89e9
std::string error_text(double value);    // 8.5e-4
std::string ratio_text(double value);    // 1.80x
std::string percent_text(double value);  // 42%
std::string count_text(std::size_t n);   // 16,000
std::string seconds_text(double seconds);

struct Table {
  std::string title;                 // may be empty
  std::vector<std::string> columns;  // a leading '>' right-aligns the column
  std::vector<std::vector<std::string>> rows;
};

struct Section {
  std::string title;
  std::vector<Table> tables;
  std::vector<std::string> notes;
};

void print_section(std::ostream& out, const Section& section, bool markdown);

// --- timing (bench_timing.cpp) -----------------------------------------------------

double seconds_since(Clock::time_point start);

struct Measured {
  double rate = 0.0;  // units per second: the median of the repetitions
  int repetitions = 0;
  double first_seconds = 0.0;  // the warm-up call
  double call_seconds = 0.0;   // a call after it
  bool capped = false;         // one call per repetition, fewer repetitions
};

// One line per measurement on a terminal, so that a run of minutes shows
// where it is; Ctrl-C stops it between repetitions.
class Runner {
 public:
  Runner(const Plan& plan, std::ostream& err)
      : plan_(plan), err_(err), verbose_(stderr_is_terminal()) {}

  void status(const std::string& what) {
    interrupt_.check();
    if (verbose_) err_ << "calder-bench: " << what << '\n' << std::flush;
  }

  // Calls `call` (which does some work and returns how much: pairs,
  // body-steps, steps) once to warm up, then in repetitions of at least
  // min_time seconds each; returns the median rate.
  Measured measure(const std::function<double()>& call);

 private:
  const Plan& plan_;
  std::ostream& err_;
  bool verbose_;
  InterruptGuard interrupt_;
};

// What a row says about its timing when it is not the plain median: a call
// too long for several per repetition, a first call much slower than the rest.
// What a row says about its timing when it is not the plain median.
std::string timing_note(const Measured& m, const std::string& unit);

// --- results the targets read ----------------------------------------------------------

struct BarnesHutRow {
  std::size_t n = 0;
  double theta = calder::kDefaultTheta;
  bool float32 = false;
  int threads = 1;
  double rate = 0.0;
  peers::ForceError error;
};

struct Results {
  std::map<std::tuple<std::size_t, bool, int>, double> direct;  // (N, float32, threads): pairs/s
  std::map<std::pair<bool, int>, double> direct_floor;          // (float32, threads): pairs/s
  std::map<std::tuple<std::size_t, int, int>, double> bulk;     // (N, arithmetic, threads)
  std::map<std::tuple<std::size_t, bool, int>, double> bulk_floor;  // (N, float32, threads)
  std::vector<BarnesHutRow> barnes_hut;
  std::size_t direct_reference_n = 0;     // the largest direct N (Barnes-Hut's "vs direct")
  std::map<std::size_t, double> learner;  // N: pairs/s (Barnes-Hut's target)
};

inline const char* precision_name(bool float32) { return float32 ? "float32" : "float64"; }

// --- the sections (one file each) ----------------------------------------------------

Section nbody_section(const Plan& plan, Runner& runner, Results& results);
Section bulk_section(const Plan& plan, Runner& runner, Results& results);
Section barnes_hut_section(const Plan& plan, Runner& runner, Results& results);
Section scaling_section(const Plan& plan, Runner& runner);
Section targets_section(const Plan& plan, const Results& results);

// --- the machine (bench_machine.cpp) -------------------------------------------------

// The share of all CPUs that other processes used between two samples.
struct CpuTimes {
  double machine_busy = -1.0;  // seconds, all CPUs; < 0 when unknown
  double machine_total = 0.0;
  double own = 0.0;  // this process, all threads
};
CpuTimes cpu_times();
std::string others_share(const CpuTimes& before, const CpuTimes& after);
std::vector<std::pair<std::string, std::string>> machine(const Plan& plan);

}  // namespace calder::app::bench
