// SPDX-License-Identifier: MIT
// calder-bench: direct n-body summation against the learner and the FMA floor.
#include "bench_parts.hpp"
#include "peers/fma_peak.hpp"
#include "peers/learner_nbody.hpp"
#include "peers/nbody_systems.hpp"

namespace calder::app::bench {

namespace {

// One run of the section: its table and the floor it measured.
struct DirectRun {
  const Plan& plan;
  Runner& runner;
  Results& results;
  Table table;
  peers::PairFloor pair_floor;
  double peak[3] = {0.0, 0.0, 0.0};  // flop/s by threads
  bool sliced = false;               // the learner was timed on slices of its loop
};

void floor_rows(DirectRun& run) {
  const Plan& plan = run.plan;
  Runner& runner = run.runner;
  Results& results = run.results;
  Table& table = run.table;
  peers::PairFloor& pair_floor = run.pair_floor;
  double* peak = run.peak;
  // The floor: the FMA peak at the kernels' vector width.
  pair_floor = peers::pair_floor(nb::kernel_name());
  for (int threads : {1, 2}) {
    runner.status("FMA peak, " + std::to_string(pair_floor.bits) + "-bit, " +
                  std::to_string(threads) + " thread(s)");
    peak[threads] =
        runner.measure([&] { return peers::fma_flops(pair_floor.bits, threads, plan.fma_rounds); })
            .rate;
  }

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
}

// The learner, on slices of its double loop when a whole one is long: its rate.
double learner_row(DirectRun& run, const peers::NBodySystem& system, std::size_t n) {
  const Plan& plan = run.plan;
  Runner& runner = run.runner;
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
    run.sliced = true;
  }
  run.table.rows.push_back({"learner: book ex. 2.9 in plain C++", count_text(n), "float64", "1",
                            rate_text(learner_rate.rate), "1x", "", learner_note});
  run.results.learner[n] = learner_rate.rate;

  return learner_rate.rate;
}

void calder_rows(DirectRun& run, const peers::NBodySystem& system, std::size_t n,
                 double learner_rate) {
  Runner& runner = run.runner;
  const double pairs = static_cast<double>(n) * static_cast<double>(n);
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
      run.results.direct[{n, float32, threads}] = m.rate;
      const double floor_rate = float32 ? run.pair_floor.pairs32(run.peak[threads])
                                        : run.pair_floor.pairs64(run.peak[threads]);
      run.table.rows.push_back({"calder direct", count_text(n), precision_name(float32),
                                std::to_string(threads), rate_text(m.rate),
                                ratio_text(m.rate / learner_rate),
                                percent_text(m.rate / floor_rate), ""});
    }
  }
}

// Like for like with the learner, at the largest N: the book's clamp
// (a square root and a division per pair; the floor counts Plummer's flops).
void clamp_rows(DirectRun& run, const peers::NBodySystem& system, std::size_t n,
                double learner_rate) {
  Runner& runner = run.runner;
  const double pairs = static_cast<double>(n) * static_cast<double>(n);
  std::vector<double> ax(n);
  std::vector<double> ay(n);
  {
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
        run.table.rows.push_back({"calder direct, the book's clamp", count_text(n),
                                  precision_name(float32), std::to_string(threads),
                                  rate_text(m.rate), ratio_text(m.rate / learner_rate), "-", ""});
      }
    }
  }
}

std::vector<std::string> direct_notes(const DirectRun& run) {
  const peers::PairFloor& pair_floor = run.pair_floor;
  const double* peak = run.peak;
  const bool sliced = run.sliced;
  return {
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
}

}  // namespace

Section nbody_section(const Plan& plan, Runner& runner, Results& results) {
  Section section;
  section.title = "n-body, direct summation: pair interactions per second";
  DirectRun run{plan, runner, results, {}, {}};
  floor_rows(run);
  for (const std::size_t n : plan.direct_n) {
    const peers::NBodySystem system = peers::disk(n, 42);
    const double learner_rate = learner_row(run, system, n);
    calder_rows(run, system, n, learner_rate);
    if (n == plan.direct_n.back()) clamp_rows(run, system, n, learner_rate);
    results.direct_reference_n = std::max(results.direct_reference_n, n);
  }
  section.tables.push_back(std::move(run.table));
  section.notes = direct_notes(run);
  return section;
}

}  // namespace calder::app::bench
