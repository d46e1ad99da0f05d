// SPDX-License-Identifier: MIT
// calder-bench: how each workload scales with the thread count (--threads):
// rate, speedup, efficiency, the serial share that the speedup implies, and
// the balance of the threads' work from the kernels' own counters (which
// depend on the thread count only, so an oversubscribed run still shows the
// balance of a larger machine).
#include <thread>

#include "bench_parts.hpp"
#include "peers/fma_peak.hpp"
#include "peers/nbody_systems.hpp"
#include "peers/rain_world.hpp"

namespace calder::app::bench {

namespace {

// One measurement: the rate and the work counters' largest imbalance (max /
// mean - 1 over the parallel regions), and Barnes-Hut's build share.
struct Point {
  double rate = 0.0;
  double imbalance = 0.0;
  double build_share = -1.0;  // < 0: not Barnes-Hut
};

// The rows of one workload at each thread count: speedup, efficiency and
// the Karp-Flatt serial share e = (1/S - 1/p) / (1 - 1/p) against the
// smallest count measured (1 thread by default).
void add_rows(Table& table, const std::string& what, std::size_t n, const std::string& unit,
              const std::vector<int>& threads, const std::vector<Point>& points) {
  const double base_rate = points.front().rate;
  const auto base_threads = static_cast<double>(threads.front());
  for (std::size_t k = 0; k < points.size(); ++k) {
    const Point& pt = points[k];
    const double p = static_cast<double>(threads[k]) / base_threads;  // threads relative to base
    const double speedup = pt.rate / base_rate;
    std::string serial = "-";
    if (p > 1.0 && speedup > 0.0) {
      serial = percent_text(std::max(0.0, (1.0 / speedup - 1.0 / p) / (1.0 - 1.0 / p)));
      if (serial == "-") serial = "0%";
    }
    table.rows.push_back({what, n == 0 ? "-" : count_text(n), std::to_string(threads[k]),
                          rate_text(pt.rate) + " " + unit, ratio_text(speedup),
                          percent_text(speedup / p), serial,
                          printf_text("%.1f", 100.0 * pt.imbalance) + "%",
                          pt.build_share < 0.0 ? "" : percent_text(pt.build_share)});
  }
}

double worst(const std::vector<nb::ThreadWork>& work) {
  double most = 0.0;
  for (const nb::ThreadWork& w : work) most = std::max(most, w.imbalance());
  return most;
}

double tile_imbalance() {
  const std::vector<std::size_t> tiles = bulk::last_batch_tiles();
  std::size_t total = 0;
  std::size_t most = 0;
  for (const std::size_t t : tiles) {
    total += t;
    most = std::max(most, t);
  }
  if (total == 0) return 0.0;
  return static_cast<double>(most) * static_cast<double>(tiles.size()) /
             static_cast<double>(total) -
         1.0;
}

void direct_rows(const Plan& plan, Runner& runner, Table& table, bool float32) {
  for (const std::size_t n : float32 ? plan.scaling_direct32_n : plan.scaling_direct64_n) {
    const peers::NBodySystem system = peers::disk(n, 42);
    std::vector<double> ax(n);
    std::vector<double> ay(n);
    std::vector<Point> points;
    for (const int threads : plan.threads) {
      runner.status("scaling: direct " + std::string(precision_name(float32)) +
                    ", N = " + count_text(n) + ", " + std::to_string(threads) + " thread(s)");
      nb::Options options;
      options.softening = peers::kDiskSoftening;
      options.precision = float32 ? nb::Precision::float32 : nb::Precision::float64;
      options.threads = threads;
      nb::DirectStats stats;
      const double pairs = static_cast<double>(n) * static_cast<double>(n);
      const Measured m = runner.measure([&] {
        nb::direct_accelerations(system.x, system.y, system.m, ax, ay, options, &stats);
        return pairs;
      });
      points.push_back({m.rate, worst(stats.work)});
    }
    add_rows(table, std::string("direct, ") + precision_name(float32), n, "pairs/s", plan.threads,
             points);
  }
}

// The machine's own ceiling: FMA chains on every thread, no memory (the
// kernels' vector width). Rows that scale like it lose nothing to calder:
// what it loses is the machine's (shared cores, lower clocks with more cores
// busy).
void ceiling_rows(const Plan& plan, Runner& runner, Table& table) {
  const int bits = peers::pair_floor(nb::kernel_name()).bits;
  std::vector<Point> points;
  for (const int threads : plan.threads) {
    runner.status("scaling: FMA peak, " + std::to_string(bits) + "-bit, " +
                  std::to_string(threads) + " thread(s)");
    const Measured m =
        runner.measure([&] { return peers::fma_flops(bits, threads, plan.fma_rounds); });
    points.push_back({m.rate, 0.0});
  }
  add_rows(table, "ceiling: FMA peak, " + std::to_string(bits) + "-bit", 0, "flops/s", plan.threads,
           points);
}

// Barnes-Hut's build phase by phase at each thread count (the last call's
// wall times): the serial phases' and the parallel ones' share.
struct PhaseRow {
  std::string what;
  std::size_t n = 0;
  int threads = 0;
  std::vector<nb::BarnesHutStats::Phase> phases;
};

Table phase_table(const std::vector<PhaseRow>& rows) {
  Table table;
  if (rows.empty()) return table;
  table.columns = {"workload", ">N", ">threads"};
  for (const nb::BarnesHutStats::Phase& ph : rows.front().phases) {
    table.columns.push_back(std::string(">") + ph.name + (ph.serial ? " (serial)" : ""));
  }
  table.columns.push_back(">build");
  for (const PhaseRow& row : rows) {
    std::vector<std::string> cells{row.what, count_text(row.n), std::to_string(row.threads)};
    double total = 0.0;
    for (const nb::BarnesHutStats::Phase& ph : row.phases) {
      cells.push_back(printf_text("%.2f", 1e3 * ph.seconds) + " ms");
      total += ph.seconds;
    }
    cells.push_back(printf_text("%.2f", 1e3 * total) + " ms");
    table.rows.push_back(std::move(cells));
  }
  return table;
}

void barnes_hut_rows(const Plan& plan, Runner& runner, Table& table, bool float32,
                     std::vector<PhaseRow>& phases) {
  for (const std::size_t n : float32 ? plan.scaling_bh32_n : plan.scaling_bh64_n) {
    const peers::NBodySystem system = peers::disk(n, 42);
    std::vector<double> ax(n);
    std::vector<double> ay(n);
    std::vector<Point> points;
    for (const int threads : plan.threads) {
      runner.status("scaling: Barnes-Hut " + std::string(precision_name(float32)) +
                    ", N = " + count_text(n) + ", " + std::to_string(threads) + " thread(s)");
      nb::BarnesHutOptions options;
      options.softening = peers::kDiskSoftening;
      options.precision = float32 ? nb::Precision::float32 : nb::Precision::float64;
      options.threads = threads;
      nb::BarnesHut solver;
      double build = 0.0;
      double step = 0.0;
      const Measured m = runner.measure([&] {
        solver.accelerations(system.x, system.y, system.m, ax, ay, options);
        build += solver.stats().build_seconds;
        step += solver.stats().build_seconds + solver.stats().walk_seconds;
        return 1.0;
      });
      points.push_back({m.rate, worst(solver.stats().work), build / step});
      phases.push_back({std::string("Barnes-Hut, ") + precision_name(float32), n, threads,
                        solver.stats().build_phases});
    }
    add_rows(table, std::string("Barnes-Hut, ") + precision_name(float32), n, "steps/s",
             plan.threads, points);
  }
}

void rain_rows(const Plan& plan, Runner& runner, Table& table, Arithmetic arithmetic) {
  for (const std::size_t n : plan.scaling_rain_n) {
    const World proto = peers::rain_world(n, arithmetic, 1);
    std::vector<Point> points;
    for (const int threads : plan.threads) {
      runner.status("scaling: rain " + std::string(arithmetic_name(arithmetic)) +
                    ", N = " + count_text(n) + ", " + std::to_string(threads) + " thread(s)");
      World world = proto;
      world.set_threads(threads);
      const Measured m = runner.measure([&] {
        world.step(World::kBatchSteps);
        return static_cast<double>(n) * World::kBatchSteps;
      });
      points.push_back({m.rate, tile_imbalance()});
    }
    add_rows(table, "rain (calder::bulk), " + std::string(arithmetic_name(arithmetic)), n,
             "body-steps/s", plan.threads, points);
  }
}

}  // namespace

Section scaling_section(const Plan& plan, Runner& runner) {
  set_step_batch_backend(bulk::step_batch);  // the kernels, whatever ran before
  Section section;
  section.title = "scaling with the thread count";
  Table table;
  table.columns = {"workload",    ">N",      ">threads",        ">rate",      ">speedup",
                   ">efficiency", ">serial", ">work imbalance", ">tree build"};
  ceiling_rows(plan, runner, table);
  for (const bool float32 : {true, false}) direct_rows(plan, runner, table, float32);
  std::vector<PhaseRow> phases;
  for (const bool float32 : {false, true}) barnes_hut_rows(plan, runner, table, float32, phases);
  for (const Arithmetic a : {Arithmetic::float32, Arithmetic::book}) {
    rain_rows(plan, runner, table, a);
  }
  section.tables.push_back(std::move(table));
  section.tables.push_back(phase_table(phases));
  const unsigned cores = std::thread::hardware_concurrency();
  section.notes = {
      "speedup: the rate over the rate at " + std::to_string(plan.threads.front()) +
          " thread(s); efficiency: speedup / (threads / " + std::to_string(plan.threads.front()) +
          "); serial: the share of the work that would have to run on one thread for that "
          "speedup (Karp-Flatt), a measure of everything that does not scale (serial phases, "
          "waits, memory bandwidth).",
      "work imbalance: the busiest thread's work over the mean, minus one, in the worst parallel "
      "region, from the kernels' own counters (pairs, interactions, bodies, keys, nodes; tiles "
      "for calder::bulk). Work goes to threads by rules of the thread count alone, so this column "
      "is the same on any machine, including rows with more threads than this machine's " +
          std::to_string(cores) +
          " logical cores (whose rates say nothing about a larger machine). Barnes-Hut's walk "
          "splits by the costs its last call measured: the first call (not timed) splits by "
          "bodies.",
      "tree build: Barnes-Hut's share of a step spent building the tree (bounding box, Morton "
      "sort, subtrees, moments); the second table times its phases (the last call's wall "
      "times): a serial phase runs on one thread while the others wait.",
      "ceiling: the machine's FMA peak on every thread, no memory; a workload that scales "
      "like it loses nothing to calder's decomposition (what the ceiling itself loses is "
      "the machine's: lower clocks with more cores busy, cores shared with other machines).",
  };
  return section;
}

}  // namespace calder::app::bench
