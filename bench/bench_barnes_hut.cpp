// SPDX-License-Identifier: MIT
// calder-bench: Barnes-Hut's steps per second and force error.
#include "bench_parts.hpp"
#include "peers/nbody_systems.hpp"

namespace calder::app::bench {

namespace {

// One size's measurement: its bodies, exact sample, solver and output.
struct BarnesHutRun {
  const Plan& plan;
  Runner& runner;
  std::size_t n;
  const peers::NBodySystem& system;
  const peers::ExactSample& exact;
  nb::BarnesHut solver;
  std::vector<double> ax;
  std::vector<double> ay;
  double evaluate(const nb::BarnesHutOptions& options) {
    std::fill(ax.begin(), ax.end(), 0.0);
    std::fill(ay.begin(), ay.end(), 0.0);
    solver.accelerations(system.x, system.y, system.m, ax, ay, options);
    return 1.0;
  }
};

// The default theta, and at the largest N the largest finer one that meets
// the accuracy target when the default does not (with a note saying so).
std::vector<double> thetas_to_run(BarnesHutRun& run, const nb::BarnesHutOptions& base,
                                  std::string& theta_note) {
  const Plan& plan = run.plan;
  const std::size_t n = run.n;
  std::vector<double> thetas{calder::kDefaultTheta};
  if (n != plan.bh_n.back()) return thetas;
  nb::BarnesHutOptions probe = base;
  for (std::size_t k = 0; k <= plan.finer_thetas.size(); ++k) {
    probe.theta = k == 0 ? calder::kDefaultTheta : plan.finer_thetas[k - 1];
    run.runner.status("Barnes-Hut, N = " + count_text(n) + ": the error at theta " +
                      printf_text("%.2g", probe.theta));
    run.evaluate(probe);
    if (peers::force_error(run.exact, run.ax, run.ay).rms < plan.max_rms) break;
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
  return thetas;
}

void rate_rows(BarnesHutRun& run, const std::vector<double>& thetas,
               const nb::BarnesHutOptions& base, Results& results, Table& table) {
  Runner& runner = run.runner;
  const std::size_t n = run.n;
  for (const double theta : thetas) {
    for (const bool float32 : {false, true}) {
      for (int threads : {1, 2}) {
        runner.status("Barnes-Hut, N = " + count_text(n) + ", theta " + printf_text("%.2g", theta) +
                      ", " + precision_name(float32) + ", " + std::to_string(threads) +
                      " thread(s)");
        nb::BarnesHutOptions options = base;
        options.theta = theta;
        options.precision = float32 ? nb::Precision::float32 : nb::Precision::float64;
        options.threads = threads;
        const Measured m = runner.measure([&] { return run.evaluate(options); });
        BarnesHutRow row{n,       theta,  float32,
                         threads, m.rate, peers::force_error(run.exact, run.ax, run.ay)};
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
                              std::to_string(threads), rate_text(m.rate), error_text(row.error.rms),
                              error_text(row.error.max), vs_direct,
                              percent_text(run.solver.stats().build_seconds * m.rate),
                              timing_note(m, "step")});
      }
    }
  }
}

// The error as theta grows, on a disk and on clumps (float64, 2 threads).
Table theta_table(const Plan& plan, Runner& runner, const nb::BarnesHutOptions& base) {
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
  return thetas;
}

std::vector<std::string> barnes_hut_notes(const Plan& plan, const Results& results) {
  return {
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
      "the walk). From 2,000 bodies all of it runs in one parallel region: the Morton codes "
      "and the sort's passes over slices, its ranges and about 256 subtrees shared out by "
      "size, the subtrees' nodes and moments; only the top of the tree is built serially.",
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
}

}  // namespace

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
    BarnesHutRun run{
        plan, runner, n, system, exact, {}, std::vector<double>(n), std::vector<double>(n)};
    rate_rows(run, thetas_to_run(run, base, theta_note), base, results, table);
  }
  section.tables.push_back(std::move(table));
  section.tables.push_back(theta_table(plan, runner, base));
  section.notes = barnes_hut_notes(plan, results);
  if (!theta_note.empty()) section.notes.push_back(theta_note);
  return section;
}

}  // namespace calder::app::bench
