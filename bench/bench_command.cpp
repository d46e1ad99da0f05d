// SPDX-License-Identifier: MIT
#include "bench_command.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <tuple>
#include <utility>
#include <vector>

#include "calder/bulk.hpp"
#include "calder/nbody.hpp"
#include "calder/world.hpp"
#include "errors.hpp"
#include "output_file.hpp"
#include "parse.hpp"
#include "peers/fma_peak.hpp"
#include "peers/learner_nbody.hpp"
#include "peers/nbody_systems.hpp"
#include "peers/rain_world.hpp"
#include "peers/soa_rain.hpp"
#include "progress.hpp"

#ifndef CALDER_BUILD_TYPE
#define CALDER_BUILD_TYPE "unknown"
#endif

namespace calder::app {

namespace {

namespace nb = calder::nbody;
namespace peers = calder::peers;
using Clock = std::chrono::steady_clock;

// --- what to measure -------------------------------------------------------------

struct Plan {
  bool quick = false;
  bool nbody = true;
  bool movers = true;
  bool barnes_hut = true;
  std::vector<std::size_t> direct_n{1000, 4000, 16000};
  std::vector<std::size_t> movers_n{1000, 100000, 1000000};
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

Plan quick_plan() {
  Plan plan;
  plan.quick = true;
  plan.direct_n = {500, 2000};
  plan.movers_n = {1000, 10000};
  plan.bh_n = {2000, 10000};
  plan.theta_table_n = 2000;
  plan.error_sample = 200;
  plan.min_time = 0.01;
  plan.repetitions = 3;
  plan.slow_budget = 0.2;
  plan.fma_rounds = 200'000;
  plan.learner_slice_pairs = 100'000;
  return plan;
}

// The targets. The n-body ones are ratios against a floor or peer
// measured in the same run: the share of the FMA floor (issue 9), and
// Barnes-Hut's steps/s at N = 10^6 in the learner's time (steps/s x N^2 / the
// learner's pairs/s at the largest direct N): 2x what the code before issue 9
// reached at RMS error < 1e-3 on the development machine (9e99ffe, theta
// 0.45, float64, 2 threads: 2.59 steps/s against the learner's 4.04e7 pairs/s,
// 6.4e4; docs/PERFORMANCE.md, issue 9 part 3). The learner's loop has not
// changed since; the direct sum, the yardstick before, has (each pair once).
constexpr std::size_t kTargetDirectN = 16000;
constexpr double kTargetDirect32 = 0.75;
constexpr double kTargetDirect64 = 0.5;
constexpr std::size_t kTargetMoversN = 100000;
constexpr double kTargetMovers32 = 2e9;
constexpr double kTargetMovers64 = 1e9;
constexpr std::size_t kTargetBarnesHutN = 1000000;
constexpr double kTargetBarnesHut = 2.0 * 2.59e12 / 4.04e7;
constexpr double kTargetScaling = 1.8;
constexpr double kTargetScalingBarnesHut = 1.85;  // issue 9
constexpr std::size_t kScalingMinN = 10000;
constexpr std::size_t kScalingMinNBarnesHut = 100000;  // issue 9: N = 10^5 and 10^6

// The arithmetics in calder::kArithmeticNames' order: book, float64, float32.
std::string arithmetic_text(int a) {
  return std::string(kArithmeticNames[static_cast<std::size_t>(a)].name);
}

// --- numbers as text ---------------------------------------------------------------

std::string printf_text(const char* format, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

// "3.89e+09" -> "3.89e9", "8.5e-04" -> "8.5e-4".
std::string short_exponent(const std::string& text) {
  const std::size_t e = text.find('e');
  if (e == std::string::npos) return text;
  return text.substr(0, e + 1) + std::to_string(std::stoi(text.substr(e + 1)));
}

// Three significant digits, at least: 3.90, 50.8, 691, 1160, 3.89e9.
std::string rate_text(double value) {
  if (!std::isfinite(value) || value <= 0.0) return "-";
  if (value >= 1e4 || value < 1e-2) return short_exponent(printf_text("%.2e", value));
  if (value >= 99.95) return printf_text("%.0f", value);
  return printf_text("%#.3g", value);  // 3.90, not 3.9
}

std::string error_text(double value) {
  if (!std::isfinite(value)) return "-";
  return short_exponent(printf_text("%.1e", value));
}

// Three significant digits, trailing zeros kept (1.80x is not 1.8x rounded up).
std::string ratio_text(double value) {
  if (!std::isfinite(value) || value <= 0.0) return "-";
  if (value >= 99.95) return printf_text("%.0f", value) + "x";
  if (value >= 9.995) return printf_text("%.1f", value) + "x";
  return printf_text("%.2f", value) + "x";
}

std::string percent_text(double value) {
  if (!std::isfinite(value) || value <= 0.0) return "-";
  return printf_text("%.0f", 100.0 * value) + "%";
}

// 16000 -> "16,000".
std::string count_text(std::size_t n) {
  std::string digits = std::to_string(n);
  std::string text;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) text += ',';
    text += digits[i];
  }
  return text;
}

std::string seconds_text(double seconds) { return printf_text("%.2g", seconds) + " s"; }

// --- tables ------------------------------------------------------------------------

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

std::string column_name(const std::string& column) {
  return !column.empty() && column.front() == '>' ? column.substr(1) : column;
}

bool right_aligned(const std::string& column) { return !column.empty() && column.front() == '>'; }

void print_text(std::ostream& out, const Table& table) {
  if (!table.title.empty()) out << table.title << "\n\n";
  const std::size_t columns = table.columns.size();
  std::vector<std::size_t> width(columns, 0);
  for (std::size_t c = 0; c < columns; ++c) width[c] = column_name(table.columns[c]).size();
  for (const auto& row : table.rows) {
    for (std::size_t c = 0; c < columns && c < row.size(); ++c) {
      width[c] = std::max(width[c], row[c].size());
    }
  }
  auto line = [&](const std::vector<std::string>& cells, bool header) {
    std::string text = "  ";
    for (std::size_t c = 0; c < columns; ++c) {
      const std::string cell = header ? column_name(cells[c]) : (c < cells.size() ? cells[c] : "");
      const std::string pad(width[c] - cell.size(), ' ');
      text += right_aligned(table.columns[c]) ? pad + cell : cell + pad;
      if (c + 1 < columns) text += "  ";
    }
    while (!text.empty() && text.back() == ' ') text.pop_back();
    out << text << '\n';
  };
  line(table.columns, true);
  std::vector<std::string> rule;
  for (std::size_t c = 0; c < columns; ++c) rule.emplace_back(width[c], '-');
  line(rule, false);
  for (const auto& row : table.rows) line(row, false);
  out << '\n';
}

void print_markdown(std::ostream& out, const Table& table) {
  if (!table.title.empty()) out << table.title << "\n\n";
  out << '|';
  for (const auto& column : table.columns) out << ' ' << column_name(column) << " |";
  out << "\n|";
  for (const auto& column : table.columns) out << (right_aligned(column) ? "--:|" : "---|");
  out << '\n';
  for (const auto& row : table.rows) {
    out << '|';
    for (std::size_t c = 0; c < table.columns.size(); ++c) {
      out << ' ' << (c < row.size() ? row[c] : "") << " |";
    }
    out << '\n';
  }
  out << '\n';
}

void print_section(std::ostream& out, const Section& section, bool markdown) {
  out << (markdown ? "## " : "== ") << section.title << "\n\n";
  for (const Table& table : section.tables) {
    if (markdown) {
      print_markdown(out, table);
    } else {
      print_text(out, table);
    }
  }
  for (const std::string& note : section.notes) out << (markdown ? "- " : "  - ") << note << '\n';
  if (!section.notes.empty()) out << '\n';
}

// --- timing ------------------------------------------------------------------------

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

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
  Measured measure(const std::function<double()>& call) {
    Measured m;
    Clock::time_point start = Clock::now();
    (void)call();
    m.first_seconds = m.call_seconds = seconds_since(start);
    if (m.first_seconds >= plan_.min_time) {
      // A slow first call may be a one-off (Box2D's first broad-phase pass
      // over every new body): the next one says what a call costs.
      interrupt_.check();
      start = Clock::now();
      (void)call();
      m.call_seconds = seconds_since(start);
    }
    int repetitions = plan_.repetitions;
    if (m.call_seconds >= plan_.min_time) {
      m.capped = true;
      repetitions =
          std::clamp(static_cast<int>(plan_.slow_budget / m.call_seconds), 1, plan_.repetitions);
    }
    std::vector<double> rates;
    for (int r = 0; r < repetitions; ++r) {
      interrupt_.check();
      double units = 0.0;
      double elapsed = 0.0;
      start = Clock::now();
      do {
        units += call();
        elapsed = seconds_since(start);
      } while (elapsed < plan_.min_time);
      rates.push_back(units / elapsed);
    }
    std::sort(rates.begin(), rates.end());
    const std::size_t mid = rates.size() / 2;
    m.rate = rates.size() % 2 == 1 ? rates[mid] : 0.5 * (rates[mid - 1] + rates[mid]);
    m.repetitions = repetitions;
    return m;
  }

 private:
  const Plan& plan_;
  std::ostream& err_;
  bool verbose_;
  InterruptGuard interrupt_;
};

// What a row says about its timing when it is not the plain median: a call
// too long for several per repetition, a first call much slower than the rest.
std::string timing_note(const Measured& m, const std::string& unit) {
  std::string note;
  if (m.capped) {
    note = "capped: 1 " + unit + " per repetition (" + seconds_text(m.call_seconds) +
           "), median of " + std::to_string(m.repetitions);
  }
  if (m.first_seconds >= 1.0 && m.first_seconds > 3.0 * m.call_seconds) {
    if (!note.empty()) note += "; ";
    note += "the first " + unit + " took " + seconds_text(m.first_seconds) + " (not counted)";
  }
  return note;
}

// --- results the targets read --------------------------------------------------------

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
  std::map<std::tuple<std::size_t, int, int>, double> movers;   // (N, arithmetic, threads)
  std::map<std::tuple<std::size_t, bool, int>, double> movers_floor;  // (N, float32, threads)
  std::vector<BarnesHutRow> barnes_hut;
  std::size_t direct_reference_n = 0;     // the largest direct N (Barnes-Hut's "vs direct")
  std::map<std::size_t, double> learner;  // N: pairs/s (Barnes-Hut's target)
};

const char* precision_name(bool float32) { return float32 ? "float32" : "float64"; }

// --- n-body, direct ----------------------------------------------------------------

Section nbody_section(const Plan& plan, Runner& runner, Results& results) {
  Section section;
  section.title = "n-body, direct summation: pair interactions per second";

  // The floor: the FMA peak at the kernels' vector width.
  peers::PairFloor pair_floor = peers::pair_floor(nb::kernel_name());
  const std::vector<int> widths = peers::fma_widths();
  if (std::find(widths.begin(), widths.end(), pair_floor.bits) == widths.end()) {
    pair_floor.bits = widths.front();
  }
  double peak[3] = {0.0, 0.0, 0.0};  // flop/s by threads
  for (int threads : {1, 2}) {
    runner.status("FMA peak, " + std::to_string(pair_floor.bits) + "-bit, " +
                  std::to_string(threads) + " thread(s)");
    peak[threads] =
        runner.measure([&] { return peers::fma_flops(pair_floor.bits, threads, plan.fma_rounds); })
            .rate;
  }

  Table table;
  table.columns = {"what",     ">N",          "precision",     ">threads",
                   ">pairs/s", ">vs learner", ">of FMA floor", "note"};
  for (int threads : {1, 2}) {
    results.direct_floor[{true, threads}] = pair_floor.pairs32(peak[threads]);
    results.direct_floor[{false, threads}] = pair_floor.pairs64(peak[threads]);
    table.rows.push_back({"floor: FMA peak / flops per pair", "any", "float32",
                          std::to_string(threads), rate_text(pair_floor.pairs32(peak[threads])), "",
                          "100%", ""});
  }
  for (int threads : {1, 2}) {
    table.rows.push_back({"floor: FMA peak / flops per pair", "any", "float64",
                          std::to_string(threads), rate_text(pair_floor.pairs64(peak[threads])), "",
                          "100%", ""});
  }

  bool sliced = false;  // the learner was timed on slices of its loop
  for (const std::size_t n : plan.direct_n) {
    const peers::NBodySystem system = peers::disk(n, 42);
    const double pairs = static_cast<double>(n) * static_cast<double>(n);

    // The learner, on slices of its double loop when a whole one is long.
    runner.status("learner, N = " + count_text(n));
    peers::LearnerNBody learner(system.x, system.y, system.m);
    const std::size_t slice = std::clamp<std::size_t>(plan.learner_slice_pairs / n, 1, n);
    std::size_t next = 0;
    const Measured learner_rate = runner.measure([&] {
      if (next >= n) {
        learner.clear();
        next = 0;
      }
      const std::size_t last = std::min(next + slice, n);
      learner.attract(next, last);
      const double done = static_cast<double>(last - next) * static_cast<double>(n);
      next = last;
      return done;
    });
    std::string learner_note;
    if (slice < n) {
      learner_note = "timed on slices of " + count_text(slice) + " rows of its loop";
      sliced = true;
    }
    table.rows.push_back({"learner: book ex. 2.9 in plain C++", count_text(n), "float64", "1",
                          rate_text(learner_rate.rate), "1x", "", learner_note});
    results.learner[n] = learner_rate.rate;

    nb::Options options;
    options.softening = peers::kDiskSoftening;
    std::vector<double> ax(n);
    std::vector<double> ay(n);
    for (const bool float32 : {false, true}) {
      for (int threads : {1, 2}) {
        runner.status(std::string("direct, N = ") + count_text(n) + ", " + precision_name(float32) +
                      ", " + std::to_string(threads) + " thread(s)");
        options.precision = float32 ? nb::Precision::float32 : nb::Precision::float64;
        options.threads = threads;
        const Measured m = runner.measure([&] {
          nb::direct_accelerations(system.x, system.y, system.m, ax, ay, options);
          return pairs;
        });
        results.direct[{n, float32, threads}] = m.rate;
        const double floor_rate =
            float32 ? pair_floor.pairs32(peak[threads]) : pair_floor.pairs64(peak[threads]);
        table.rows.push_back({"calder direct", count_text(n), precision_name(float32),
                              std::to_string(threads), rate_text(m.rate),
                              ratio_text(m.rate / learner_rate.rate),
                              percent_text(m.rate / floor_rate), ""});
      }
    }
    // Like for like with the learner, at the largest N: the book's clamp
    // (a square root and a division per pair; the floor counts Plummer's flops).
    if (n == plan.direct_n.back()) {
      nb::Options clamp;
      clamp.law = nb::Law::clamp_distance;
      clamp.min_distance = 5.0;
      clamp.max_distance = 25.0;
      for (const bool float32 : {false, true}) {
        for (int threads : {1, 2}) {
          runner.status(std::string("direct, book clamp, N = ") + count_text(n) + ", " +
                        precision_name(float32) + ", " + std::to_string(threads) + " thread(s)");
          clamp.precision = float32 ? nb::Precision::float32 : nb::Precision::float64;
          clamp.threads = threads;
          const Measured m = runner.measure([&] {
            nb::direct_accelerations(system.x, system.y, system.m, ax, ay, clamp);
            return pairs;
          });
          table.rows.push_back({"calder direct, the book's clamp", count_text(n),
                                precision_name(float32), std::to_string(threads), rate_text(m.rate),
                                ratio_text(m.rate / learner_rate.rate), "-", ""});
        }
      }
    }
    results.direct_reference_n = std::max(results.direct_reference_n, n);
  }
  section.tables.push_back(std::move(table));

  section.notes = {
      "pairs/s counts N^2 pair interactions per evaluation (self pairs included, as the kernels "
      "compute them). From 3,585 bodies calder evaluates each pair once and adds it to both "
      "bodies (Newton's third law), about N^2 / 2 evaluations; the floor is per evaluation, so "
      "from there the share of it can pass 100%. calder direct: "
      "calder::nbody::direct_accelerations, Plummer softening " +
          printf_text("%.2g", peers::kDiskSoftening) + ", " + nb::kernel_name() +
          " kernels, on a uniform disk of N bodies.",
      "learner: the book's example 2.9 as a learner writes it in C++ (a Mover object per body, "
      "a new heap vector per force, the book's clamp of the distance to [5, 25], as the clamp "
      "rows), one thread, in double" +
          std::string(sliced ? "; at large N timed on slices of its double loop (the "
                               "same inner loop over all N bodies), not whole "
                               "evaluations"
                             : "") +
          ".",
      "floor: this CPU's FMA peak, measured with " + std::to_string(pair_floor.bits) +
          "-bit vectors (the kernels' width): " + rate_text(peak[1]) + " flop/s on 1 thread, " +
          rate_text(peak[2]) + " on 2; divided by the flops of one pair, " +
          printf_text("%.0f", pair_floor.flops_per_pair32) + " in float32 and " +
          printf_text("%.0f", pair_floor.flops_per_pair64) +
          " in float64 (an FMA counts 2; float64 vectors hold half the lanes). No kernel that "
          "evaluates every pair can go faster.",
  };
  return section;
}

// --- movers ------------------------------------------------------------------------

// Steps the world body by body (no kernels) while alive.
class PlainLoops {
 public:
  PlainLoops() { set_step_batch_backend(nullptr); }
  ~PlainLoops() { set_step_batch_backend(bulk::step_batch); }
  PlainLoops(const PlainLoops&) = delete;
  PlainLoops& operator=(const PlainLoops&) = delete;
};

Section movers_section(const Plan& plan, Runner& runner, Results& results) {
  Section section;
  section.title = "movers, the rain scene: body-steps per second";
  Table table;
  table.columns = {"what",          ">N",        "arithmetic", ">threads",
                   ">body-steps/s", ">vs Box2D", ">vs floor",  "note"};
  // The floor's copy for the movers' instruction set: AVX2 + FMA alone when
  // the movers run their AVX2 kernels, else -march=native.
  const bool avx2 = std::string(bulk::kernel_name()) == "avx2+fma";
  std::string floor_flags;

  for (const std::size_t n : plan.movers_n) {
    const World proto = peers::rain_world(n, Arithmetic::book, 1);
    const double bodies = static_cast<double>(n);

    // The floor: the plain SoA loop of the same physics, in each precision.
    std::map<std::pair<bool, int>, double> floor;  // (float32, threads)
    std::vector<std::vector<std::string>> floor_rows;
    for (const bool float32 : {false, true}) {
      for (int threads : {1, 2}) {
        runner.status(std::string("SoA floor, N = ") + count_text(n) + ", " +
                      precision_name(float32) + ", " + std::to_string(threads) + " thread(s)");
        peers::SoaRain soa(proto, float32, avx2, threads);
        floor_flags = soa.flags();
        const Measured m = runner.measure([&] {
          soa.step(World::kBatchSteps);
          return bodies * World::kBatchSteps;
        });
        floor[{float32, threads}] = m.rate;
        results.movers_floor[{n, float32, threads}] = m.rate;
        floor_rows.push_back({"floor: plain SoA loop", count_text(n), precision_name(float32),
                              std::to_string(threads), rate_text(m.rate), "", "1x",
                              timing_note(m, "batch")});
      }
    }
    // Against the floor of the same precision (book: float64) and threads.
    const auto vs_floor = [&](double rate, bool float32, int threads) {
      return ratio_text(rate / floor[{float32, threads}]);
    };

    double box2d_rate = 0.0;
    for (const peers::Box2dBodies kind :
         {peers::Box2dBodies::circles, peers::Box2dBodies::points}) {
      const bool circles = kind == peers::Box2dBodies::circles;
      runner.status("Box2D " + std::string(circles ? "circles" : "points") +
                    ", N = " + count_text(n));
      const Clock::time_point built = Clock::now();
      peers::Box2dRain box2d = peers::box2d_rain(proto, kind);
      const double build_seconds = seconds_since(built);
      const Measured m = runner.measure([&] {
        box2d.step();
        return bodies;
      });
      if (circles) box2d_rate = m.rate;
      std::string note = timing_note(m, "step");
      if (build_seconds >= 1.0) {
        note += (note.empty() ? "" : "; ") + std::string("building it took ") +
                seconds_text(build_seconds) + " (not counted)";
      }
      table.rows.push_back({circles ? "Box2D 2.4: circles, collisions filtered out"
                                    : "Box2D 2.4: bodies without shapes",
                            count_text(n), "float32", "1", rate_text(m.rate),
                            ratio_text(m.rate / box2d_rate), vs_floor(m.rate, true, 1), note});
    }
    for (std::vector<std::string>& row : floor_rows) {
      row[5] = ratio_text(floor[{row[2] == "float32", std::stoi(row[3])}] / box2d_rate);
      table.rows.push_back(std::move(row));
    }

    {
      runner.status("plain loops, N = " + count_text(n));
      World world = proto;
      const PlainLoops plain;
      const Measured m = runner.measure([&] {
        world.step();
        return bodies;
      });
      table.rows.push_back({"calder, plain loops (no kernels)", count_text(n), "book", "1",
                            rate_text(m.rate), ratio_text(m.rate / box2d_rate),
                            vs_floor(m.rate, false, 1), timing_note(m, "step")});
    }

    for (int a = 0; a < 3; ++a) {
      for (int threads : {1, 2}) {
        runner.status(std::string("movers, N = ") + count_text(n) + ", " + arithmetic_text(a) +
                      ", " + std::to_string(threads) + " thread(s)");
        World world = proto;
        world.set_arithmetic(kArithmeticNames[static_cast<std::size_t>(a)].value);
        world.set_threads(threads);
        const Measured m = runner.measure([&] {
          world.step(World::kBatchSteps);
          return bodies * World::kBatchSteps;
        });
        results.movers[{n, a, threads}] = m.rate;
        table.rows.push_back({"calder movers", count_text(n), arithmetic_text(a),
                              std::to_string(threads), rate_text(m.rate),
                              ratio_text(m.rate / box2d_rate), vs_floor(m.rate, a == 2, threads),
                              timing_note(m, "batch")});
      }
    }
  }
  section.tables.push_back(std::move(table));
  section.notes = {
      "body-steps/s: bodies x steps per second. The rain scene (scenes/rain.toml): gravity scaled "
      "by mass, quadratic drag, a bounce on the radius off the walls and the floor, no body-body "
      "collisions; the canvas grows with N so that the density stays that of 1000 drops on "
      "640 x 240.",
      std::string("calder movers: World::step(") + std::to_string(World::kBatchSteps) +
          ") through calder::bulk's " + bulk::kernel_name() +
          " kernels; book is bit-identical to the plain loops, float64 and float32 trade the "
          "last bits for speed (calder/bulk.hpp). plain loops: the same world stepped body by "
          "body by calder's core.",
      "floor: the rain physics as the plain structure-of-arrays loop anyone would write "
      "(bench/peers/soa_rain_loop.cpp: one pass over the arrays per step, branch-free, "
      "gravity, drag, the bounce), compiled " +
          floor_flags +
          "; on 2 threads each runs every step on its own half of the arrays. vs floor: "
          "against the floor of the same precision (book: float64) and threads.",
      "Box2D 2.4 (single-threaded, float): forces applied per body (ApplyForceToCenter), "
      "b2World::Step, then the bounce per body. vs Box2D compares with its circles row: a circle "
      "fixture per body in the broad phase, body-body collisions filtered out, as the issue asks. "
      "Bodies without shapes skip the broad phase: what Box2D costs at the least.",
  };
  return section;
}

// --- Barnes-Hut --------------------------------------------------------------------

Section barnes_hut_section(const Plan& plan, Runner& runner, Results& results) {
  Section section;
  section.title = "n-body, Barnes-Hut: steps per second and force error";
  Table table;
  table.columns = {">N",         ">theta",     "precision",  ">threads",    ">steps/s",
                   ">RMS error", ">max error", ">vs direct", ">tree build", "note"};
  nb::BarnesHutOptions base;
  base.softening = peers::kDiskSoftening;

  std::string theta_note;
  for (const std::size_t n : plan.bh_n) {
    runner.status("Barnes-Hut, N = " + count_text(n) + ": the exact forces of " +
                  count_text(std::min(plan.error_sample, n)) + " bodies");
    const peers::NBodySystem system = peers::disk(n, 42);
    const peers::ExactSample exact = peers::exact_sample(system, base, plan.error_sample);
    nb::BarnesHut solver;
    std::vector<double> ax(n);
    std::vector<double> ay(n);
    auto evaluate = [&](const nb::BarnesHutOptions& options) {
      std::fill(ax.begin(), ax.end(), 0.0);
      std::fill(ay.begin(), ay.end(), 0.0);
      solver.accelerations(system.x, system.y, system.m, ax, ay, options);
      return 1.0;
    };

    // At the largest N, the theta that meets the accuracy target too.
    std::vector<double> thetas{calder::kDefaultTheta};
    if (n == plan.bh_n.back()) {
      nb::BarnesHutOptions probe = base;
      double rms = 0.0;
      for (std::size_t k = 0; k <= plan.finer_thetas.size(); ++k) {
        probe.theta = k == 0 ? calder::kDefaultTheta : plan.finer_thetas[k - 1];
        runner.status("Barnes-Hut, N = " + count_text(n) + ": the error at theta " +
                      printf_text("%.2g", probe.theta));
        evaluate(probe);
        rms = peers::force_error(exact, ax, ay).rms;
        if (rms < plan.max_rms) break;
      }
      if (probe.theta != calder::kDefaultTheta) {
        thetas.push_back(probe.theta);
        theta_note = "theta " + printf_text("%.2g", probe.theta) + " at N = " + count_text(n) +
                     ": the largest of the default (" + printf_text("%.2g", calder::kDefaultTheta) +
                     "), " + printf_text("%.2g", plan.finer_thetas[0]) + ", " +
                     printf_text("%.2g", plan.finer_thetas[1]) +
                     ", ... whose RMS error there is below " + error_text(plan.max_rms) +
                     " (the default is not: the error is the truncation of the multipole "
                     "expansion and falls about as theta^5, table below).";
      }
    }

    for (const double theta : thetas) {
      for (const bool float32 : {false, true}) {
        for (int threads : {1, 2}) {
          runner.status("Barnes-Hut, N = " + count_text(n) + ", theta " +
                        printf_text("%.2g", theta) + ", " + precision_name(float32) + ", " +
                        std::to_string(threads) + " thread(s)");
          nb::BarnesHutOptions options = base;
          options.theta = theta;
          options.precision = float32 ? nb::Precision::float32 : nb::Precision::float64;
          options.threads = threads;
          const Measured m = runner.measure([&] { return evaluate(options); });
          BarnesHutRow row{n, theta, float32, threads, m.rate, peers::force_error(exact, ax, ay)};
          results.barnes_hut.push_back(row);
          // Direct summation's steps/s at this N, from its pairs/s in this run.
          std::string vs_direct = "-";
          const auto direct = results.direct.find({results.direct_reference_n, float32, threads});
          if (direct != results.direct.end()) {
            const double direct_steps =
                direct->second / (static_cast<double>(n) * static_cast<double>(n));
            vs_direct = ratio_text(m.rate / direct_steps);
          }
          table.rows.push_back({count_text(n), printf_text("%.2g", theta), precision_name(float32),
                                std::to_string(threads), rate_text(m.rate),
                                error_text(row.error.rms), error_text(row.error.max), vs_direct,
                                percent_text(solver.stats().build_seconds * m.rate),
                                timing_note(m, "step")});
        }
      }
    }
  }
  section.tables.push_back(std::move(table));

  // The error as theta grows, on a disk and on clumps (float64, 2 threads).
  Table thetas;
  thetas.title = "Force error against theta, N = " + count_text(plan.theta_table_n) +
                 " (RMS / max relative error; all bodies against the direct float64 sum):";
  thetas.columns = {">theta", ">disk, softening 1.4", ">clumps, softening 0.05"};
  const std::size_t n = plan.theta_table_n;
  const peers::NBodySystem disk_system = peers::disk(n, 43);
  const peers::NBodySystem clumps = peers::clusters(n, 44);
  nb::BarnesHutOptions disk_options = base;
  nb::BarnesHutOptions clump_options = base;
  clump_options.softening = 0.05;
  runner.status("Barnes-Hut error against theta, N = " + count_text(n));
  const peers::ExactSample disk_exact = peers::exact_sample(disk_system, disk_options, n);
  const peers::ExactSample clump_exact = peers::exact_sample(clumps, clump_options, n);
  std::vector<double> ax(n);
  std::vector<double> ay(n);
  auto error_at = [&](const peers::NBodySystem& s, const peers::ExactSample& exact,
                      nb::BarnesHutOptions options, double theta) {
    options.theta = theta;
    options.threads = 2;
    std::fill(ax.begin(), ax.end(), 0.0);
    std::fill(ay.begin(), ay.end(), 0.0);
    nb::barnes_hut_accelerations(s.x, s.y, s.m, ax, ay, options);
    const peers::ForceError e = peers::force_error(exact, ax, ay);
    return error_text(e.rms) + " / " + error_text(e.max);
  };
  for (const double theta : {0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 1.0}) {
    thetas.rows.push_back({printf_text("%.1f", theta),
                           error_at(disk_system, disk_exact, disk_options, theta),
                           error_at(clumps, clump_exact, clump_options, theta)});
  }
  section.tables.push_back(std::move(thetas));

  section.notes = {
      "One step is one evaluation of all N accelerations (tree build and walk; leaf " +
          std::to_string(nb::BarnesHutOptions{}.leaf_size) + ", group " +
          std::to_string(nb::BarnesHutOptions{}.group_size) +
          ", multipoles to fourth order, the far nodes' field interpolated over each group; " +
          (nb::kernel_target_block() > 0
               ? "float64 re-tests the opened leaves for each run of " +
                     std::to_string(nb::kernel_target_block()) + " targets"
               : std::string("float64 sums the opened leaves for the whole group")) +
          " with these kernels: BarnesHutOptions::target_block) on the uniform disk of the "
          "direct rows, Plummer softening " +
          printf_text("%.2g", peers::kDiskSoftening) + ".",
      "tree build: its share of a step (bounding box, Morton sort, tree, moments; the rest is "
      "the walk). From 2,000 bodies every part of it runs on the threads too: the Morton "
      "sort's slices, about 64 subtrees built side by side, the moments; the top of the tree "
      "and the merge of the subtrees stay serial.",
      "error: |a - a_direct| / |a_direct| against the direct float64 sum, over " +
          count_text(plan.error_sample) +
          " random bodies (all of them when N is smaller); results are bit-identical for any "
          "number of threads, so are their errors.",
      results.direct_reference_n > 0
          ? "vs direct: against direct summation's steps/s at the same N, precision and threads, "
            "estimated as its pairs/s at N = " +
                count_text(results.direct_reference_n) + " in this run / N^2."
          : "vs direct: needs the nbody rows (--only nbody,barnes-hut).",
  };
  if (!theta_note.empty()) section.notes.push_back(theta_note);
  return section;
}

// --- targets -----------------------------------------------------------------------

struct TargetRow {
  std::string target;
  std::string measured;
  std::string result;
};

std::string pass(bool ok) { return ok ? "pass" : "MISS"; }

TargetRow rate_target(const std::string& target, double goal, const std::string& unit,
                      std::optional<double> measured, bool section_ran) {
  if (!section_ran) return {target, "-", "not run"};
  if (!measured) return {target, "-", "not measured (--quick)"};
  return {target, rate_text(*measured) + " " + unit, pass(*measured >= goal)};
}

template <class Map, class Key>
std::optional<double> lookup(const Map& map, const Key& key) {
  const auto it = map.find(key);
  if (it == map.end()) return std::nullopt;
  return it->second;
}

// A rate as a share of its floor measured in the same run.
TargetRow share_target(const std::string& target, double goal, std::optional<double> measured,
                       std::optional<double> floor, bool section_ran) {
  if (!section_ran) return {target, "-", "not run"};
  if (!measured || !floor) return {target, "-", "not measured (--quick)"};
  const double share = *measured / *floor;
  return {target, percent_text(share) + " (" + rate_text(*measured) + " pairs/s)",
          pass(share >= goal)};
}

// The smallest 2-thread / 1-thread ratio among rows with N >= kScalingMinN
// (Barnes-Hut: kScalingMinNBarnesHut).
struct Scaling {
  double ratio = 0.0;
  std::string where;
};

void worst(Scaling& scaling, double one, double two, const std::string& where) {
  if (!(one > 0.0) || !(two > 0.0)) return;
  const double ratio = two / one;
  if (scaling.where.empty() || ratio < scaling.ratio) scaling = {ratio, where};
}

TargetRow scaling_target(const std::string& what, const Scaling& scaling, bool section_ran,
                         double goal = kTargetScaling, std::size_t min_n = kScalingMinN) {
  const std::string target = "2 threads >= " + printf_text("%.3g", goal) +
                             "x 1 thread, N >= " + count_text(min_n) + ": " + what;
  if (!section_ran) return {target, "-", "not run"};
  if (scaling.where.empty()) return {target, "-", "not measured (--quick)"};
  return {target, "lowest " + ratio_text(scaling.ratio) + " (" + scaling.where + ")",
          pass(scaling.ratio >= goal)};
}

Section targets_section(const Plan& plan, const Results& results) {
  Section section;
  section.title = "targets";
  Table table;
  table.columns = {"target", "measured", "result"};
  auto add = [&](const TargetRow& row) {
    table.rows.push_back({row.target, row.measured, row.result});
  };

  for (const bool float32 : {true, false}) {
    const double goal = float32 ? kTargetDirect32 : kTargetDirect64;
    const std::string target = std::string("direct ") + precision_name(float32) +
                               ", N = 16,000, 2 threads: >= " + percent_text(goal) +
                               " of the FMA floor";
    add(share_target(target, goal,
                     lookup(results.direct, std::make_tuple(kTargetDirectN, float32, 2)),
                     lookup(results.direct_floor, std::make_pair(float32, 2)), plan.nbody));
  }
  add(rate_target("movers float32, N = 100,000, 2 threads: >= 2e9 body-steps/s", kTargetMovers32,
                  "body-steps/s", lookup(results.movers, std::make_tuple(kTargetMoversN, 2, 2)),
                  plan.movers));
  add(rate_target("movers float64, N = 100,000, 2 threads: >= 1e9 body-steps/s", kTargetMovers64,
                  "body-steps/s", lookup(results.movers, std::make_tuple(kTargetMoversN, 1, 2)),
                  plan.movers));

  // Movers against the plain SoA loop of the same precision, 2 threads, every N.
  for (int a = 0; a < 3; ++a) {
    const double goal = a == 0 ? 0.5 : 1.0;
    const std::string target =
        "movers " + arithmetic_text(a) +
        " vs the SoA floor, 2 threads, every N: >= " + printf_text("%.2g", goal) + "x";
    if (!plan.movers) {
      add({target, "-", "not run"});
      continue;
    }
    Scaling lowest;
    for (const auto& [key, floor] : results.movers_floor) {
      const auto [n, float32, threads] = key;
      if (threads != 2 || float32 != (a == 2)) continue;
      const auto rate = lookup(results.movers, std::make_tuple(n, a, 2));
      if (rate) worst(lowest, floor, *rate, "N = " + count_text(n));
    }
    if (lowest.where.empty()) {
      add({target, "-", "not measured"});
    } else {
      add({target, "lowest " + ratio_text(lowest.ratio) + " (" + lowest.where + ")",
           pass(lowest.ratio >= goal)});
    }
  }

  // Barnes-Hut: the fastest 2-thread row at 10^6 that meets the accuracy
  // (the target is float64's; float32 is shown beside it).
  for (const bool float32 : {false, true}) {
    const std::string target = std::string("Barnes-Hut ") + precision_name(float32) +
                               ", N = 10^6, 2 threads, RMS error < 1e-3: " +
                               (float32 ? std::string("in the learner's time (no target)")
                                        : ">= " + rate_text(kTargetBarnesHut) +
                                              " in the learner's time (2x issue 9's start)");
    if (!plan.barnes_hut) {
      add({target, "-", "not run"});
      continue;
    }
    const BarnesHutRow* best = nullptr;
    bool measured = false;
    for (const BarnesHutRow& row : results.barnes_hut) {
      if (row.n != kTargetBarnesHutN || row.float32 != float32 || row.threads != 2) continue;
      measured = true;
      if (row.error.rms < plan.max_rms && (best == nullptr || row.rate > best->rate)) best = &row;
    }
    if (!measured) {
      add({target, "-", "not measured (--quick)"});
    } else if (best == nullptr) {
      add({target, "no theta tried meets the RMS error", "MISS"});
    } else {
      // The learner's time for the N^2 pairs of a step at 10^6, from its
      // pairs/s at the largest N of this run, over Barnes-Hut's step.
      const auto learner = lookup(results.learner, results.direct_reference_n);
      const std::string at = " steps/s at theta " + printf_text("%.2g", best->theta) + " (RMS " +
                             error_text(best->error.rms) + ")";
      if (!learner) {
        add({target, rate_text(best->rate) + at + "; the learner's time needs the nbody rows",
             "-"});
      } else {
        const double in_learner_time = best->rate * static_cast<double>(kTargetBarnesHutN) *
                                       static_cast<double>(kTargetBarnesHutN) / *learner;
        add({target,
             rate_text(in_learner_time) + " (" +
                 printf_text("%.2f", in_learner_time / (kTargetBarnesHut / 2)) +
                 "x issue 9's start): " + rate_text(best->rate) + at,
             float32 ? "-" : pass(in_learner_time >= kTargetBarnesHut)});
      }
    }
  }

  Scaling direct;
  for (const auto& [key, two] : results.direct) {
    const auto [n, float32, threads] = key;
    if (threads != 2 || n < kScalingMinN) continue;
    const auto one = lookup(results.direct, std::make_tuple(n, float32, 1));
    if (one)
      worst(direct, *one, two, std::string(precision_name(float32)) + ", N = " + count_text(n));
  }
  add(scaling_target("direct", direct, plan.nbody));
  Scaling mover_scaling;
  for (const auto& [key, two] : results.movers) {
    const auto [n, arithmetic, threads] = key;
    if (threads != 2 || n < kScalingMinN) continue;
    const auto one = lookup(results.movers, std::make_tuple(n, arithmetic, 1));
    if (one) {
      worst(mover_scaling, *one, two, arithmetic_text(arithmetic) + ", N = " + count_text(n));
    }
  }
  add(scaling_target("movers", mover_scaling, plan.movers));
  Scaling tree;
  for (const BarnesHutRow& two : results.barnes_hut) {
    if (two.threads != 2 || two.n < kScalingMinNBarnesHut) continue;
    for (const BarnesHutRow& one : results.barnes_hut) {
      if (one.threads == 1 && one.n == two.n && one.theta == two.theta &&
          one.float32 == two.float32) {
        worst(tree, one.rate, two.rate,
              std::string(precision_name(two.float32)) + ", N = " + count_text(two.n) + ", theta " +
                  printf_text("%.2g", two.theta));
      }
    }
  }
  add(scaling_target("Barnes-Hut", tree, plan.barnes_hut, kTargetScalingBarnesHut,
                     kScalingMinNBarnesHut));

  section.tables.push_back(std::move(table));
  if (nb::max_threads() < 2) {
    section.notes.push_back("this machine runs 1 thread at a time: the 2-thread rows share a core");
  }
  return section;
}

// --- the machine -------------------------------------------------------------------

std::string cpu_model() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line)) {
    if (line.rfind("model name", 0) == 0) {
      const std::size_t colon = line.find(':');
      if (colon == std::string::npos) break;
      std::string model = line.substr(colon + 1);
      model.erase(0, model.find_first_not_of(" \t"));
      return model;
    }
  }
  return "unknown CPU";
}

std::string load_average() {
  std::ifstream loadavg("/proc/loadavg");
  std::string first;
  if (loadavg >> first) return first;
  return "unknown";
}

// The CPU time of the whole machine (/proc/stat) and of this process, so
// that a run can say how much other processes took: they drag the 2-thread
// rows down.
struct CpuTimes {
  double machine_busy = -1.0;  // seconds, all CPUs; < 0 when unknown
  double machine_total = 0.0;
  double own = 0.0;  // this process, all threads
};

CpuTimes cpu_times() {
  CpuTimes times;
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) == 0) {
    times.own = static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
  }
  std::ifstream stat("/proc/stat");
  std::string name;
  if (!(stat >> name) || name != "cpu") return times;
  std::vector<double> ticks;  // user nice system idle iowait irq softirq steal
  double value = 0.0;
  while (ticks.size() < 8 && stat >> value) ticks.push_back(value);
  const long hz = sysconf(_SC_CLK_TCK);
  if (ticks.size() < 8 || hz <= 0) return times;
  double total = 0.0;
  for (const double t : ticks) total += t;
  times.machine_total = total / static_cast<double>(hz);
  times.machine_busy = (total - ticks[3] - ticks[4]) / static_cast<double>(hz);
  return times;
}

// The share of all CPUs that other processes used between two samples, e.g. "3%".
std::string others_share(const CpuTimes& before, const CpuTimes& after) {
  if (before.machine_busy < 0.0 || after.machine_busy < 0.0) return "";
  const double total = after.machine_total - before.machine_total;
  if (total <= 0.0) return "";
  const double others = (after.machine_busy - before.machine_busy) - (after.own - before.own);
  return printf_text("%.0f", std::max(0.0, 100.0 * others / total)) + "%";
}

// How busy the CPUs are over the next `seconds`, e.g. "2% busy over 0.5 s".
std::string busy_cpus(double seconds) {
  const CpuTimes before = cpu_times();
  std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
  const std::string share = others_share(before, cpu_times());
  if (share.empty()) return "";
  return share + " busy over " + printf_text("%g", seconds) + " s";
}

std::string compiler() {
#if defined(__clang__)
  return std::string("Clang ") + __clang_version__;
#elif defined(__GNUC__)
  return std::string("GCC ") + __VERSION__;
#else
  return "unknown compiler";
#endif
}

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buffer[32];
  std::strftime(buffer, sizeof buffer, "%Y-%m-%d %H:%M UTC", &tm);
  return buffer;
}

std::vector<std::pair<std::string, std::string>> machine(const Plan& plan) {
  std::string kernels =
      std::string("n-body ") + nb::kernel_name() + ", movers " + bulk::kernel_name();
  if (const char* forced = std::getenv("CALDER_KERNELS")) {
    kernels += std::string(" (CALDER_KERNELS=") + forced + ")";
  }
  const std::string busy = busy_cpus(plan.quick ? 0.1 : 0.5);
  std::string build = CALDER_BUILD_TYPE;
#if defined(CALDER_BENCH_PORTABLE)
  build += ", CALDER_PORTABLE=ON";
#endif
  return {
      {"CPU",
       cpu_model() + ", " + std::to_string(std::thread::hardware_concurrency()) + " logical cores"},
      {"kernels", kernels},
      {"threads", "OpenMP max threads " + std::to_string(nb::max_threads()) + " (n-body), " +
                      std::to_string(bulk::max_threads()) + " (movers)"},
      {"compiler", compiler() + ", build type " + build},
      {"date", utc_now() + "; at the start: " + (busy.empty() ? "" : "CPUs " + busy + ", ") +
                   "load average " + load_average()},
      {"timing", "median of " + std::to_string(plan.repetitions) + " repetitions of at least " +
                     printf_text("%g", plan.min_time) + " s each, after one warm-up; wall clock" +
                     (plan.quick ? " (--quick: tiny sizes, rough figures)" : "")},
  };
}

// --- flags -------------------------------------------------------------------------

void parse_only(const std::string& text, Plan& plan) {
  plan.nbody = plan.movers = plan.barnes_hut = false;
  std::stringstream list(text);
  std::string name;
  bool any = false;
  while (std::getline(list, name, ',')) {
    if (name == "nbody") {
      plan.nbody = true;
    } else if (name == "movers") {
      plan.movers = true;
    } else if (name == "barnes-hut") {
      plan.barnes_hut = true;
    } else {
      throw InputError("--only: expected a list of nbody, movers, barnes-hut, got '" + text + "'");
    }
    any = true;
  }
  if (!any) throw InputError("--only: expected a list of nbody, movers, barnes-hut, got ''");
}

double parse_min_time(const std::string& text) {
  const std::optional<double> value = to_double(text);
  if (!value || !(*value > 0.0 && *value <= 60.0)) {
    throw InputError("--min-time: expected a number of seconds in (0, 60], got '" + text + "'");
  }
  return *value;
}

}  // namespace

void add_bench_flags(CLI::App& bench, BenchOptions& options) {
  bench
      .add_option("--only", options.only,
                  "Sections to run, comma-separated: nbody, movers, barnes-hut (default: all)")
      ->type_name("LIST");
  bench.add_flag("--quick", options.quick,
                 "Tiny sizes and times: a few seconds, rough figures (a smoke test)");
  bench.add_option("--format", options.format, "text (default) or markdown (GitHub tables)")
      ->type_name("FORMAT");
  bench
      .add_option("--output", options.output,
                  "Write the tables to FILE (atomically) instead of standard output")
      ->type_name("FILE");
  bench
      .add_option("--min-time", options.min_time,
                  "Seconds per repetition, in (0, 60] (default 0.5; --quick 0.01)")
      ->type_name("SECONDS");
  bench.footer(
      "The full run takes a few minutes; each figure is the median of several repetitions, "
      "after one warm-up. Progress lines go to standard error when it is a terminal.\n"
      "Exit status: 0 success (whether or not the targets are met), 1 a write failed, 2 bad "
      "usage or an output path that can't be written.\n");
}

void bench_command(const BenchOptions& options, std::ostream& out, std::ostream& err) {
  Plan plan = options.quick ? quick_plan() : Plan{};
  if (options.only) parse_only(*options.only, plan);
  if (options.min_time) plan.min_time = parse_min_time(*options.min_time);
  const std::string format = options.format.value_or("text");
  if (format != "text" && format != "markdown") {
    throw InputError("--format: expected text or markdown, got '" + format + "'");
  }
  const bool markdown = format == "markdown";
  // Before minutes of measuring: a path that can't be written fails now.
  std::optional<OutputFile> file;
  if (options.output && *options.output != "-") file.emplace(*options.output);

  auto header = machine(plan);  // the date and the load before we add ours
  const CpuTimes start = cpu_times();
  Runner runner(plan, err);
  Results results;
  std::vector<Section> sections;
  if (plan.nbody) sections.push_back(nbody_section(plan, runner, results));
  if (plan.movers) sections.push_back(movers_section(plan, runner, results));
  if (plan.barnes_hut) sections.push_back(barnes_hut_section(plan, runner, results));
  sections.push_back(targets_section(plan, results));
  if (const std::string others = others_share(start, cpu_times()); !others.empty()) {
    header.emplace_back("others", "other processes took " + others +
                                      " of the CPUs during the run (0% for clean figures)");
  }

  std::ostringstream report;
  if (markdown) {
    report << "## Machine\n\n";
    for (const auto& [key, value] : header) report << "- " << key << ": " << value << '\n';
  } else {
    report << "calder-bench\n";
    for (const auto& [key, value] : header) {
      report << "  " << key << std::string(10 - std::min<std::size_t>(key.size(), 9), ' ') << value
             << '\n';
    }
  }
  report << '\n';
  for (const Section& section : sections) print_section(report, section, markdown);

  std::string text = report.str();
  while (text.size() >= 2 && text[text.size() - 1] == '\n' && text[text.size() - 2] == '\n') {
    text.pop_back();
  }
  if (file) {
    file->stream() << text;
    file->commit();
  } else {
    out << text;
  }
}

}  // namespace calder::app
