// SPDX-License-Identifier: MIT
// calder::movers: compiles a batch's fields into passes (see plan.hpp).
#include "plan.hpp"

#include <limits>
#include <type_traits>
#include <variant>

#include "calder/forces.hpp"
#include "calder/random.hpp"

namespace calder::movers::detail {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Why the kernels can't run this field ("" when they can).
std::string why_not_field(const Field& field) {
  if (std::holds_alternative<MutualAttraction>(field)) {
    return "field mutual_attraction has no per-body kernel (calder::nbody sums it)";
  }
  if (std::holds_alternative<CustomForce>(field)) return "field custom_force has no kernel";
  if (const auto* a = std::get_if<Attractor>(&field)) {
    if (!a->law.inverse_square()) {
      return "field attractor: only the inverse-square laws have a kernel (no custom law, "
             "exponent 2, no repulsive core)";
    }
  }
  return "";
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
  plan.ops.clear();
  plan.per_step.clear();
  plan.boundary = batch.boundary;
  plan.width = batch.width;
  plan.height = batch.height;
  plan.dt = batch.dt;
  plan.steps = batch.steps;
  // Per-step forces are stored first and pointed to afterwards (the vector may grow).
  std::vector<std::size_t> per_step_offsets;
  const auto steps = static_cast<std::size_t>(batch.steps);

  for (const Field& field : *batch.fields) {
    if (std::string why = why_not_field(field); !why.empty()) {
      if (why_not != nullptr) *why_not = std::move(why);
      return false;
    }
    std::visit(
        [&](const auto& f) {
          using F = std::decay_t<decltype(f)>;
          if (!f.enabled) return;
          Op op;
          if constexpr (std::is_same_v<F, Gravity>) {
            op.kind = f.scale_by_mass ? OpKind::gravity_scaled : OpKind::uniform;
            op.fx = f.g.x;
            op.fy = f.g.y;
          } else if constexpr (std::is_same_v<F, Wind>) {
            op.fx = f.force.x;
            op.fy = f.force.y;
          } else if constexpr (std::is_same_v<F, Helium>) {
            const Vec2 force = helium(f.lift);
            op.fx = force.x;
            op.fy = force.y;
          } else if constexpr (std::is_same_v<F, NoiseWind>) {
            // The world's time advances by dt each step, added as World does.
            per_step_offsets.push_back(plan.per_step.size());
            double time = batch.time;
            for (std::size_t s = 0; s < steps; ++s) {
              const Vec2 force = noise_wind(*batch.noise, time, f.strength, f.rate, f.offset);
              plan.per_step.push_back(force.x);
              plan.per_step.push_back(force.y);
              time += batch.dt;
            }
          } else if constexpr (std::is_same_v<F, Fan>) {
            op.kind = OpKind::fan;
            op.px = f.position.x;
            op.py = f.position.y;
            op.c = f.strength;
            op.reach = f.reach;
          } else if constexpr (std::is_same_v<F, EdgeForce>) {
            op.kind = OpKind::edge_force;
            op.c = f.strength;
            op.margin = f.margin;
          } else if constexpr (std::is_same_v<F, Friction>) {
            op.kind = OpKind::friction;
            op.c = f.mu;
            op.normal = f.normal;
            op.surface = f.surface;
            op.tolerance = f.tolerance;
            op.never_reverse = f.never_reverse;
          } else if constexpr (std::is_same_v<F, Liquid>) {
            op.kind = OpKind::drag;
            op.c = f.c;
            op.never_reverse = f.never_reverse;
            // Rect::contains: x < p.x < x + w, y < p.y < y + h.
            op.x_min = f.region.x;
            op.x_max = f.region.x + f.region.w;
            op.y_min = f.region.y;
            op.y_max = f.region.y + f.region.h;
          } else if constexpr (std::is_same_v<F, Drag>) {
            op.kind = OpKind::drag;
            op.c = f.c;
            op.never_reverse = f.never_reverse;
            op.everywhere = true;
            op.x_min = -kInf;
            op.x_max = kInf;
            op.y_min = -kInf;
            op.y_max = kInf;
          } else if constexpr (std::is_same_v<F, Lift>) {
            op.kind = OpKind::lift;
            op.c = f.coefficient;
          } else if constexpr (std::is_same_v<F, Attractor>) {
            op.kind = OpKind::attractor;
            op.px = f.position.x;
            op.py = f.position.y;
            op.mass = f.mass;
            op.G = f.law.G;
            op.masses_first = f.law.product == MassProduct::masses_first;
            op.law = f.law.clamp;
            op.lo = f.law.min;
            op.hi = f.law.max;
            op.softening = f.law.softening;
          } else {
            static_assert(std::is_same_v<F, MutualAttraction> || std::is_same_v<F, CustomForce>);
            return;  // refused above
          }
          plan.ops.push_back(op);
        },
        field);
  }
  // Point the noise winds at their forces, in field order.
  std::size_t next = 0;
  std::size_t op_index = 0;
  for (const Field& field : *batch.fields) {
    bool enabled = false;
    std::visit([&](const auto& f) { enabled = f.enabled; }, field);
    if (!enabled) continue;
    if (std::holds_alternative<NoiseWind>(field)) {
      plan.ops[op_index].per_step = plan.per_step.data() + per_step_offsets[next++];
    }
    ++op_index;
  }
  return true;
}

}  // namespace calder::movers::detail
