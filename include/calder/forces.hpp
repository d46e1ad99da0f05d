// SPDX-License-Identifier: MIT
// calder: the force laws of chapter 2, each one function returning a force.
//
// Book-style code calls them directly; the fields of calder/fields.hpp apply
// the same laws to all bodies of a world each step. Each law is written once,
// with its field kind (src/field_kinds/), and these functions run it for
// one body:
//
//   mover.apply_force(calder::friction(mover.velocity(), 0.1));
//
// Units are the book's: pixels, frames, and masses with no particular unit;
// y points down. The arithmetic of the laws that the book's examples use
// follows their p5.js code operation by operation (shared/spec/chapter2.md),
// so that calder reproduces those sketches to the last bits.
#pragma once

#include <array>
#include <functional>
#include <string_view>

#include "calder/names.hpp"
#include "calder/vec2.hpp"

namespace calder {

class Noise;

// --- made-up forces ---

// Uniform gravity, (0, g) with y down. Scaled by mass it is g * mass, so that
// every body falls with the same acceleration (example 2.3).
Vec2 gravity(Vec2 g, double mass, bool scale_by_mass);

// Helium: a constant upward force of the given strength, (0, -lift).
Vec2 helium(double lift);

// Wind from Perlin noise over time (exercise 2.1): a horizontal force
// map(noise(offset + time * rate), 0, 1, -strength, strength). It changes
// smoothly; rate sets how fast, offset picks another stretch of noise.
Vec2 noise_wind(const Noise& noise, double time, double strength, double rate = 0.01,
                double offset = 0.0);

// A fan at fan_position blowing away from it (exercise 2.5). The magnitude
// falls off linearly with distance d: strength * (1 - d / reach) for d < reach,
// zero beyond reach and at the fan's own position (no direction there).
Vec2 fan(Vec2 fan_position, Vec2 body_position, double strength, double reach);

// An invisible force pushing a body back from the canvas edges (exercise 2.3).
// Within margin of an edge it points inward with magnitude
// strength * (margin - d) / margin, d the distance to that edge: zero at the
// margin, strength at the edge, stronger still past it. The four edges add up.
Vec2 edge_force(Vec2 position, double width, double height, double strength, double margin);

// --- modeled forces ---

// Kinetic friction: -mu * N * v-hat. The book takes N = 1. A body at rest
// feels none (the direction is undefined; set_mag keeps zero at zero).
// Computed as the book does: copy v, multiply by -1, set_mag(mu * N).
Vec2 friction(Vec2 velocity, double mu, double normal = 1.0);

// Quadratic drag: magnitude (c * |v|) * |v| * area against the velocity. The
// book folds -1/2 rho A Cd into c; area brings the frontal area back
// (exercise 2.9) and is 1 by default.
Vec2 drag(Vec2 velocity, double c, double area = 1.0);

// Limits a drag (or any resistive) force so that, applied alone for one step of dt to a body of
// this mass, it can slow the body to rest but never reverse it (exercise 2.8):
// |F| <= mass * |v| / dt.
Vec2 limit_drag(Vec2 drag_force, Vec2 velocity, double mass, double dt);

// Lift: perpendicular to the velocity, magnitude coefficient * |v|^2, on the
// left of the motion in a y-down canvas (a body moving right is lifted up).
// A negative coefficient pushes the other way.
Vec2 lift(Vec2 velocity, double coefficient);

// --- attraction ---

// What is clamped before the inverse-square law is applied: the one list of
// the inverse-square laws, shared by the core, calder::nbody (nbody::Law is
// this enum) and calder::bulk.
enum class DistanceClamp {
  distance,          // d = constrain(|r|, min, max); strength / (d * d)   (examples 2.6-2.9)
  squared_distance,  // dsq = constrain(|r|^2, min, max); strength / dsq   (exercise 2.16)
  none,              // physical: strength / (|r|^2 + softening^2), Plummer softening
  // The same laws by the names calder::nbody's kernels use.
  clamp_distance = distance,
  clamp_squared_distance = squared_distance,
  plummer = none,
};

// The laws' names, as scene files, Python and the web page spell them.
using DistanceClampName = EnumName<DistanceClamp>;
inline constexpr std::array<DistanceClampName, 3> kDistanceClampNames{{
    {"distance", DistanceClamp::distance},
    {"squared_distance", DistanceClamp::squared_distance},
    {"none", DistanceClamp::none},
}};

// How G and the two masses are multiplied. The sketches differ in the last
// bits: (G * M) * m in examples 2.6, 2.7 and 2.9; G * (M * m) in 2.8 and 2.16.
enum class MassProduct { left_to_right, masses_first };

// A force law of distance and masses for custom attraction (exercise 2.13):
// returns the signed magnitude, positive toward the source, negative away.
using ForceLaw = std::function<double(double distance, double source_mass, double target_mass)>;

// Gravitational attraction, as the book models it. G < 0 repels.
struct AttractionLaw {
  double G = 1.0;
  DistanceClamp clamp = DistanceClamp::distance;
  double min = 5.0;        // lower bound of the clamped quantity (distance, or squared distance)
  double max = 25.0;       // upper bound of the clamped quantity
  double softening = 0.0;  // Plummer epsilon; only with DistanceClamp::none (else an error)
  MassProduct product = MassProduct::left_to_right;
  // Other force laws of distance, as data (exercise 2.13): the attraction
  // is G M m / d^exponent (2: Newton; 1 or less: weaker when close), minus a
  // repulsive core repulsion * M * m / d^repulsion_exponent, so with
  // repulsion_exponent > exponent bodies attract far and repel near. With the
  // distance clamp or no clamp; softening and the squared clamp need exponent 2.
  double exponent = 2.0;
  double repulsion = 0.0;
  double repulsion_exponent = 3.0;
  ForceLaw custom;  // when set, replaces the law above (G, clamp, ... unused)

  // The book's law: d clamped to [min_distance, max_distance].
  static AttractionLaw book(double G = 1.0, double min_distance = 5.0, double max_distance = 25.0,
                            MassProduct product = MassProduct::left_to_right);
  // Newton's law with optional Plummer softening, no clamp (for physical runs).
  static AttractionLaw newtonian(double G = 1.0, double softening = 0.0);
  // A custom law of distance (exercise 2.13).
  static AttractionLaw from(ForceLaw law);

  // Throws calder::Error naming `where` and the field for a bad parameter.
  void validate(const char* where) const;
  // Whether this is one of the inverse-square laws of DistanceClamp (no
  // custom law, exponent 2, no repulsive core): the laws that calder::nbody's
  // and calder::bulk's kernels run.
  [[nodiscard]] bool inverse_square() const {
    return !custom && exponent == 2.0 && repulsion == 0.0;
  }
};

// The force that a source (an attractor, or another body) at source_position
// with source_mass exerts on a target at target_position with target_mass:
// r = source - target; |F| from the law; F = r.set_mag(|F|). Zero when the two
// positions coincide (no direction). The force on the source is exactly -F.
Vec2 attraction(Vec2 source_position, double source_mass, Vec2 target_position, double target_mass,
                const AttractionLaw& law);

// The potential energy of a source-target pair under the law, zero at
// infinity for the unclamped law. For the clamped laws the force is constant
// below and above the clamp, so the potential is linear there and continuous
// everywhere (taken as -G M m / d inside the clamp). Throws calder::Error for
// a custom law, whose potential calder does not know.
double attraction_potential(double distance, double source_mass, double target_mass,
                            const AttractionLaw& law);

}  // namespace calder
