// SPDX-License-Identifier: MIT
#include "calder/fields.hpp"

#include <atomic>
#include <cmath>
#include <string>

#include "calder/error.hpp"
#include "calder/random.hpp"

namespace calder {

double BodyView::friction_or(std::size_t i, double fallback) const {
  // Bodies without their own coefficient store NaN (never visible outside).
  return std::isnan(friction[i]) ? fallback : friction[i];
}

bool touches_edge(Edge edge, Vec2 position, double radius, double width, double height,
                  double tolerance) {
  switch (edge) {
    case Edge::left:
      return position.x < radius + tolerance;
    case Edge::right:
      return position.x > width - radius - tolerance;
    case Edge::top:
      return position.y < radius + tolerance;
    case Edge::bottom:
      return position.y > height - radius - tolerance;
  }
  return false;
}

namespace {

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

void require_finite_vec(Vec2 v, const char* where, const char* what) {
  detail::require_finite(v.x, where, what);
  detail::require_finite(v.y, where, what);
}

// acceleration += force / mass, exactly as applyForce does it.
inline void add_force(std::span<double> ax, std::span<double> ay, std::size_t i, Vec2 force,
                      double mass) {
  ax[i] += force.x / mass;
  ay[i] += force.y / mass;
}

// Applies the same force to every body of the range.
void accumulate_uniform(Vec2 force, const FieldContext& c, std::size_t first, std::size_t last,
                        std::span<double> ax, std::span<double> ay) {
  for (std::size_t i = first; i < last; ++i) add_force(ax, ay, i, force, c.bodies.mass[i]);
}

// Applies force_of(i) to every body of the range.
template <class ForceOf>
void accumulate_each(const FieldContext& c, std::size_t first, std::size_t last,
                     std::span<double> ax, std::span<double> ay, ForceOf force_of) {
  for (std::size_t i = first; i < last; ++i) add_force(ax, ay, i, force_of(i), c.bodies.mass[i]);
}

void accumulate_mutual(const MutualAttraction& f, const FieldContext& c, std::size_t first,
                       std::size_t last, std::span<double> ax, std::span<double> ay) {
  const BodyView& b = c.bodies;
  const std::size_t n = b.size();
  const auto central_pulls = [&](std::size_t i) {
    if (!f.central) return;
    add_force(ax, ay, i,
              attraction(f.central->position, f.central->mass, b.position(i), b.mass[i], f.law),
              b.mass[i]);
  };
  if (f.method != NBodyMethod::exact) {
    if (first != 0 || last != n) {
      throw Error("field mutual_attraction: the fast methods need the simultaneous update order");
    }
    const MutualAttractionBackend backend =
        Backends{.mutual_attraction = c.mutual_attraction}.or_defaults().mutual_attraction;
    if (backend == nullptr) {
      throw Error(
          "field mutual_attraction: method direct and barnes_hut need calder::nbody (link "
          "calder::nbody and set WorldDef::backends.mutual_attraction = "
          "calder::nbody::mutual_attraction, or call calder::nbody::install())");
    }
    for (std::size_t i = 0; i < n; ++i) central_pulls(i);
    backend(f, c, ax, ay);
    return;
  }
  if (first != 0 || last != n) {
    // A sub-range (sequential update): each target feels the central body,
    // then every other body in index order at its current position (example 2.9).
    for (std::size_t i = first; i < last; ++i) {
      central_pulls(i);
      for (std::size_t j = 0; j < n; ++j) {
        if (j == i) continue;
        add_force(ax, ay, i, attraction(b.position(j), b.mass[j], b.position(i), b.mass[i], f.law),
                  b.mass[i]);
      }
    }
    return;
  }
  if (f.order == PairOrder::by_source) {
    // For each source i: the central body pulls i, then i pulls every other body.
    for (std::size_t i = 0; i < n; ++i) {
      central_pulls(i);
      for (std::size_t j = 0; j < n; ++j) {
        if (j == i) continue;
        add_force(ax, ay, j, attraction(b.position(i), b.mass[i], b.position(j), b.mass[j], f.law),
                  b.mass[j]);
      }
    }
    return;
  }
  // Pairwise: the central body first, then one force per pair, +F on j and
  // exactly -F on i.
  for (std::size_t i = 0; i < n; ++i) central_pulls(i);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      const Vec2 force = attraction(b.position(i), b.mass[i], b.position(j), b.mass[j], f.law);
      add_force(ax, ay, j, force, b.mass[j]);
      add_force(ax, ay, i, -force, b.mass[i]);
    }
  }
}

}  // namespace

const char* field_name(const Field& field) {
  return std::visit(Overloaded{
                        [](const Gravity&) { return "gravity"; },
                        [](const Wind&) { return "wind"; },
                        [](const NoiseWind&) { return "noise_wind"; },
                        [](const Helium&) { return "helium"; },
                        [](const Fan&) { return "fan"; },
                        [](const EdgeForce&) { return "edge_force"; },
                        [](const Friction&) { return "friction"; },
                        [](const Liquid&) { return "liquid"; },
                        [](const Drag&) { return "drag"; },
                        [](const Lift&) { return "lift"; },
                        [](const Attractor&) { return "attractor"; },
                        [](const MutualAttraction&) { return "mutual_attraction"; },
                        [](const CustomForce&) { return "custom_force"; },
                    },
                    field);
}

void validate(const Field& field) {
  const std::string where_s = std::string("field ") + field_name(field);
  const char* where = where_s.c_str();
  std::visit(
      Overloaded{
          [&](const Gravity& f) { require_finite_vec(f.g, where, "g"); },
          [&](const Wind& f) { require_finite_vec(f.force, where, "force"); },
          [&](const NoiseWind& f) {
            detail::require_finite(f.strength, where, "strength");
            detail::require_finite(f.rate, where, "rate");
            detail::require_finite(f.offset, where, "offset");
          },
          [&](const Helium& f) { detail::require_finite(f.lift, where, "lift"); },
          [&](const Fan& f) {
            require_finite_vec(f.position, where, "position");
            detail::require_finite(f.strength, where, "strength");
            detail::require_positive(f.reach, where, "reach");
          },
          [&](const EdgeForce& f) {
            detail::require_finite(f.strength, where, "strength");
            detail::require_positive(f.margin, where, "margin");
          },
          [&](const Friction& f) {
            detail::require_non_negative(f.mu, where, "mu");
            detail::require_non_negative(f.normal, where, "normal");
            detail::require_non_negative(f.tolerance, where, "tolerance");
          },
          [&](const Liquid& f) {
            detail::require_finite(f.region.x, where, "region.x");
            detail::require_finite(f.region.y, where, "region.y");
            detail::require_non_negative(f.region.w, where, "region.w");
            detail::require_non_negative(f.region.h, where, "region.h");
            detail::require_non_negative(f.c, where, "c");
          },
          [&](const Drag& f) { detail::require_non_negative(f.c, where, "c"); },
          [&](const Lift& f) { detail::require_finite(f.coefficient, where, "coefficient"); },
          [&](const Attractor& f) {
            require_finite_vec(f.position, where, "position");
            detail::require_positive(f.mass, where, "mass");
            f.law.validate(where);
          },
          [&](const MutualAttraction& f) {
            f.law.validate(where);
            if (!(f.theta >= 0.0 && f.theta <= 1.0)) {
              throw Error(where_s + ": theta must be in [0, 1] (got " +
                          detail::format_number(f.theta) + ")");
            }
            if (f.threads < 0) {
              throw Error(where_s + ": threads must be >= 0 (got " + std::to_string(f.threads) +
                          ")");
            }
            if (f.method != NBodyMethod::exact && !f.law.inverse_square()) {
              throw Error(where_s +
                          ": the fast methods support the inverse-square law only (the book "
                          "clamp, the squared clamp or Plummer softening)");
            }
            if (f.central) {
              require_finite_vec(f.central->position, where, "central.position");
              detail::require_positive(f.central->mass, where, "central.mass");
            }
          },
          [&](const CustomForce& f) {
            if (!f.force) throw Error(where_s + ": force function is empty");
          },
      },
      field);
}

void accumulate(const Field& field, const FieldContext& c, std::size_t first, std::size_t last,
                std::span<double> ax, std::span<double> ay) {
  const BodyView& b = c.bodies;
  std::visit(
      Overloaded{
          [&](const Gravity& f) {
            if (!f.enabled) return;
            if (!f.scale_by_mass) return accumulate_uniform(f.g, c, first, last, ax, ay);
            accumulate_each(c, first, last, ax, ay,
                            [&](std::size_t i) { return gravity(f.g, b.mass[i], true); });
          },
          [&](const Wind& f) {
            if (f.enabled) accumulate_uniform(f.force, c, first, last, ax, ay);
          },
          [&](const NoiseWind& f) {
            if (!f.enabled) return;
            if (c.noise == nullptr) throw Error("field noise_wind: the world has no noise");
            // Accumulating: the noise is read at offset itself (0 * rate adds nothing).
            const double time = f.accumulate ? 0.0 : c.time;
            accumulate_uniform(noise_wind(*c.noise, time, f.strength, f.rate, f.offset), c, first,
                               last, ax, ay);
          },
          [&](const Helium& f) {
            if (f.enabled) accumulate_uniform(helium(f.lift), c, first, last, ax, ay);
          },
          [&](const Fan& f) {
            if (!f.enabled) return;
            accumulate_each(c, first, last, ax, ay, [&](std::size_t i) {
              return fan(f.position, b.position(i), f.strength, f.reach);
            });
          },
          [&](const EdgeForce& f) {
            if (!f.enabled) return;
            accumulate_each(c, first, last, ax, ay, [&](std::size_t i) {
              return edge_force(b.position(i), c.width, c.height, f.strength, f.margin);
            });
          },
          [&](const Friction& f) {
            if (!f.enabled) return;
            for (std::size_t i = first; i < last; ++i) {
              if (!touches_edge(f.surface, b.position(i), b.radius[i], c.width, c.height,
                                f.tolerance)) {
                continue;
              }
              Vec2 force = friction(b.velocity(i), b.friction_or(i, f.mu), f.normal);
              if (f.never_reverse) force = limit_drag(force, b.velocity(i), b.mass[i], c.dt);
              add_force(ax, ay, i, force, b.mass[i]);
            }
          },
          [&](const Liquid& f) {
            if (!f.enabled) return;
            for (std::size_t i = first; i < last; ++i) {
              if (!f.contains(b.position(i))) continue;
              Vec2 force = drag(b.velocity(i), f.c, b.drag_area[i]);
              if (f.never_reverse) force = limit_drag(force, b.velocity(i), b.mass[i], c.dt);
              add_force(ax, ay, i, force, b.mass[i]);
            }
          },
          [&](const Drag& f) {
            if (!f.enabled) return;
            accumulate_each(c, first, last, ax, ay, [&](std::size_t i) {
              const Vec2 force = drag(b.velocity(i), f.c, b.drag_area[i]);
              return f.never_reverse ? limit_drag(force, b.velocity(i), b.mass[i], c.dt) : force;
            });
          },
          [&](const Lift& f) {
            if (!f.enabled) return;
            accumulate_each(c, first, last, ax, ay,
                            [&](std::size_t i) { return lift(b.velocity(i), f.coefficient); });
          },
          [&](const Attractor& f) {
            if (!f.enabled) return;
            accumulate_each(c, first, last, ax, ay,
                            [&](std::size_t i) { return f.attract(b.position(i), b.mass[i]); });
          },
          [&](const MutualAttraction& f) {
            if (f.enabled) accumulate_mutual(f, c, first, last, ax, ay);
          },
          [&](const CustomForce& f) {
            if (!f.enabled) return;
            accumulate_each(c, first, last, ax, ay, [&](std::size_t i) {
              const Vec2 force = f.force(c, i);
              if (!force.is_finite()) {
                throw Error("field custom_force: returned a non-finite force for body " +
                            std::to_string(i));
              }
              return force;
            });
          },
      },
      field);
}

}  // namespace calder
