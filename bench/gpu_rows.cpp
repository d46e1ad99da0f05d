// SPDX-License-Identifier: MIT
#include "gpu_rows.hpp"

#include <calder/bulk.hpp>
#include <calder/error.hpp>
#include <calder/gpu.hpp>
#include <calder/random.hpp>
#include <calder/world.hpp>
#include <chrono>
#include <cmath>
#include <functional>
#include <memory>

namespace calder::bench {

namespace {

using Clock = std::chrono::steady_clock;

// Seconds per call of f: at least `repeats` calls and 0.2 s (one warm-up call first).
double seconds_per_call(const std::function<void()>& f, int repeats) {
  f();
  int calls = 0;
  const Clock::time_point start = Clock::now();
  double elapsed = 0.0;
  while (calls < repeats || elapsed < 0.2) {
    f();
    ++calls;
    elapsed = std::chrono::duration<double>(Clock::now() - start).count();
    if (repeats == 1) break;
  }
  return elapsed / calls;
}

std::string megabytes(double bytes) {
  char text[64];
  std::snprintf(text, sizeof text, "%.3g MB copied", bytes / 1e6);
  return text;
}

void direct_rows(gpu::Context& context, bool quick, std::vector<GpuRow>& rows) {
  const std::size_t n = quick ? 1024 : std::size_t{1} << 20;
  Random rng(42);
  std::vector<double> x(n), y(n), m(n), ax(n), ay(n);
  for (std::size_t i = 0; i < n; ++i) {
    x[i] = rng.random(-1.0, 1.0);
    y[i] = rng.random(-1.0, 1.0);
    m[i] = rng.random(0.5, 2.0);
  }
  nbody::Options options{.softening = 0.5 / std::sqrt(static_cast<double>(n)),
                         .precision = nbody::Precision::float32};
  const double pairs = static_cast<double>(n) * static_cast<double>(n);
  const std::string size = ", N = " + std::to_string(n);
  gpu::DirectSums sums(context);
  sums.upload(x, y, m, options);
  context.reset_stats();
  const double resident = seconds_per_call([&] { sums.evaluate(); }, quick ? 1 : 3);
  rows.push_back({"gpu direct float32" + size + ", bodies on the device", pairs / resident,
                  "pairs/s", megabytes(0)});
  context.reset_stats();
  int calls = 0;
  const double copied = seconds_per_call(
      [&] {
        gpu::direct_accelerations(context, x, y, m, ax, ay, options);
        ++calls;
      },
      quick ? 1 : 3);
  rows.push_back({"gpu direct float32" + size + ", with transfers", pairs / copied, "pairs/s",
                  megabytes(static_cast<double>(context.stats().upload_bytes +
                                                context.stats().download_bytes) /
                            calls)});
}

void rain_rows(gpu::Context& context, bool quick, std::vector<GpuRow>& rows) {
  const std::size_t n = quick ? 10000 : 10000000;
  const double body_steps = static_cast<double>(n) * World::kBatchSteps;
  const std::string size = ", N = " + std::to_string(n) + ", batches of 128 steps";
  World world = gpu_rain_world(n, Arithmetic::float32, bulk::step_batch);
  gpu::DeviceWorld on_device(context, world);
  const double resident =
      seconds_per_call([&] { on_device.step(World::kBatchSteps); }, quick ? 1 : 3);
  rows.push_back({"gpu rain float32" + size + ", bodies on the device", body_steps / resident,
                  "body-steps/s", "a few hundred bytes copied"});
  gpu::open(context.info().index);
  World backed = gpu_rain_world(n, Arithmetic::float32, gpu::step_batch);
  gpu::installed()->reset_stats();
  int calls = 0;
  const double copied = seconds_per_call(
      [&] {
        backed.step(World::kBatchSteps);
        ++calls;
      },
      quick ? 1 : 3);
  const gpu::TransferStats& s = gpu::installed()->stats();
  rows.push_back({"gpu rain float32" + size + ", with transfers", body_steps / copied,
                  "body-steps/s",
                  megabytes(static_cast<double>(s.upload_bytes + s.download_bytes) / calls)});
}

}  // namespace

std::string gpu_device_text() {
  try {
    const gpu::Context context;
    const gpu::DeviceInfo& d = context.info();
    return d.name + " (" + d.type + ", Vulkan " + d.api_version + ")";
  } catch (const Error& e) {
    return e.what();
  }
}

World gpu_rain_world(std::size_t n, Arithmetic arithmetic, StepBatchBackend backend) {
  const double scale = std::sqrt(static_cast<double>(n) / 1000.0);
  WorldDef def;
  def.width = 640.0 * scale;
  def.height = 240.0 * scale;
  def.boundary = Boundary::bounce(0.9, true, Edges{true, true, false, true});
  def.arithmetic = arithmetic;
  def.backends.step_batch = backend;
  World world(def);
  Random rng(1);
  std::vector<double> x(n), y(n), mass(n), radius(n);
  for (std::size_t i = 0; i < n; ++i) {
    x[i] = rng.random(def.width);
    y[i] = rng.random(def.height);
    mass[i] = rng.random(0.5, 3.0);
    radius[i] = 2.0 * mass[i];
  }
  world.add_bodies({.x = x, .y = y, .mass = mass, .radius = radius});
  world.add(Gravity{.g = {0.0, 0.1}, .scale_by_mass = true});
  world.add(Drag{.c = 0.01});
  return world;
}

std::vector<GpuRow> gpu_rows(bool quick) {
  std::vector<GpuRow> rows;
  std::unique_ptr<gpu::Context> context;
  try {
    context = std::make_unique<gpu::Context>();
  } catch (const Error& e) {
    rows.push_back({"gpu", 0.0, "", e.what()});
    return rows;
  }
  direct_rows(*context, quick, rows);
  rain_rows(*context, quick, rows);
  return rows;
}

}  // namespace calder::bench
