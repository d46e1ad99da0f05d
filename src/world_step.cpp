// SPDX-License-Identifier: MIT
// How World steps: the checks before a step, one step at a time through the
// integrators (integrators.cpp), or whole batches handed to the world's
// step_batch backend (calder/backends.hpp) when the world and the arithmetic
// allow it; a step either completes or leaves the world as it was.
#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "calder/error.hpp"
#include "calder/world.hpp"
#include "step_batch.hpp"

namespace calder {

namespace {

// Below this many body-steps a call is not worth a batch's setup.
constexpr std::int64_t kBatchMinBodySteps = 4096;

}  // namespace

void World::check_step_settings() const {
  for (const Field& field : fields_) {
    try {
      validate(field);
    } catch (const Error& e) {
      rethrow_with_context(e, "World::step: ");
    }
  }
  if (def_.max_speed > 0.0 && def_.integrator != Integrator::semi_implicit_euler) {
    throw InvalidArgument("World::step: max_speed needs the semi_implicit_euler integrator");
  }
  if (def_.update_order == UpdateOrder::sequential &&
      def_.integrator != Integrator::semi_implicit_euler) {
    throw InvalidArgument(
        "World::step: the sequential update order needs the semi_implicit_euler integrator");
  }
  if (def_.integrator == Integrator::ias15) check_adaptive_settings();
  if (def_.threads < 0) {
    throw InvalidArgument("World::step: threads must be >= 0 (got " + std::to_string(def_.threads) +
                          ")");
  }
}

// IAS15 holds its error to the rounding of doubles: a force summed with a
// relative error of 1e-3 (Barnes-Hut) would make its steps and its accuracy
// meaningless, so it is refused rather than run.
void World::check_adaptive_settings() const {
  if (!(def_.tolerance > 0.0) || !std::isfinite(def_.tolerance)) {
    throw InvalidArgument("World::step: the ias15 tolerance must be finite and > 0 (got " +
                          detail::format_number(def_.tolerance) + ")");
  }
  for (const Field& field : fields_) {
    const auto* mutual = std::get_if<MutualAttraction>(&field);
    if (mutual != nullptr && mutual->enabled && mutual->method == NBodyMethod::barnes_hut) {
      throw InvalidArgument(
          "World::step: the ias15 integrator needs mutual_attraction's method exact or direct: "
          "Barnes-Hut's force error (about 1e-3) is far above what ias15 resolves");
    }
  }
}

void World::step() { step(1); }

void World::step_one() {
  check_step_settings();
  // A step either completes or throws with the world as it was: keep the
  // state it may change (a copy of six arrays, small next to the forces).
  save_state();
  // The adaptive integrator's carried state changes with the step too.
  const bool adaptive = def_.integrator == Integrator::ias15;
  AdaptiveState saved_adaptive;
  if (adaptive) saved_adaptive = adaptive_;
  try {
    if (def_.update_order == UpdateOrder::sequential) {
      step_euler_sequential();
    } else if (def_.integrator == Integrator::semi_implicit_euler) {
      step_euler_simultaneous();
    } else if (def_.integrator == Integrator::ias15) {
      step_ias15();
    } else {
      step_multistage();
    }
    check_finite("World::step");
  } catch (...) {
    restore_state();
    if (adaptive) adaptive_ = std::move(saved_adaptive);
    throw;
  }
  advance_clock();
  ++step_count_;
  advance_noise(1);
}

void World::advance_noise(int steps) {
  for (Field& field : fields_) {
    auto* wind = std::get_if<NoiseWind>(&field);
    if (wind == nullptr || !wind->accumulate) continue;
    for (int k = 0; k < steps; ++k) wind->offset += wind->rate;  // one addition a step, as p5
  }
}

std::string World::needs_plain_loops() const {
  if (def_.max_speed > 0.0) return "a speed limit (max_speed)";
  if (def_.boundary.inset != 0.0 || !def_.boundary.periodic) {
    return "a boundary with an inset or a non-periodic wrap";
  }
  for (const Field& field : fields_) {
    const auto* wind = std::get_if<NoiseWind>(&field);
    if (wind != nullptr && wind->accumulate) return "an accumulating noise_wind";
  }
  return {};
}

void World::step(int count) {
  if (count < 0)
    throw InvalidArgument("World::step: count must be >= 0 (got " + std::to_string(count) + ")");
  if (count == 0) return;
  const bool book = def_.arithmetic == Arithmetic::book;
  const std::string plain_only = needs_plain_loops();
  if (!book && !plain_only.empty()) {
    throw InvalidArgument(std::string("World::step: arithmetic ") +
                          std::string(arithmetic_name(def_.arithmetic)) + " has no kernel for " +
                          plain_only);
  }
  const StepBatchBackend backend = def_.backends.or_defaults().step_batch;
  const bool batchable = def_.integrator == Integrator::semi_implicit_euler &&
                         def_.update_order == UpdateOrder::simultaneous && backend != nullptr &&
                         plain_only.empty();
  if (!book && !batchable) {
    throw InvalidArgument(
        std::string("World::step: arithmetic ") + std::string(arithmetic_name(def_.arithmetic)) +
        (backend == nullptr
             ? " needs calder::bulk's kernels (link calder::bulk: it registers them)"
             : " needs the semi_implicit_euler integrator and the simultaneous update "
               "order"));
  }
  const auto body_steps = static_cast<std::int64_t>(bodies_.x.size()) * count;
  if (batchable && (!book || body_steps >= kBatchMinBodySteps)) {
    check_step_settings();
    while (count > 0) {
      const int steps = std::min(kBatchSteps, count);
      // No kernel for one of the fields (book arithmetic): the loops below take over.
      if (!step_batch(steps)) break;
      count -= steps;
    }
  }
  for (int k = 0; k < count; ++k) step_one();
}

bool World::step_batch(int steps) {
  const StepBatchBackend backend = def_.backends.or_defaults().step_batch;
  StepBatch batch;
  for_each_column([](const char*, auto& to, std::vector<double>& from) { to = from; }, batch.bodies,
                  bodies_);
  batch.fields = &fields_;
  batch.boundary = def_.boundary;
  batch.width = def_.width;
  batch.height = def_.height;
  batch.dt = def_.dt;
  batch.time = time_;
  batch.steps = steps;
  batch.arithmetic = def_.arithmetic;
  batch.threads = def_.threads;
  batch.noise = &noise_;

  const bool book = def_.arithmetic == Arithmetic::book;
  const std::size_t n = bodies_.x.size();
  saved_.resize(kStateColumns * n);  // the backend saves the state into it (restore_state's layout)
  std::size_t first_non_finite = n;
  batch.saved = saved_.data();
  batch.first_non_finite = &first_non_finite;
  std::string why_not;
  // The backend declines (or throws) only before it changes anything.
  const bool ran = backend(batch, &why_not);
  if (!ran) {
    if (book) return false;
    throw InvalidArgument(std::string("World::step: arithmetic ") +
                          std::string(arithmetic_name(def_.arithmetic)) +
                          " needs a kernel for every field: " + why_not);
  }
  if (first_non_finite < n) {
    const std::size_t i = first_non_finite;
    restore_state();
    if (book) {
      // The same bits step by step: the failing step throws with its own
      // message and leaves the world as it was before that step.
      for (int k = 0; k < steps; ++k) step_one();
      // The plain loops went through: the kernels disagreed with them, a bug
      // the result no longer shows; debug builds (the sanitizer CI) say so.
      assert(false && "calder::bulk's book kernels went non-finite where the plain loops did not");
      return true;
    }
    throw RunError("World::step: body " + std::to_string(i) +
                   " got a non-finite position or velocity within steps " +
                   std::to_string(step_count_ + 1) + " to " + std::to_string(step_count_ + steps) +
                   " (arithmetic " + std::string(arithmetic_name(def_.arithmetic)) +
                   "); the world is left as it was after step " + std::to_string(step_count_));
  }
  for (int k = 0; k < steps; ++k) time_ += def_.dt;
  step_count_ += steps;
  return true;
}

void World::save_state() {
  saved_.resize(kStateColumns * body_count());
  auto out = saved_.begin();
  for_each_state(
      [&out](const char*, const std::vector<double>& array) {
        out = std::copy(array.begin(), array.end(), out);
      },
      bodies_);
}

void World::restore_state() {
  auto in = saved_.cbegin();
  for_each_state(
      [&in](const char*, std::vector<double>& array) {
        std::copy(in, in + static_cast<std::ptrdiff_t>(array.size()), array.begin());
        in += static_cast<std::ptrdiff_t>(array.size());
      },
      bodies_);
}

}  // namespace calder
