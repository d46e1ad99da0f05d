// SPDX-License-Identifier: MIT
// calder::bulk: compiles a batch's fields into passes (see plan.hpp).
//
// Every field kind has either a law over lanes (FieldLaw<F>::law and run,
// src/field_kinds/), which its op runs, or a no_kernel (why the kernels
// can't run it, or "" when they can after all); a kind with neither fails
// the static_assert below, so a new kind can't be skipped silently.
#include "plan.hpp"

#include <concepts>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>

#include "calder/forces.hpp"
#include "calder/random.hpp"

namespace calder::bulk::detail {

namespace {

// A kind that calder::bulk may refuse says why (FieldLaw<F>::no_kernel).
template <class F>
concept HasReason = requires(const F& f) {
  { FieldLaw<F>::no_kernel(f) } -> std::same_as<std::string>;
};

template <class... Kinds>
constexpr bool every_kind_covered(const std::variant<Kinds...>*) {
  return ((HasLaw<Kinds> || HasReason<Kinds>)&&...);
}
static_assert(every_kind_covered(static_cast<const Field*>(nullptr)),
              "a field kind has neither a law (its kernel) nor a no_kernel (why it has none)");

// Why the kernels can't run this field ("" when they can).
std::string why_not_field(const Field& field) {
  return std::visit(
      [](const auto& f) -> std::string {
        using F = std::decay_t<decltype(f)>;
        if constexpr (HasReason<F>) {
          return FieldLaw<F>::no_kernel(f);
        } else {
          return "";
        }
      },
      field);
}

// Clears the plan for a batch and takes its settings.
void reset(const StepBatch& batch, Plan& plan) {
  plan.ops.clear();
  plan.per_step.clear();
  plan.boundary = batch.boundary;
  plan.width = batch.width;
  plan.height = batch.height;
  plan.dt = batch.dt;
  plan.steps = batch.steps;
}

// Appends the op of an enabled field that has a kernel (why_not_field says "").
void add_op(const Field& field, Plan& plan) {
  std::visit(
      [&plan](const auto& f) {
        using F = std::decay_t<decltype(f)>;
        if constexpr (HasLaw<F>) {
          if (!f.enabled) return;
          Op op;
          op.law64 = KindLaw<F, double>{FieldLaw<F>::template law<double>(f)};
          op.law32 = KindLaw<F, float>{FieldLaw<F>::template law<float>(f)};
          plan.ops.push_back(op);
        }
      },
      field);
}

// The enabled noise winds' forces at each step of the batch, stored in
// plan.per_step and pointed to by their ops (in field order; the ops must
// be those of add_op).
void add_noise_forces(const StepBatch& batch, Plan& plan) {
  const auto steps = static_cast<std::size_t>(batch.steps);
  std::vector<std::pair<std::size_t, std::size_t>> winds;  // (op, offset in per_step)
  std::size_t op_index = 0;
  for (const Field& field : *batch.fields) {
    const bool enabled = std::visit([](const auto& f) { return f.enabled; }, field);
    if (!enabled) continue;
    if (const auto* wind = std::get_if<NoiseWind>(&field)) {
      winds.emplace_back(op_index, plan.per_step.size());
      // The world's time advances by dt each step, added as World does.
      double time = batch.time;
      for (std::size_t s = 0; s < steps; ++s) {
        const Vec2 force = noise_wind(*batch.noise, time, wind->strength, wind->rate, wind->offset);
        plan.per_step.push_back(force.x);
        plan.per_step.push_back(force.y);
        time += batch.dt;
      }
    }
    ++op_index;
  }
  // Pointed to afterwards: per_step may have grown.
  for (const auto& [op, offset] : winds) {
    const double* forces = plan.per_step.data() + offset;
    std::get<KindLaw<NoiseWind, double>>(plan.ops[op].law64).law.per_step = forces;
    std::get<KindLaw<NoiseWind, float>>(plan.ops[op].law32).law.per_step = forces;
  }
}

}  // namespace

std::string unsupported_field(const std::deque<Field>& fields) {
  for (const Field& field : fields) {
    std::string why = why_not_field(field);
    if (!why.empty()) return why;
  }
  return "";
}

bool compile(const StepBatch& batch, Plan& plan, std::string* why_not) {
  if (std::string why = unsupported_field(*batch.fields); !why.empty()) {
    if (why_not != nullptr) *why_not = std::move(why);
    return false;
  }
  reset(batch, plan);
  for (const Field& field : *batch.fields) add_op(field, plan);
  add_noise_forces(batch, plan);
  return true;
}

}  // namespace calder::bulk::detail
