// SPDX-License-Identifier: MIT
#include "calder/fields.hpp"

#include <atomic>
#include <cmath>
#include <string>
#include <tuple>
#include <type_traits>

#include "calder/error.hpp"
#include "calder/random.hpp"
#include "calder/world.hpp"
#include "field_kinds/laws.hpp"

namespace calder {

double BodyView::friction_or(std::size_t i, double fallback) const {
  // Bodies without their own coefficient store NaN (never visible outside).
  return std::isnan(friction[i]) ? fallback : friction[i];
}

bool touches_edge(Edge edge, Vec2 position, double radius, double width, double height,
                  double tolerance) {
  return laws::touches<lanes::ScalarBook>(edge, position.x, position.y, radius, tolerance, width,
                                          height);
}

namespace {

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

// Applies force_of(i) to every body of the range.
template <class ForceOf>
void accumulate_each(const FieldContext& c, std::size_t first, std::size_t last,
                     std::span<double> ax, std::span<double> ay, ForceOf force_of) {
  for (std::size_t i = first; i < last; ++i) add_force(ax, ay, i, force_of(i), c.bodies.mass[i]);
}

// One body as the laws of src/field_kinds/ read it (lanes.hpp): its state,
// the acceleration the fields add to, and its constants from the view.
struct BodyLane {
  double x, y, vx, vy, ax, ay;
  const BodyView* view;
  std::size_t i;
  [[nodiscard]] double m() const { return view->mass[i]; }
  [[nodiscard]] double inv_m() const { return 1.0 / view->mass[i]; }
  [[nodiscard]] double r() const { return view->radius[i]; }
  [[nodiscard]] double area() const { return view->drag_area[i]; }
  [[nodiscard]] double mu() const { return view->friction[i]; }  // NaN: none of its own
};

// A kind's law (FieldLaw<F>::run) on the bodies of the range, one at a time,
// in the book's arithmetic.
template <class F>
void accumulate_law(const typename FieldLaw<F>::template Law<double>& law, const FieldContext& c,
                    std::size_t first, std::size_t last, std::span<double> ax,
                    std::span<double> ay) {
  const BodyView& v = c.bodies;
  const lanes::Frame<double> frame{c.width, c.height, c.dt, 0};
  FieldLaw<F>::template run<lanes::ScalarBook>(
      [&](auto op) {
        for (std::size_t i = first; i < last; ++i) {
          BodyLane b{v.x[i], v.y[i], v.vx[i], v.vy[i], ax[i], ay[i], &v, i};
          op(b);
          ax[i] = b.ax;
          ay[i] = b.ay;
        }
      },
      law, frame);
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
          "field mutual_attraction: method direct and barnes_hut need calder::nbody's kernels "
          "(link calder::nbody: it registers them)");
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

// An enabled field on the bodies of the range: its law, one body at a time;
// or, for a kind with a force of its own (the attractor: any attraction
// law), that force; the noise wind and the kinds without a law have their own.
template <class F>
void accumulate_kind(const F& f, const FieldContext& c, std::size_t first, std::size_t last,
                     std::span<double> ax, std::span<double> ay) {
  if constexpr (requires { FieldLaw<F>::force(f, c, first); }) {
    accumulate_each(c, first, last, ax, ay,
                    [&](std::size_t i) { return FieldLaw<F>::force(f, c, i); });
  } else {
    accumulate_law<F>(FieldLaw<F>::template law<double>(f), c, first, last, ax, ay);
  }
}

void accumulate_kind(const NoiseWind& f, const FieldContext& c, std::size_t first, std::size_t last,
                     std::span<double> ax, std::span<double> ay) {
  if (c.noise == nullptr) throw Error("field noise_wind: the world has no noise");
  // Accumulating: the noise is read at offset itself (0 * rate adds nothing).
  const double time = f.accumulate ? 0.0 : c.time;
  const Vec2 force = noise_wind(*c.noise, time, f.strength, f.rate, f.offset);
  accumulate_law<NoiseWind>({.fx = force.x, .fy = force.y}, c, first, last, ax, ay);
}

void accumulate_kind(const MutualAttraction& f, const FieldContext& c, std::size_t first,
                     std::size_t last, std::span<double> ax, std::span<double> ay) {
  accumulate_mutual(f, c, first, last, ax, ay);
}

void accumulate_kind(const CustomForce& f, const FieldContext& c, std::size_t first,
                     std::size_t last, std::span<double> ax, std::span<double> ay) {
  accumulate_each(c, first, last, ax, ay, [&](std::size_t i) {
    const Vec2 force = f.force(c, i);
    if (!force.is_finite()) {
      throw Error("field custom_force: returned a non-finite force for body " + std::to_string(i));
    }
    return force;
  });
}

}  // namespace

const char* field_name(const Field& field) {
  return std::visit([](const auto& f) { return FieldKind<std::decay_t<decltype(f)>>::name; },
                    field);
}

namespace {

// One parameter's value against its range; messages "field fan: reach must be > 0 (got 0)".
void validate_value(double value, Range range, const std::string& where, const char* key) {
  switch (range) {
    case Range::finite:
      return detail::require_finite(value, where.c_str(), key);
    case Range::positive:
      return detail::require_positive(value, where.c_str(), key);
    case Range::non_negative:
      return detail::require_non_negative(value, where.c_str(), key);
    case Range::unit_interval:
      if (!(value >= 0.0 && value <= 1.0)) {
        throw Error(where + ": " + key + " must be in [0, 1] (got " + detail::format_number(value) +
                    ")");
      }
      return;
  }
}

void validate_value(int value, Range range, const std::string& where, const char* key) {
  validate_value(static_cast<double>(value), range, where, key);
}

void validate_value(Vec2 value, Range, const std::string& where, const char* key) {
  require_finite_vec(value, where.c_str(), key);
}

void validate_value(const Rect& region, Range, const std::string& where, const char* key) {
  const std::string k(key);
  detail::require_finite(region.x, where.c_str(), (k + ".x").c_str());
  detail::require_finite(region.y, where.c_str(), (k + ".y").c_str());
  detail::require_non_negative(region.w, where.c_str(), (k + ".w").c_str());
  detail::require_non_negative(region.h, where.c_str(), (k + ".h").c_str());
}

void validate_value(const AttractionLaw& law, Range, const std::string& where, const char*) {
  law.validate(where.c_str());
}

void validate_value(const std::optional<CentralBody>& central, Range, const std::string& where,
                    const char* key) {
  if (!central) return;
  const std::string k(key);
  require_finite_vec(central->position, where.c_str(), (k + ".position").c_str());
  detail::require_positive(central->mass, where.c_str(), (k + ".mass").c_str());
}

// Booleans and enumerations: any value.
template <class T>
requires std::is_same_v<T, bool> || std::is_enum_v<T>
void validate_value(T, Range, const std::string&, const char*) {}

}  // namespace

void FieldKind<MutualAttraction>::check(const MutualAttraction& f, const std::string& where) {
  if (f.threads > max_threads) {
    throw Error(where + ": threads must be at most " + std::to_string(max_threads) + " (got " +
                std::to_string(f.threads) + ")");
  }
  if (field_kind_detail::fast_method(f) && !f.law.inverse_square()) {
    throw Error(where +
                ": the fast methods support the inverse-square law only (the book "
                "clamp, the squared clamp or Plummer softening)");
  }
}

void FieldKind<CustomForce>::check(const CustomForce& f, const std::string& where) {
  if (!f.force) throw Error(where + ": force function is empty");
}

void validate(const Field& field) {
  std::visit(
      [](const auto& f) {
        using Kind = FieldKind<std::decay_t<decltype(f)>>;
        const std::string where = std::string("field ") + Kind::name;
        std::apply(
            [&](const auto&... p) { (validate_value(f.*p.member, p.range, where, p.key), ...); },
            Kind::parameters);
        if constexpr (requires { Kind::check(f, where); }) Kind::check(f, where);
      },
      field);
}

void accumulate(const Field& field, const FieldContext& c, std::size_t first, std::size_t last,
                std::span<double> ax, std::span<double> ay) {
  std::visit(
      [&](const auto& f) {
        if (f.enabled) accumulate_kind(f, c, first, last, ax, ay);
      },
      field);
}

}  // namespace calder
