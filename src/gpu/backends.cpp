// SPDX-License-Identifier: MIT
// calder::gpu: the World's backends on the process's device (install()).
#include <algorithm>
#include <cmath>
#include <memory>
#include <mutex>
#include <string>

#include "../step_batch.hpp"
#include "calder/error.hpp"
#include "calder/gpu.hpp"
#include "context.hpp"
#include "steps.hpp"

namespace calder::gpu {

namespace {

// The process's device and its buffers; one batch at a time.
struct Installed {
  std::unique_ptr<Context> context;
  std::unique_ptr<Stepper> stepper;
  std::unique_ptr<DirectSums> sums;
  bulk::detail::Plan plan;
  std::mutex mutex;
};

Installed& installed_state() {
  static Installed state;
  return state;
}

Context& require_context(const char* who) {
  Installed& s = installed_state();
  if (!s.context) {
    throw InvalidArgument(std::string(who) + ": no GPU is installed (call calder::gpu::install())");
  }
  return *s.context;
}

// The first of [first, n) whose position or velocity is not finite, or n.
std::size_t first_non_finite(const StepBatch& batch) {
  const auto& b = batch.bodies;
  for (std::size_t i = 0; i < b.x.size(); ++i) {
    if (!std::isfinite(b.x[i]) || !std::isfinite(b.y[i]) || !std::isfinite(b.vx[i]) ||
        !std::isfinite(b.vy[i])) {
      return i;
    }
  }
  return b.x.size();
}

}  // namespace

bool step_batch(const StepBatch& batch, std::string* why_not) {
  Context& context = require_context("gpu::step_batch");
  Installed& s = installed_state();
  const std::lock_guard<std::mutex> lock(s.mutex);
  // Declined (World then throws, or, for the book arithmetic, runs its loops).
  std::string why =
      unsupported_settings(batch.arithmetic, batch.boundary, *batch.fields, context.impl());
  if (why.empty()) bulk::detail::compile(batch, s.plan, &why);
  if (!why.empty()) {
    if (why_not != nullptr) *why_not = "on the GPU, " + why;
    return false;
  }
  if (!s.stepper) s.stepper = std::make_unique<Stepper>(context.impl());
  const std::size_t n = batch.bodies.x.size();
  if (batch.saved != nullptr) {
    std::size_t k = 0;
    for_each_state(
        [&](const char*, std::span<double> column) {
          std::copy(column.begin(), column.end(), batch.saved + (k++) * n);
        },
        batch.bodies);
  }
  BodyColumnsOf<std::span<const double>> in;
  for_each_column([](const char*, auto& to, auto from) { to = from; }, in, batch.bodies);
  s.stepper->upload(in, batch.arithmetic == Arithmetic::float64);
  s.stepper->run(s.plan, batch.steps);
  s.stepper->download(batch.bodies.x, batch.bodies.y, batch.bodies.vx, batch.bodies.vy);
  std::fill(batch.bodies.ax.begin(), batch.bodies.ax.end(), 0.0);
  std::fill(batch.bodies.ay.begin(), batch.bodies.ay.end(), 0.0);
  if (batch.first_non_finite != nullptr) *batch.first_non_finite = first_non_finite(batch);
  return true;
}

void mutual_attraction(const MutualAttraction& field, const FieldContext& context,
                       std::span<double> ax, std::span<double> ay) {
  Context& device = require_context("gpu::mutual_attraction");
  if (field.method == NBodyMethod::barnes_hut) {
    throw InvalidArgument(
        "gpu::mutual_attraction: the GPU sums method direct only (no Barnes-Hut on the GPU)");
  }
  Installed& s = installed_state();
  const std::lock_guard<std::mutex> lock(s.mutex);
  nbody::Options options = nbody::options_for(field.law);  // throws for a custom law
  options.precision =
      field.single_precision ? nbody::Precision::float32 : nbody::Precision::float64;
  if (!s.sums) s.sums = std::make_unique<DirectSums>(device);
  const BodyView& b = context.bodies;
  s.sums->upload(b.x, b.y, b.mass, options);
  s.sums->evaluate();
  s.sums->add_to(ax, ay);
}

Context& open(int device) {
  Installed& s = installed_state();
  const std::lock_guard<std::mutex> lock(s.mutex);
  if (!s.context || (device >= 0 && s.context->info().index != device)) {
    s.sums.reset();
    s.stepper.reset();
    s.context = std::make_unique<Context>(device);
  }
  return *s.context;
}

void install(int device) {
  open(device);
  set_step_batch_backend(step_batch);
  set_mutual_attraction_backend(mutual_attraction);
}

Context* installed() { return installed_state().context.get(); }

}  // namespace calder::gpu
