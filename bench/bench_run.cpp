// SPDX-License-Identifier: MIT
// bench_run: body-steps per second of running a scene headless, the way
// `calder run` does (Simulation::step once per frame), with no output and
// with the CSV trajectory written to /dev/null. items_per_second is
// body-steps per second.
//
//   Example27/N        example 2.7 with N movers around the book's attractor
//   Example27Csv/N     the same, each frame written as CSV to /dev/null
//   Rain/N             N bodies of random mass under gravity scaled by mass,
//                      falling into a liquid (lower half), bouncing (0.9) off
//                      the walls and the floor on their radius
//   RainCsv/N          the same with CSV output to /dev/null
//   NBodies/N          example 2.9 with N bodies (all pairs: O(N^2) per step)
//   CliRun/F           `calder run example-2.7 --frames F` in process
//                      (10 bodies; F = 100000: 10^6 body-steps)
#include <benchmark/benchmark.h>

#include <cstdint>
#include <fstream>
#include <string>

#include "calder/calder.hpp"

#if CALDER_BENCH_HAS_APP
#include <sstream>
#include <vector>

#include "cli.hpp"
#endif

namespace {

calder::Scene example_2_7(std::size_t movers) {
  calder::Scene scene = calder::builtin_scene("example-2.7");
  scene.bodies.front().count = movers;
  return scene;
}

calder::Scene example_2_9(std::size_t bodies) {
  calder::Scene scene = calder::builtin_scene("example-2.9");
  scene.bodies.front().count = bodies;
  return scene;
}

// Rain: gravity scaled by mass, a liquid over the lower half, bounce on the
// radius off the walls and the floor (example 2.5 with many bodies spread over
// the canvas).
calder::Scene rain(std::size_t drops) {
  calder::Scene scene;
  scene.name = "rain";
  scene.description = "drops falling into a liquid";
  scene.world.width = 640.0;
  scene.world.height = 240.0;
  scene.world.boundary = calder::Boundary::bounce(0.9, true, {.top = false});
  scene.world.seed = 1;
  calder::BodyGroup group;
  group.count = drops;
  group.x = calder::Draw::uniform(0.0, 640.0);
  group.y = calder::Draw::uniform(0.0, 120.0);
  group.mass = calder::Draw::uniform(0.5, 3.0);
  group.radius = {calder::RadiusRule::Kind::per_mass, 2.0};
  scene.bodies.push_back(group);
  scene.fields.push_back({calder::Liquid{.region = {0.0, 120.0, 640.0, 120.0}, .c = 0.1}, {}});
  scene.fields.push_back({calder::Gravity{.g = {0.0, 0.1}, .scale_by_mass = true}, {}});
  return scene;
}

// One frame per iteration, continuing the same simulation.
void run_steps(benchmark::State& state, const calder::Scene& scene) {
  calder::Simulation simulation(scene, 1);
  const auto bodies = static_cast<std::int64_t>(simulation.world().body_count());
  for (auto _ : state) {
    simulation.step();
    benchmark::DoNotOptimize(simulation.world().bodies().x.data());
  }
  state.SetItemsProcessed(state.iterations() * bodies);
}

// One frame and its CSV rows per iteration, to /dev/null.
void run_steps_csv(benchmark::State& state, const calder::Scene& scene) {
  calder::Simulation simulation(scene, 1);
  const auto bodies = static_cast<std::int64_t>(simulation.world().body_count());
  std::ofstream null_out("/dev/null", std::ios::binary);
  calder::TrajectoryWriter writer(null_out);
  writer.write(0, simulation.world());
  for (auto _ : state) {
    simulation.step();
    writer.write(simulation.frame(), simulation.world());
  }
  state.SetItemsProcessed(state.iterations() * bodies);
}

std::size_t arg(const benchmark::State& state) { return static_cast<std::size_t>(state.range(0)); }

void Example27(benchmark::State& state) { run_steps(state, example_2_7(arg(state))); }
void Example27Csv(benchmark::State& state) { run_steps_csv(state, example_2_7(arg(state))); }
void Rain(benchmark::State& state) { run_steps(state, rain(arg(state))); }
void RainCsv(benchmark::State& state) { run_steps_csv(state, rain(arg(state))); }
void NBodies(benchmark::State& state) { run_steps(state, example_2_9(arg(state))); }

BENCHMARK(Example27)->Arg(10)->Arg(1000)->Arg(10000);
BENCHMARK(Example27Csv)->Arg(10)->Arg(1000)->Arg(10000);
BENCHMARK(Rain)->Arg(10)->Arg(1000)->Arg(10000);
BENCHMARK(RainCsv)->Arg(10)->Arg(1000)->Arg(10000);
BENCHMARK(NBodies)->Arg(10)->Arg(100)->Arg(1000);

#if CALDER_BENCH_HAS_APP
// The whole command in process: parse, setup, F frames, the summary.
void CliRun(benchmark::State& state) {
  const std::string frames = std::to_string(state.range(0));
  const std::vector<const char*> argv = {"calder", "run", "example-2.7", "--frames",
                                         frames.c_str()};
  for (auto _ : state) {
    std::ostringstream out;
    std::ostringstream err;
    const int status = calder::app::main(static_cast<int>(argv.size()), argv.data(), out, err);
    if (status != 0) state.SkipWithError(err.str().c_str());
  }
  state.SetItemsProcessed(state.iterations() * state.range(0) * 10);
}
BENCHMARK(CliRun)->Arg(10)->Arg(100000)->Unit(benchmark::kMillisecond);
#endif

}  // namespace

BENCHMARK_MAIN();
