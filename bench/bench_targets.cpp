// SPDX-License-Identifier: MIT
// calder-bench: the targets, pass or miss, from the results of the run.
#include "bench_parts.hpp"

namespace calder::app::bench {

namespace {

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

// Direct's share of the FMA floor and calder::bulk's rates.
void rate_targets(const Plan& plan, const Results& results,
                  const std::function<void(const TargetRow&)>& add) {
  for (const bool float32 : {true, false}) {
    const double goal = float32 ? kTargetDirect32 : kTargetDirect64;
    const std::string target = std::string("direct ") + precision_name(float32) +
                               ", N = 16,000, 2 threads: >= " + percent_text(goal) +
                               " of the FMA floor";
    add(share_target(target, goal,
                     lookup(results.direct, std::make_tuple(kTargetDirectN, float32, 2)),
                     lookup(results.direct_floor, std::make_pair(float32, 2)), plan.nbody));
  }
  add(rate_target("calder::bulk float32, N = 100,000, 2 threads: >= 2e9 body-steps/s",
                  kTargetBulk32, "body-steps/s",
                  lookup(results.bulk, std::make_tuple(kTargetBulkN, 2, 2)), plan.bulk));
  add(rate_target("calder::bulk float64, N = 100,000, 2 threads: >= 1e9 body-steps/s",
                  kTargetBulk64, "body-steps/s",
                  lookup(results.bulk, std::make_tuple(kTargetBulkN, 1, 2)), plan.bulk));
}

// calder::bulk against the plain SoA loop of the same precision, 2 threads, every N.
void floor_targets(const Plan& plan, const Results& results,
                   const std::function<void(const TargetRow&)>& add) {
  for (int a = 0; a < 3; ++a) {
    const double goal = a == 0 ? 0.5 : 1.0;
    const std::string target =
        "calder::bulk " + arithmetic_text(a) +
        " vs the SoA floor, 2 threads, every N: >= " + printf_text("%.2g", goal) + "x";
    if (!plan.bulk) {
      add({target, "-", "not run"});
      continue;
    }
    Scaling lowest;
    for (const auto& [key, floor] : results.bulk_floor) {
      const auto [n, float32, threads] = key;
      if (threads != 2 || float32 != (a == 2)) continue;
      const auto rate = lookup(results.bulk, std::make_tuple(n, a, 2));
      if (rate) worst(lowest, floor, *rate, "N = " + count_text(n));
    }
    if (lowest.where.empty()) {
      add({target, "-", "not measured"});
    } else {
      add({target, "lowest " + ratio_text(lowest.ratio) + " (" + lowest.where + ")",
           pass(lowest.ratio >= goal)});
    }
  }
}

// Barnes-Hut: the fastest 2-thread row at 10^6 that meets the accuracy
// (the target is float64's; float32 is shown beside it).
void barnes_hut_targets(const Plan& plan, const Results& results,
                        const std::function<void(const TargetRow&)>& add) {
  for (const bool float32 : {false, true}) {
    const std::string target = std::string("Barnes-Hut ") + precision_name(float32) +
                               ", N = 10^6, 2 threads, RMS error < 1e-3: " +
                               (float32 ? std::string("in the learner's time (no target)")
                                        : ">= " + rate_text(kTargetBarnesHut) +
                                              " in the learner's time (2x the baseline)");
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
                 "x the baseline): " + rate_text(best->rate) + at,
             float32 ? "-" : pass(in_learner_time >= kTargetBarnesHut)});
      }
    }
  }
}

// 2 threads against 1, in each section.
void scaling_targets(const Plan& plan, const Results& results,
                     const std::function<void(const TargetRow&)>& add) {
  Scaling direct;
  for (const auto& [key, two] : results.direct) {
    const auto [n, float32, threads] = key;
    if (threads != 2 || n < kScalingMinN) continue;
    const auto one = lookup(results.direct, std::make_tuple(n, float32, 1));
    if (one)
      worst(direct, *one, two, std::string(precision_name(float32)) + ", N = " + count_text(n));
  }
  add(scaling_target("direct", direct, plan.nbody));
  Scaling bulk_scaling;
  for (const auto& [key, two] : results.bulk) {
    const auto [n, arithmetic, threads] = key;
    if (threads != 2 || n < kScalingMinN) continue;
    const auto one = lookup(results.bulk, std::make_tuple(n, arithmetic, 1));
    if (one) {
      worst(bulk_scaling, *one, two, arithmetic_text(arithmetic) + ", N = " + count_text(n));
    }
  }
  add(scaling_target("calder::bulk", bulk_scaling, plan.bulk));
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
}

}  // namespace

Section targets_section(const Plan& plan, const Results& results) {
  Section section;
  section.title = "targets";
  Table table;
  table.columns = {"target", "measured", "result"};
  const std::function<void(const TargetRow&)> add = [&](const TargetRow& row) {
    table.rows.push_back({row.target, row.measured, row.result});
  };
  rate_targets(plan, results, add);
  floor_targets(plan, results, add);
  barnes_hut_targets(plan, results, add);
  scaling_targets(plan, results, add);
  section.tables.push_back(std::move(table));
  if (nb::max_threads() < 2) {
    section.notes.push_back("this machine runs 1 thread at a time: the 2-thread rows share a core");
  }
  return section;
}

}  // namespace calder::app::bench
