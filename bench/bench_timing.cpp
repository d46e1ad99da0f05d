// SPDX-License-Identifier: MIT
// calder-bench: repetitions, medians and what a row says about its timing.
#include "bench_parts.hpp"

namespace calder::app::bench {

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

Measured Runner::measure(const std::function<double()>& call) {
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

}  // namespace calder::app::bench
