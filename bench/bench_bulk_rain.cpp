// SPDX-License-Identifier: MIT
// bench_bulk: body-steps per second of the rain scene (built-in "rain":
// gravity scaled by mass, quadratic drag, bounce on the radius off the walls
// and the floor, no body-body collisions), canvas grown with N so that the
// density stays that of the scene; items_per_second is body-steps per second.
//
//   Calder/N/arithmetic/threads  World::step(World::kBatchSteps) through
//                                calder::bulk (arithmetic 0 book, 1 float64,
//                                2 float32)
//   CalderPlain/N                the same world stepped by the plain loops
//                                (no kernels: the book's loop in C++)
//   SoaFloor/N/float32/threads   calder::bulk's floor: the rain physics as a plain
//                                SoA loop, -O3 -march=native -ffast-math
//                                (float32 0: double, 1: float; the AVX2 copy
//                                when calder::bulk runs its AVX2 kernels)
//   Box2d/N/kind                 Box2D 2.4 (kind 0 circles with collisions
//                                filtered out, 1 bodies without shapes)
//
// `calder bench` prints the same comparison as one table (docs/PERFORMANCE.md).
#include <benchmark/benchmark.h>

#include <cstdint>
#include <string>

#include "calder/bulk.hpp"
#include "peers/rain_world.hpp"
#include "peers/soa_rain.hpp"

namespace {

void Calder(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  calder::World world = calder::peers::rain_world(
      n, static_cast<calder::Arithmetic>(state.range(1)), static_cast<int>(state.range(2)));
  for (auto _ : state) {
    world.step(calder::World::kBatchSteps);
    benchmark::DoNotOptimize(world.bodies().x.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(n) *
                          calder::World::kBatchSteps);
}

void CalderPlain(benchmark::State& state) {
  calder::set_step_batch_backend(nullptr);
  const auto n = static_cast<std::size_t>(state.range(0));
  calder::World world = calder::peers::rain_world(n);
  for (auto _ : state) {
    world.step();
    benchmark::DoNotOptimize(world.bodies().x.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(n));
  calder::set_step_batch_backend(calder::bulk::step_batch);
}

void SoaFloor(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const bool avx2 = std::string(calder::bulk::kernel_name()) == "avx2+fma";
  calder::peers::SoaRain soa(calder::peers::rain_world(n), state.range(1) != 0, avx2,
                             static_cast<int>(state.range(2)));
  for (auto _ : state) soa.step(calder::World::kBatchSteps);
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(n) *
                          calder::World::kBatchSteps);
  state.SetLabel(soa.flags());
}

void Box2d(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const calder::World world = calder::peers::rain_world(n);
  calder::peers::Box2dRain box2d =
      calder::peers::box2d_rain(world, state.range(1) == 0 ? calder::peers::Box2dBodies::circles
                                                           : calder::peers::Box2dBodies::points);
  for (auto _ : state) box2d.step();
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(n));
}

BENCHMARK(Calder)
    ->ArgNames({"N", "arithmetic", "threads"})
    ->ArgsProduct({{1000, 100000, 1000000}, {0, 1, 2}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(SoaFloor)
    ->ArgNames({"N", "float32", "threads"})
    ->ArgsProduct({{1000, 100000, 1000000}, {0, 1}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(CalderPlain)->ArgNames({"N"})->Arg(1000)->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK(Box2d)
    ->ArgNames({"N", "kind"})
    ->ArgsProduct({{1000, 100000}, {0, 1}})
    ->Args({1000000, 1})
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
