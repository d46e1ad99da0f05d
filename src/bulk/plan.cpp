// SPDX-License-Identifier: MIT
// calder::bulk: compiles a batch's fields into passes (see plan.hpp).
//
// Every field kind has here either an op_of (the op its kernel runs, its
// parameters in the kernel's precision R) or a no_kernel (why the kernels
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

// --- the kinds with a kernel: each writes its parameters and returns its op's kind ---

template <class R>
OpKind op_of(const Gravity& f, Params<R>& p) {
  p.fx = R(f.g.x);
  p.fy = R(f.g.y);
  return f.scale_by_mass ? OpKind::gravity_scaled : OpKind::uniform;
}

template <class R>
OpKind op_of(const Wind& f, Params<R>& p) {
  p.fx = R(f.force.x);
  p.fy = R(f.force.y);
  return OpKind::uniform;
}

template <class R>
OpKind op_of(const Helium& f, Params<R>& p) {
  const Vec2 force = helium(f.lift);
  p.fx = R(force.x);
  p.fy = R(force.y);
  return OpKind::uniform;
}

// Its force changes with time: add_noise_forces gives each step's.
template <class R>
OpKind op_of(const NoiseWind&, Params<R>&) {
  return OpKind::uniform;
}

template <class R>
OpKind op_of(const Fan& f, Params<R>& p) {
  p.px = R(f.position.x);
  p.py = R(f.position.y);
  p.c = R(f.strength);
  p.reach = R(f.reach);
  return OpKind::fan;
}

template <class R>
OpKind op_of(const EdgeForce& f, Params<R>& p) {
  p.c = R(f.strength);
  p.margin = R(f.margin);
  return OpKind::edge_force;
}

template <class R>
OpKind op_of(const Friction& f, Params<R>& p) {
  p.c = R(f.mu);
  p.normal = R(f.normal);
  p.surface = f.surface;
  p.tolerance = R(f.tolerance);
  p.never_reverse = f.never_reverse;
  return OpKind::friction;
}

template <class R>
OpKind op_of(const Liquid& f, Params<R>& p) {
  p.c = R(f.c);
  p.never_reverse = f.never_reverse;
  // Rect::contains: x < p.x < x + w, y < p.y < y + h (the sums in double).
  p.x_min = R(f.region.x);
  p.x_max = R(f.region.x + f.region.w);
  p.y_min = R(f.region.y);
  p.y_max = R(f.region.y + f.region.h);
  return OpKind::drag;
}

template <class R>
OpKind op_of(const Drag& f, Params<R>& p) {
  constexpr R kInf = std::numeric_limits<R>::infinity();
  p.c = R(f.c);
  p.never_reverse = f.never_reverse;
  p.everywhere = true;
  p.x_min = -kInf;
  p.x_max = kInf;
  p.y_min = -kInf;
  p.y_max = kInf;
  return OpKind::drag;
}

template <class R>
OpKind op_of(const Lift& f, Params<R>& p) {
  p.c = R(f.coefficient);
  return OpKind::lift;
}

template <class R>
OpKind op_of(const Attractor& f, Params<R>& p) {
  p.px = R(f.position.x);
  p.py = R(f.position.y);
  p.mass = R(f.mass);
  p.G = R(f.law.G);
  p.gm = R(f.law.G * f.mass);
  p.masses_first = f.law.product == MassProduct::masses_first;
  p.law = f.law.clamp;
  p.lo = R(f.law.min);
  p.hi = R(f.law.max);
  p.eps = R(f.law.softening);
  return OpKind::attractor;
}

// --- why a kind has no kernel ("": it has one for these parameters) ---

std::string no_kernel(const MutualAttraction&) {
  return "field mutual_attraction has no per-body kernel (calder::nbody sums it)";
}

std::string no_kernel(const CustomForce&) { return "field custom_force has no kernel"; }

std::string no_kernel(const Attractor& f) {
  if (f.law.inverse_square()) return "";
  return "field attractor: only the inverse-square laws have a kernel (no custom law, "
         "exponent 2, no repulsive core)";
}

template <class F>
concept HasOp = requires(const F& f, Params<double>& p64, Params<float>& p32) {
  { op_of(f, p64) } -> std::same_as<OpKind>;
  { op_of(f, p32) } -> std::same_as<OpKind>;
};
template <class F>
concept HasReason = requires(const F& f) {
  { no_kernel(f) } -> std::same_as<std::string>;
};

template <class... Kinds>
constexpr bool every_kind_covered(const std::variant<Kinds...>*) {
  return ((HasOp<Kinds> || HasReason<Kinds>)&&...);
}
static_assert(every_kind_covered(static_cast<const Field*>(nullptr)),
              "a field kind has neither an op_of (its kernel) nor a no_kernel (why it has none)");

// Why the kernels can't run this field ("" when they can).
std::string why_not_field(const Field& field) {
  return std::visit(
      [](const auto& f) -> std::string {
        if constexpr (HasReason<std::decay_t<decltype(f)>>) {
          return no_kernel(f);
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
        if constexpr (HasOp<std::decay_t<decltype(f)>>) {
          if (!f.enabled) return;
          Op op;
          op.kind = op_of(f, op.p64);
          op_of(f, op.p32);
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
  for (const auto& [op, offset] : winds) plan.ops[op].per_step = plan.per_step.data() + offset;
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
