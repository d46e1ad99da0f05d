// SPDX-License-Identifier: MIT
// bench_ias15: the classic problems under ias15 (tolerance 1e-9), each run
// whole: wall time, and as counters the internal steps, the force
// evaluations and the relative energy error at the end.
//
//   Pythagorean    Burrau's three bodies to t = 70 (700 frames of 0.1)
//   FigureEight    the figure-eight choreography, ten periods (1200 frames)
//   Kepler09       a Kepler orbit of e = 0.9, 1,000 orbits, one frame per orbit
//
// REBOUND's IAS15 on the same problems, in the same run: bench/rebound_compare.sh
// (its figures in bench/results/rebound-ias15.md).
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>

#include "calder/calder.hpp"

namespace {

void report(benchmark::State& state, const calder::World& world, double e0) {
  const calder::AdaptiveStats& s = world.adaptive_stats();
  state.counters["steps"] = static_cast<double>(s.steps);
  state.counters["force_evaluations"] = static_cast<double>(s.force_evaluations);
  state.counters["energy_error"] = std::fabs((calder::total_energy(world) - e0) / e0);
}

void run_scene(benchmark::State& state, const std::string& name) {
  for (auto _ : state) {
    calder::Simulation sim(calder::builtin_scene(name));
    const double e0 = calder::total_energy(sim.world());
    while (sim.frame() < sim.scene().frames) sim.step();
    state.PauseTiming();
    report(state, sim.world(), e0);
    state.ResumeTiming();
  }
}

void Pythagorean(benchmark::State& state) { run_scene(state, "pythagorean"); }
void FigureEight(benchmark::State& state) { run_scene(state, "figure-eight"); }

void Kepler09(benchmark::State& state) {
  const double e = 0.9;
  for (auto _ : state) {
    calder::World world({.width = 10,
                         .height = 10,
                         .dt = 2 * 3.141592653589793,
                         .integrator = calder::Integrator::ias15});
    world.add(calder::Attractor{
        .position = {0, 0}, .mass = 1.0, .law = calder::AttractionLaw::newtonian()});
    world.add_body({.position = {1 - e, 0}, .velocity = {0, std::sqrt((1 + e) / (1 - e))}});
    const double e0 = calder::total_energy(world);
    world.step(static_cast<int>(state.range(0)));
    state.PauseTiming();
    report(state, world, e0);
    state.ResumeTiming();
  }
}

BENCHMARK(Pythagorean)->Unit(benchmark::kMillisecond);
BENCHMARK(FigureEight)->Unit(benchmark::kMillisecond);
BENCHMARK(Kepler09)->Arg(1000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
