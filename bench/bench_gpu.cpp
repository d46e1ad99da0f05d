// SPDX-License-Identifier: MIT
// bench_gpu: calder::gpu against the CPU in one run.
//
//   GpuDirect/N/precision/law/transfers  direct n-body sums, pairs/s (N^2 per
//                                        evaluation); transfers:1 uploads the
//                                        bodies and downloads the sums each time
//                                        (gpu::direct_accelerations), 0 only runs
//                                        the kernel on bodies already there
//   CpuDirect/N/precision                calder::nbody::direct_accelerations, all cores
//   GpuRain/N/arithmetic/transfers       the rain scene, body-steps/s over batches of
//                                        128 steps; transfers:0 a DeviceWorld (the
//                                        bodies stay on the device), 1 a World whose
//                                        step_batch backend is the GPU's (bodies
//                                        copied there and back each batch)
//   CpuRain/N/arithmetic                 the rain through calder::bulk, all cores
//
// precision / arithmetic: 32 float32, 64 float64; law: 0 Plummer, 1 the book's
// clamp. Counters: up_MB and down_MB per iteration, the bytes copied (the
// context's TransferStats). The device is the first Vulkan device with compute
// (CALDER_GPU_DEVICE=N picks another; `calder devices` lists them).
//
// The review's figures (an H100 or H200; a few minutes): bench/gpu_review.sh,
// which runs
//   bench_gpu --benchmark_filter='Direct/N:(1048576|131072)/|Rain/N:(10000000|1000000)/'
// The small sizes (N:1024, N:10000) run on lavapipe in seconds. GpuRows
// prints calder-bench's GPU rows (bench/gpu_rows.hpp), quick sizes.
#include <benchmark/benchmark.h>

#include <calder/bulk.hpp>
#include <calder/gpu.hpp>
#include <calder/nbody.hpp>
#include <calder/random.hpp>
#include <calder/world.hpp>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <vector>

#include "gpu_rows.hpp"

namespace {

namespace gpu = calder::gpu;
namespace nb = calder::nbody;

gpu::Context& device() {
  static gpu::Context context;
  static const bool said = [] {
    std::fprintf(stderr, "bench_gpu: device %d, %s (%s, Vulkan %s)\n", context.info().index,
                 context.info().name.c_str(), context.info().type.c_str(),
                 context.info().api_version.c_str());
    return true;
  }();
  (void)said;
  return context;
}

struct Disk {
  std::vector<double> x, y, m;
};

// A uniform disk of n bodies of masses in [0.5, 2], built once per size.
const Disk& disk(std::size_t n) {
  static std::map<std::size_t, Disk> cache;
  auto [it, fresh] = cache.try_emplace(n);
  if (fresh) {
    calder::Random rng(42);
    for (std::size_t i = 0; i < n; ++i) {
      const double r = std::sqrt(rng.random(1.0));
      const double angle = rng.random(6.283185307179586);
      it->second.x.push_back(r * std::cos(angle));
      it->second.y.push_back(r * std::sin(angle));
      it->second.m.push_back(rng.random(0.5, 2.0));
    }
  }
  return it->second;
}

nb::Options options_of(std::int64_t precision, std::int64_t law, std::size_t n) {
  nb::Options o;
  o.precision = precision == 64 ? nb::Precision::float64 : nb::Precision::float32;
  o.law = law == 1 ? nb::Law::clamp_distance : nb::Law::plummer;
  // Softening half the mean spacing; clamp bounds at a tenth and twice of it.
  const double spacing = 1.0 / std::sqrt(static_cast<double>(n));
  o.softening = 0.5 * spacing;
  o.min_distance = 0.1 * spacing;
  o.max_distance = 2.0;
  return o;
}

void transfer_counters(benchmark::State& state, const gpu::TransferStats& s) {
  const auto per = static_cast<double>(state.iterations());
  state.counters["up_MB"] = static_cast<double>(s.upload_bytes) / per / 1e6;
  state.counters["down_MB"] = static_cast<double>(s.download_bytes) / per / 1e6;
}

void GpuDirect(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const Disk& d = disk(n);
  const nb::Options o = options_of(state.range(1), state.range(2), n);
  if (o.precision == nb::Precision::float64 && !device().info().float64) {
    state.SkipWithError("the device has no shaderFloat64");
    return;
  }
  std::vector<double> ax(n), ay(n);
  gpu::DirectSums sums(device());
  sums.upload(d.x, d.y, d.m, o);
  sums.evaluate();  // warm: the pipeline is built
  device().reset_stats();
  for (auto _ : state) {
    if (state.range(3) != 0) {
      gpu::direct_accelerations(device(), d.x, d.y, d.m, ax, ay, o);
    } else {
      sums.evaluate();
    }
  }
  const double pairs = static_cast<double>(n) * static_cast<double>(n);
  state.counters["pairs/s"] = benchmark::Counter(pairs * static_cast<double>(state.iterations()),
                                                 benchmark::Counter::kIsRate);
  transfer_counters(state, device().stats());
}
BENCHMARK(GpuDirect)
    ->ArgNames({"N", "precision", "law", "transfers"})
    ->ArgsProduct({{1024, 1 << 20}, {32, 64}, {0, 1}, {0, 1}})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

void CpuDirect(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const Disk& d = disk(n);
  const nb::Options o = options_of(state.range(1), 0, n);
  std::vector<double> ax(n), ay(n);
  for (auto _ : state) {
    nb::direct_accelerations(d.x, d.y, d.m, ax, ay, o);
    benchmark::DoNotOptimize(ax.data());
  }
  const double pairs = static_cast<double>(n) * static_cast<double>(n);
  state.counters["pairs/s"] = benchmark::Counter(pairs * static_cast<double>(state.iterations()),
                                                 benchmark::Counter::kIsRate);
}
BENCHMARK(CpuDirect)
    ->ArgNames({"N", "precision"})
    ->ArgsProduct({{1024, 1 << 17}, {32, 64}})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

calder::Arithmetic arithmetic_of(std::int64_t precision) {
  return precision == 64 ? calder::Arithmetic::float64 : calder::Arithmetic::float32;
}

void GpuRain(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const calder::Arithmetic a = arithmetic_of(state.range(1));
  if (a == calder::Arithmetic::float64 && !device().info().float64) {
    state.SkipWithError("the device has no shaderFloat64");
    return;
  }
  const bool transfers = state.range(2) != 0;
  gpu::open(device().info().index);
  calder::World world =
      calder::bench::gpu_rain_world(n, a, transfers ? gpu::step_batch : calder::bulk::step_batch);
  std::unique_ptr<gpu::DeviceWorld> on_device;
  if (!transfers) on_device = std::make_unique<gpu::DeviceWorld>(device(), world);
  gpu::Context& context = transfers ? *gpu::installed() : device();
  context.reset_stats();
  for (auto _ : state) {
    if (transfers) {
      world.step(calder::World::kBatchSteps);
    } else {
      on_device->step(calder::World::kBatchSteps);
    }
  }
  const double body_steps = static_cast<double>(n) * calder::World::kBatchSteps;
  state.counters["body-steps/s"] = benchmark::Counter(
      body_steps * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  transfer_counters(state, context.stats());
}
BENCHMARK(GpuRain)
    ->ArgNames({"N", "arithmetic", "transfers"})
    ->ArgsProduct({{10000, 10000000}, {32, 64}, {0, 1}})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

void CpuRain(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  calder::World world =
      calder::bench::gpu_rain_world(n, arithmetic_of(state.range(1)), calder::bulk::step_batch);
  for (auto _ : state) world.step(calder::World::kBatchSteps);
  const double body_steps = static_cast<double>(n) * calder::World::kBatchSteps;
  state.counters["body-steps/s"] = benchmark::Counter(
      body_steps * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(CpuRain)
    ->ArgNames({"N", "arithmetic"})
    ->ArgsProduct({{10000, 1000000}, {32, 64}})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

void GpuRows(benchmark::State& state) {
  for (auto _ : state) {
    for (const calder::bench::GpuRow& row : calder::bench::gpu_rows(true)) {
      std::fprintf(stderr, "bench_gpu: %s: %.3g %s (%s)\n", row.name.c_str(), row.value,
                   row.unit.c_str(), row.note.c_str());
    }
  }
}
BENCHMARK(GpuRows)->Iterations(1)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
