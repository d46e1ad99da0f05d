// SPDX-License-Identifier: MIT
// bench_nbody: mutual attraction of N bodies (calder/nbody.hpp), in pair
// interactions per second (N^2 per evaluation: self pairs included, as the
// kernels compute them) and Barnes-Hut evaluations per second.
//
//   Direct/N/precision/threads/law    direct_accelerations; precision 64 or
//                                     32, law 0 = Plummer (eps 0.5), 1 = the
//                                     book's clamp [5, 25]
//   Learner/N                         the book's example 2.9 written plainly in
//                                     C++ (Mover objects, a heap vector per
//                                     force), one thread, the book's clamp
//                                     (peers/learner_nbody.hpp)
//   FmaPeak/bits/threads              this CPU's FMA throughput: 12 independent
//                                     chains of bits-wide vector FMAs per
//                                     thread, flops/s (an FMA is 2 flops); the
//                                     floor_pairs/s counters divide it by the
//                                     flops of one interaction of each kernel
//                                     (peers/fma_peak.hpp)
//   EstimateRate/bits                 the reciprocal square root estimate's
//                                     issue rate against the FMA's (vs_fma),
//                                     one thread (peers/fma_peak.hpp)
//   BarnesHut/N/precision/threads/theta100/leaf/block
//                                     one evaluation at the default theta,
//                                     calder::kDefaultTheta (and 0.05 either
//                                     side at N = 10^6; the default leaf, and
//                                     16, 24 at 10^5 and 10^6 on 2 threads;
//                                     group 128; block: target_block, -1 the
//                                     kernels' choice, and 0 and 16 at 10^5
//                                     and 10^6, float64, 2 threads) on a
//                                     uniform disk, steps/s, the build's and
//                                     the walk's ms a step, with the RMS and
//                                     max relative error against the direct
//                                     sum (on a sample of 256 bodies for
//                                     N > 10^4), weak_share (the part of the
//                                     squared error from bodies of weak pull,
//                                     below an eighth of the median) and
//                                     abs_err (RMS |error| / median |a|)
//   BarnesHutError/theta*100/clusters the error table at N = 10^4, threads 2
//
// Every rate is wall-clock (UseRealTime): threads count. The context block
// names the kernels (calder::nbody::kernel_name()).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "calder/nbody.hpp"
#include "peers/fma_peak.hpp"
#include "peers/learner_nbody.hpp"
#include "peers/nbody_systems.hpp"

namespace {

namespace nb = calder::nbody;
namespace peers = calder::peers;
using System = peers::NBodySystem;

const System& cached_disk(std::size_t n) {
  static std::map<std::size_t, System> systems;
  auto it = systems.find(n);
  if (it == systems.end()) it = systems.emplace(n, peers::disk(n, 42)).first;
  return it->second;
}

nb::Options options_for(std::int64_t precision, std::int64_t threads, std::int64_t law) {
  nb::Options o;
  o.precision = precision == 32 ? nb::Precision::float32 : nb::Precision::float64;
  o.threads = static_cast<int>(threads);
  if (law == 1) {
    o.law = nb::Law::clamp_distance;
    o.min_distance = 5.0;
    o.max_distance = 25.0;
  } else {
    o.softening = peers::kDiskSoftening;
  }
  return o;
}

// ------------------------------------------------------------------ direct ---

void Direct(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const System& s = cached_disk(n);
  const nb::Options o = options_for(state.range(1), state.range(2), state.range(3));
  std::vector<double> ax(n);
  std::vector<double> ay(n);
  for (auto _ : state) {
    nb::direct_accelerations(s.x, s.y, s.m, ax, ay, o);
    benchmark::DoNotOptimize(ax.data());
    benchmark::ClobberMemory();
  }
  const double pairs = static_cast<double>(n) * static_cast<double>(n);
  state.counters["pairs/s"] = benchmark::Counter(pairs * static_cast<double>(state.iterations()),
                                                 benchmark::Counter::kIsRate);
}
BENCHMARK(Direct)
    ->ArgNames({"N", "precision", "threads", "law"})
    ->ArgsProduct({{1000, 4000, 16000}, {64, 32}, {1, 2}, {0, 1}})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// ----------------------------------------------------------------- learner ---

void Learner(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const System& s = cached_disk(n);
  peers::LearnerNBody learner(s.x, s.y, s.m);
  for (auto _ : state) {
    learner.attract(0, n);
    benchmark::DoNotOptimize(&learner.mover(0));
    learner.clear();
  }
  const double pairs = static_cast<double>(n) * static_cast<double>(n);
  state.counters["pairs/s"] = benchmark::Counter(pairs * static_cast<double>(state.iterations()),
                                                 benchmark::Counter::kIsRate);
}
BENCHMARK(Learner)->ArgName("N")->Arg(1000)->Arg(4000)->UseRealTime()->Unit(
    benchmark::kMillisecond);
BENCHMARK(Learner)->ArgName("N")->Arg(16000)->Iterations(1)->UseRealTime()->Unit(
    benchmark::kMillisecond);

// -------------------------------------------------------------- FMA floor ---

void FmaPeak(benchmark::State& state) {
  const auto bits = static_cast<int>(state.range(0));
  const auto threads = static_cast<int>(state.range(1));
  constexpr std::int64_t kRounds = 20'000'000;
  double flops = 0.0;
  for (auto _ : state) flops += peers::fma_flops(bits, threads, kRounds);
  state.counters["flops/s"] = benchmark::Counter(flops, benchmark::Counter::kIsRate);
  // Per-precision floors: float32 uses bits-wide vectors of floats; float64
  // the same width of doubles (half the lanes, so half the flops/s).
  state.counters["floor32_pairs/s"] =
      benchmark::Counter(flops / peers::kFlopsPerPair32, benchmark::Counter::kIsRate);
  state.counters["floor64_rsqrt_pairs/s"] =
      benchmark::Counter(flops / 2.0 / peers::kFlopsPerPair64Rsqrt, benchmark::Counter::kIsRate);
  state.counters["floor64_sqrt_pairs/s"] =
      benchmark::Counter(flops / 2.0 / peers::kFlopsPerPair64Sqrt, benchmark::Counter::kIsRate);
  state.counters["floor64_float_rsqrt_pairs/s"] = benchmark::Counter(
      flops / 2.0 / peers::kFlopsPerPair64FloatRsqrt, benchmark::Counter::kIsRate);
}
// Registered in main() for the widths this CPU has (peers::fma_widths()).

// The reciprocal square root estimate's issue rate against the FMA's, one
// thread, each timed alone: vs_fma = estimates/s / FMAs/s. A 512-bit
// vrsqrt14ps is three micro-ops, two of them on the FMA port 0, and issues
// every other cycle where FMAs issue twice a cycle (vs_fma about 0.27): in
// the float32 pair kernels, one estimate a vector of pairs costs the time of
// 3 to 4 FMAs.
void EstimateRate(benchmark::State& state) {
  const auto bits = static_cast<int>(state.range(0));
  constexpr std::int64_t kRounds = 20'000'000;
  const double lanes = bits / 32.0;
  double fma_seconds = 0.0;
  double estimate_seconds = 0.0;
  double fmas = 0.0;
  double estimates = 0.0;
  for (auto _ : state) {
    auto start = std::chrono::steady_clock::now();
    fmas += peers::fma_flops(bits, 1, kRounds) / (2.0 * lanes);
    auto middle = std::chrono::steady_clock::now();
    estimates += peers::rsqrt_estimates(bits, kRounds);
    fma_seconds += std::chrono::duration<double>(middle - start).count();
    estimate_seconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - middle).count();
  }
  state.counters["fmas/s"] = fmas / fma_seconds;
  state.counters["estimates/s"] = estimates / estimate_seconds;
  state.counters["vs_fma"] = (estimates / estimate_seconds) / (fmas / fma_seconds);
}

// -------------------------------------------------------------- Barnes-Hut ---

// The exact accelerations of all bodies (N <= 10^4: direct, float64) or of
// 256 random ones (reference_acceleration), computed once per key.
const peers::ExactSample& exact(const System& s, const nb::Options& o, const std::string& key) {
  static std::map<std::string, peers::ExactSample> cache;
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  const std::size_t sample = s.size() <= 10000 ? s.size() : 256;
  return cache.emplace(key, peers::exact_sample(s, o, sample)).first->second;
}

void report_error(benchmark::State& state, const peers::ExactSample& e,
                  const std::vector<double>& ax, const std::vector<double>& ay) {
  const peers::ForceError error = peers::force_error(e, ax, ay);
  state.counters["rms_err"] = error.rms;
  state.counters["max_err"] = error.max;
  state.counters["weak_share"] = error.weak_share;
  state.counters["abs_err"] = error.abs_rms;
}

void BarnesHut(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const System& s = cached_disk(n);
  nb::BarnesHutOptions o;
  static_cast<nb::Options&>(o) = options_for(state.range(1), state.range(2), 0);
  o.theta = static_cast<double>(state.range(3)) / 100.0;
  o.leaf_size = static_cast<int>(state.range(4));
  o.target_block = static_cast<int>(state.range(5));
  const peers::ExactSample& e = exact(s, o, "disk" + std::to_string(n));
  nb::BarnesHut solver;
  std::vector<double> ax(n);
  std::vector<double> ay(n);
  // One step first, untimed: the solver's first step allocates its
  // workspace, which at 10^6 bodies (one to three timed steps) read as up to
  // a tenth of a step.
  solver.accelerations(s.x, s.y, s.m, ax, ay, o);
  double build = 0.0;
  double walk = 0.0;
  for (auto _ : state) {
    std::fill(ax.begin(), ax.end(), 0.0);
    std::fill(ay.begin(), ay.end(), 0.0);
    solver.accelerations(s.x, s.y, s.m, ax, ay, o);
    build += solver.stats().build_seconds;
    walk += solver.stats().walk_seconds;
    benchmark::DoNotOptimize(ax.data());
  }
  state.counters["steps/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["build_ms"] = 1e3 * build / static_cast<double>(state.iterations());
  state.counters["walk_ms"] = 1e3 * walk / static_cast<double>(state.iterations());
  state.counters["pairs/body"] =
      static_cast<double>(solver.stats().interactions) / static_cast<double>(n);
  report_error(state, e, ax, ay);
}
constexpr auto kDefaultTheta100 = static_cast<std::int64_t>(calder::kDefaultTheta * 100.0 + 0.5);
constexpr std::int64_t kDefaultLeaf = nb::BarnesHutOptions{}.leaf_size;
BENCHMARK(BarnesHut)
    ->ArgNames({"N", "precision", "threads", "theta100", "leaf", "block"})
    ->ArgsProduct(
        {{10000, 100000, 1000000}, {64, 32}, {1, 2}, {kDefaultTheta100}, {kDefaultLeaf}, {-1}})
    ->ArgsProduct({{1000000},
                   {64, 32},
                   {1, 2},
                   {kDefaultTheta100 - 5, kDefaultTheta100 + 5},
                   {kDefaultLeaf},
                   {-1}})
    ->ArgsProduct({{100000, 1000000}, {64, 32}, {2}, {kDefaultTheta100}, {16, 24}, {-1}})
    ->ArgsProduct({{100000, 1000000}, {64}, {2}, {kDefaultTheta100}, {kDefaultLeaf}, {0, 16}})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

void BarnesHutError(benchmark::State& state) {
  constexpr std::size_t n = 10000;
  const bool clustered = state.range(1) != 0;
  static const System uniform_disk = peers::disk(n, 43);
  static const System clumps = peers::clusters(n, 44);
  const System& s = clustered ? clumps : uniform_disk;
  nb::BarnesHutOptions o;
  o.softening = clustered ? 0.05 : peers::kDiskSoftening;
  o.theta = static_cast<double>(state.range(0)) / 100.0;
  o.threads = 2;
  const peers::ExactSample& e = exact(s, o, clustered ? "clusters" : "disk");
  std::vector<double> ax(n);
  std::vector<double> ay(n);
  nb::BarnesHut solver;
  for (auto _ : state) {
    std::fill(ax.begin(), ax.end(), 0.0);
    std::fill(ay.begin(), ay.end(), 0.0);
    solver.accelerations(s.x, s.y, s.m, ax, ay, o);
  }
  state.counters["pairs/body"] =
      static_cast<double>(solver.stats().interactions) / static_cast<double>(n);
  report_error(state, e, ax, ay);
}
BENCHMARK(BarnesHutError)
    ->ArgNames({"theta100", "clusters"})
    ->ArgsProduct({{20, 30, 40, 50, 60, 70, 80, 100}, {0, 1}})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  benchmark::internal::Benchmark* fma = benchmark::RegisterBenchmark("FmaPeak", FmaPeak);
  fma->ArgNames({"bits", "threads"})->UseRealTime();
  for (const int bits : peers::fma_widths()) fma->Args({bits, 1})->Args({bits, 2});
#if defined(__x86_64__) || defined(__i386__)
  benchmark::internal::Benchmark* estimate =
      benchmark::RegisterBenchmark("EstimateRate", EstimateRate);
  estimate->ArgNames({"bits"})->UseRealTime();
  for (const int bits : peers::fma_widths()) estimate->Args({bits});
#endif
  benchmark::AddCustomContext("calder_nbody_kernels", nb::kernel_name());
  benchmark::AddCustomContext("calder_nbody_max_threads", std::to_string(nb::max_threads()));
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
