// SPDX-License-Identifier: MIT
#include "calder/forces.hpp"

#include <cmath>
#include <string>

#include "calder/detmath.hpp"
#include "calder/error.hpp"
#include "calder/random.hpp"

namespace calder {

Vec2 gravity(Vec2 g, double mass, bool scale_by_mass) {
  // p5.Vector.mult(gravity, mass): (0 * m, 0.1 * m), component by component.
  return scale_by_mass ? g * mass : g;
}

Vec2 helium(double lift) { return {0.0, -lift}; }

Vec2 noise_wind(const Noise& noise, double time, double strength, double rate, double offset) {
  const double n = noise.noise(offset + time * rate);
  return {map_range(n, 0.0, 1.0, -strength, strength), 0.0};
}

Vec2 fan(Vec2 fan_position, Vec2 body_position, double strength, double reach) {
  Vec2 away = body_position - fan_position;
  const double d = away.mag();
  if (d == 0.0 || d >= reach) return {};
  return away.set_mag(strength * (1.0 - d / reach));
}

Vec2 edge_force(Vec2 position, double width, double height, double strength, double margin) {
  // Inward push for one edge at distance d: zero at the margin, growing toward the edge.
  const auto push = [&](double d) { return d < margin ? strength * (margin - d) / margin : 0.0; };
  return {push(position.x) - push(width - position.x),
          push(position.y) - push(height - position.y)};
}

Vec2 friction(Vec2 velocity, double mu, double normal) {
  // The book: friction = velocity.copy(); friction.mult(-1); friction.setMag(c * normal).
  Vec2 f = velocity;
  f.mult(-1.0);
  f.set_mag(mu * normal);
  return f;
}

Vec2 drag(Vec2 velocity, double c, double area) {
  // The book: speed = v.mag(); dragMagnitude = c * speed * speed; the force is
  // -v with that magnitude. area = 1 leaves every bit as the book has it.
  const double speed = velocity.mag();
  const double magnitude = c * speed * speed * area;
  Vec2 f = velocity;
  f.mult(-1.0);
  f.set_mag(magnitude);
  return f;
}

Vec2 limit_drag(Vec2 drag_force, Vec2 velocity, double mass, double dt) {
  // One step changes the velocity by F / m * dt; keep that within |v|.
  return drag_force.limit(mass * velocity.mag() / dt);
}

Vec2 lift(Vec2 velocity, double coefficient) {
  const double speed_sq = velocity.mag_sq();
  // Perpendicular on the left of the motion with y down: (vy, -vx).
  Vec2 f{velocity.y, -velocity.x};
  return f.set_mag(coefficient * speed_sq);
}

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
  switch (law.clamp) {
    case DistanceClamp::distance: {
      double d = force.mag();
      d = constrain(d, law.min, law.max);
      return force.set_mag(power_strength(law, source_mass, target_mass, d));
    }
    case DistanceClamp::squared_distance: {
      const double dsq = constrain(force.mag_sq(), law.min, law.max);
      return force.set_mag(strength_of(law.G, source_mass, target_mass, dsq, law.product));
    }
    case DistanceClamp::none:
      break;
  }
  const double d_sq = force.mag_sq();
  if (d_sq == 0.0) return {};  // coincident: no direction (softened force is zero there too)
  if (law.softening == 0.0) {
    if (law.exponent == 2.0 && law.repulsion == 0.0) {
      return force.set_mag(strength_of(law.G, source_mass, target_mass, d_sq, law.product));
    }
    return force.set_mag(power_strength(law, source_mass, target_mass, std::sqrt(d_sq)));
  }
  // Plummer: |F| = G M m d / (d^2 + eps^2)^(3/2).
  const double s_sq = d_sq + law.softening * law.softening;
  const double d = std::sqrt(d_sq);
  return force.set_mag(
      strength_of(law.G, source_mass, target_mass, s_sq * std::sqrt(s_sq), law.product) * d);
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
