// SPDX-License-Identifier: MIT
// calder-bench: what to measure, and the flags that change it.
#include "bench_parts.hpp"
#include "errors.hpp"
#include "parse.hpp"

namespace calder::app::bench {

Plan quick_plan() {
  Plan plan;
  plan.quick = true;
  plan.direct_n = {500, 2000};
  plan.bulk_n = {1000, 10000};
  plan.bh_n = {2000, 10000};
  plan.theta_table_n = 2000;
  plan.error_sample = 200;
  plan.min_time = 0.01;
  plan.repetitions = 3;
  plan.slow_budget = 0.2;
  plan.fma_rounds = 200'000;
  plan.learner_slice_pairs = 100'000;
  plan.scaling_direct32_n = {2000};
  plan.scaling_direct64_n = {2000};
  plan.scaling_bh64_n = {10000};
  plan.scaling_bh32_n = {10000};
  plan.scaling_rain_n = {10000};
  return plan;
}

// The arithmetics in calder::kArithmeticNames' order: book, float64, float32.
std::string arithmetic_text(int a) {
  return std::string(kArithmeticNames[static_cast<std::size_t>(a)].name);
}

void parse_only(const std::string& text, Plan& plan) {
  plan.nbody = plan.bulk = plan.barnes_hut = plan.scaling = false;
  const std::string expected = "--only: expected a list of nbody, bulk, barnes-hut, scaling, got '";
  std::stringstream list(text);
  std::string name;
  bool any = false;
  while (std::getline(list, name, ',')) {
    if (name == "nbody") {
      plan.nbody = true;
    } else if (name == "bulk" || name == "movers") {  // movers: the section's former name
      plan.bulk = true;
    } else if (name == "barnes-hut") {
      plan.barnes_hut = true;
    } else if (name == "scaling") {
      plan.scaling = true;
    } else {
      throw InputError(expected + text + "'");
    }
    any = true;
  }
  if (!any) throw InputError(expected + "'");
}

std::vector<int> parse_threads(const std::string& text) {
  std::vector<int> threads;
  std::stringstream list(text);
  std::string item;
  while (std::getline(list, item, ',')) {
    const std::optional<double> value = to_double(item);
    if (!value || *value != std::floor(*value) || *value < 1.0 || *value > 1024.0) {
      throw InputError(
          "--threads: expected a list of thread counts in [1, 1024], e.g. 1,2,4,8,16, "
          "got '" +
          text + "'");
    }
    threads.push_back(static_cast<int>(*value));
  }
  if (threads.empty()) throw InputError("--threads: expected a list of thread counts, got ''");
  std::sort(threads.begin(), threads.end());
  threads.erase(std::unique(threads.begin(), threads.end()), threads.end());
  return threads;
}

double parse_min_time(const std::string& text) {
  const std::optional<double> value = to_double(text);
  if (!value || !(*value > 0.0 && *value <= 60.0)) {
    throw InputError("--min-time: expected a number of seconds in (0, 60], got '" + text + "'");
  }
  return *value;
}

}  // namespace calder::app::bench
