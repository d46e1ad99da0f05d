// SPDX-License-Identifier: MIT
#include "calder/forces.hpp"

#include <cmath>
#include <string>

#include "calder/detmath.hpp"
#include "calder/error.hpp"
#include "calder/fields.hpp"
#include "calder/random.hpp"
#include "field_kinds/laws.hpp"

// The laws are the field kinds' (src/field_kinds/), instantiated here for
// one body in the book's arithmetic.
namespace calder {

namespace {

using lanes::ScalarBook;

Vec2 vec(lanes::Pair<double> f) { return {f.x, f.y}; }

}  // namespace

Vec2 gravity(Vec2 g, double mass, bool scale_by_mass) {
  // p5.Vector.mult(gravity, mass): (0 * m, 0.1 * m), component by component.
  return scale_by_mass ? g * mass : g;
}

Vec2 helium(double lift) {
  const auto law = FieldLaw<Helium>::law<double>(Helium{.lift = lift});
  return {law.fx, law.fy};
}

Vec2 noise_wind(const Noise& noise, double time, double strength, double rate, double offset) {
  return FieldLaw<NoiseWind>::force<ScalarBook>(noise, time, strength, rate, offset);
}

Vec2 fan(Vec2 fan_position, Vec2 body_position, double strength, double reach) {
  const auto law = FieldLaw<Fan>::law<double>(
      Fan{.position = fan_position, .strength = strength, .reach = reach});
  const auto blow = FieldLaw<Fan>::force<ScalarBook>(law, body_position.x, body_position.y);
  return blow.apply ? vec(blow.f) : Vec2{};
}

Vec2 edge_force(Vec2 position, double width, double height, double strength, double margin) {
  const auto law =
      FieldLaw<EdgeForce>::law<double>(EdgeForce{.strength = strength, .margin = margin});
  return vec(FieldLaw<EdgeForce>::force<ScalarBook>(law, position.x, position.y, width, height));
}

Vec2 friction(Vec2 velocity, double mu, double normal) {
  return vec(laws::friction<ScalarBook>(velocity.x, velocity.y, velocity.mag(), mu, normal));
}

Vec2 drag(Vec2 velocity, double c, double area) {
  return vec(laws::drag<ScalarBook>(velocity.x, velocity.y, velocity.mag(), c, area));
}

Vec2 limit_drag(Vec2 drag_force, Vec2 velocity, double mass, double dt) {
  lanes::Pair<double> f{drag_force.x, drag_force.y};
  lanes::never_reverse<ScalarBook>(f, mass, velocity.mag(), dt);
  return vec(f);
}

Vec2 lift(Vec2 velocity, double coefficient) {
  return vec(FieldLaw<Lift>::force<ScalarBook>(velocity.x, velocity.y, coefficient));
}

Vec2 Liquid::calculate_drag(Vec2 velocity, double area) const { return drag(velocity, c, area); }

AttractionLaw AttractionLaw::book(double G, double min_distance, double max_distance,
                                  MassProduct product) {
  AttractionLaw law;
  law.G = G;
  law.clamp = DistanceClamp::distance;
  law.min = min_distance;
  law.max = max_distance;
  law.product = product;
  return law;
}

AttractionLaw AttractionLaw::newtonian(double G, double softening) {
  AttractionLaw law;
  law.G = G;
  law.clamp = DistanceClamp::none;
  law.min = 0.0;
  law.max = 0.0;
  law.softening = softening;
  return law;
}

AttractionLaw AttractionLaw::from(ForceLaw custom_law) {
  AttractionLaw law;
  law.custom = std::move(custom_law);
  return law;
}

void AttractionLaw::validate(const char* where) const {
  const std::string w = std::string(where) + ": attraction law";
  if (custom) return;
  detail::require_finite(G, w.c_str(), "G");
  detail::require_non_negative(softening, w.c_str(), "softening");
  detail::require_finite(exponent, w.c_str(), "exponent");
  detail::require_non_negative(repulsion, w.c_str(), "repulsion");
  detail::require_finite(repulsion_exponent, w.c_str(), "repulsion_exponent");
  if (exponent != 2.0 && (softening != 0.0 || clamp == DistanceClamp::squared_distance)) {
    throw Error(w + ": softening and the squared-distance clamp need exponent 2 (got " +
                detail::format_number(exponent) + ")");
  }
  if (repulsion != 0.0 && (softening != 0.0 || clamp == DistanceClamp::squared_distance)) {
    throw Error(w + ": a repulsive core needs the distance clamp or no clamp, without softening");
  }
  if (clamp != DistanceClamp::none && softening != 0.0) {
    // A clamped law never reads it: said, not silently dropped.
    throw Error(w + ": softening needs clamp \"none\" (got softening " +
                detail::format_number(softening) + " with a clamped law, whose min bounds the " +
                "force)");
  }
  if (clamp != DistanceClamp::none) {
    detail::require_non_negative(min, w.c_str(), "min");
    detail::require_non_negative(max, w.c_str(), "max");
    if (min > max) {
      throw Error(w + ": min must not exceed max (got min " + detail::format_number(min) +
                  ", max " + detail::format_number(max) + ")");
    }
    if (min == 0.0) throw Error(w + ": min must be > 0 for a clamped law (got 0)");
  }
}

namespace {

double strength_of(double G, double source_mass, double target_mass, double denominator,
                   MassProduct product) {
  // The sketches group these differently; the last bits follow the grouping.
  const double numerator = product == MassProduct::masses_first ? G * (source_mass * target_mass)
                                                                : G * source_mass * target_mass;
  return numerator / denominator;
}

// The magnitude at distance d (already clamped) of the power law with its
// repulsive core. Exponent 2 keeps the book's d * d, bit for bit.
double power_strength(const AttractionLaw& law, double source_mass, double target_mass, double d) {
  const double denominator = law.exponent == 2.0 ? d * d : math::pow(d, law.exponent);
  double strength = strength_of(law.G, source_mass, target_mass, denominator, law.product);
  if (law.repulsion != 0.0) {
    strength -= law.repulsion * source_mass * target_mass / math::pow(d, law.repulsion_exponent);
  }
  return strength;
}

// An antiderivative of d^-p: d^(1-p) / (1-p), or ln d for p = 1.
double power_integral(double d, double p) {
  return p == 1.0 ? math::log(d) : math::pow(d, 1.0 - p) / (1.0 - p);
}

// U(d) with dU/dd = |F(d)| (attraction positive) for the unclamped power law
// with its repulsive core; for exponent 2 and no core, -G M m / d.
double power_potential(const AttractionLaw& law, double source_mass, double target_mass, double d) {
  const double gmm = law.G * source_mass * target_mass;
  double u = law.exponent == 2.0 ? -gmm / d : gmm * power_integral(d, law.exponent);
  if (law.repulsion != 0.0) {
    u -= law.repulsion * source_mass * target_mass * power_integral(d, law.repulsion_exponent);
  }
  return u;
}

}  // namespace

Vec2 attraction(Vec2 source_position, double source_mass, Vec2 target_position, double target_mass,
                const AttractionLaw& law) {
  Vec2 force = source_position - target_position;  // p5.Vector.sub(this.position, mover.position)
  if (law.custom) {
    const double d = force.mag();
    if (d == 0.0) return {};
    const double magnitude = law.custom(d, source_mass, target_mass);
    if (!std::isfinite(magnitude)) {
      throw Error("attraction: custom force law returned " + detail::format_number(magnitude) +
                  " at distance " + detail::format_number(d));
    }
    return force.set_mag(magnitude);
  }
  // The squared clamp and softening need exponent 2 (AttractionLaw::validate):
  // they are inverse-square laws whatever the exponent says.
  if (law.inverse_square() || law.clamp == DistanceClamp::squared_distance ||
      law.softening != 0.0) {
    const auto p = laws::inverse_square_law<double>(source_position, source_mass, law);
    Vec2 out;
    laws::with_inverse_square_case(p, [&]<DistanceClamp kClamp, bool kSoftened>() {
      const auto pull = laws::inverse_square<ScalarBook, kClamp, kSoftened>(
          p, target_position.x, target_position.y, target_mass);
      out = pull.apply ? vec(pull.f) : Vec2{};
    });
    return out;
  }
  // The power laws with a repulsive core (exercise 2.13).
  if (law.clamp == DistanceClamp::distance) {
    const double d = constrain(force.mag(), law.min, law.max);
    return force.set_mag(power_strength(law, source_mass, target_mass, d));
  }
  const double d_sq = force.mag_sq();
  if (d_sq == 0.0) return {};  // coincident: no direction
  return force.set_mag(power_strength(law, source_mass, target_mass, std::sqrt(d_sq)));
}

double attraction_potential(double distance, double source_mass, double target_mass,
                            const AttractionLaw& law) {
  if (law.custom) {
    throw Error("attraction_potential: a custom force law has no known potential");
  }
  double lo = 0.0;
  double hi = 0.0;
  switch (law.clamp) {
    case DistanceClamp::none:
      if (law.softening != 0.0) {
        const double gmm = law.G * source_mass * target_mass;
        return -gmm / std::sqrt(distance * distance + law.softening * law.softening);
      }
      if (distance == 0.0) {
        throw Error("attraction_potential: unbounded at distance 0 without softening");
      }
      return power_potential(law, source_mass, target_mass, distance);
    case DistanceClamp::distance:
      lo = law.min;
      hi = law.max;
      break;
    case DistanceClamp::squared_distance:
      lo = std::sqrt(law.min);
      hi = std::sqrt(law.max);
      break;
  }
  // The force is constant below lo and above hi, so U continues linearly
  // there with the slope it has at the clamp: continuous everywhere.
  if (distance < lo) {
    return power_potential(law, source_mass, target_mass, lo) +
           power_strength(law, source_mass, target_mass, lo) * (distance - lo);
  }
  if (distance > hi) {
    return power_potential(law, source_mass, target_mass, hi) +
           power_strength(law, source_mass, target_mass, hi) * (distance - hi);
  }
  return power_potential(law, source_mass, target_mass, distance);
}

}  // namespace calder
