// SPDX-License-Identifier: MIT
// calder: fields, the forces that act on every body of a world each step.
//
// A field is a plain struct of parameters; World::add stores it and returns a
// reference that stays valid for the world's lifetime, so a sketch can turn
// the wind on while the mouse is pressed or drag an attractor:
//
//   auto& wind = world.add(calder::Wind{.force = {0.1, 0}});
//   wind.enabled = mouse_pressed;
//
// Fields act in the order they were added, each one body at a time, and each
// force is divided by the body's mass and added to its acceleration as
// apply_force does. The laws themselves are in calder/forces.hpp.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <span>
#include <variant>

#include "calder/backends.hpp"
#include "calder/body_columns.hpp"
#include "calder/forces.hpp"
#include "calder/vec2.hpp"

namespace calder {

class Noise;

// An axis-aligned rectangle: top-left corner (x, y), width w, height h.
struct Rect {
  double x = 0.0;
  double y = 0.0;
  double w = 0.0;
  double h = 0.0;
  // Strictly inside, as the book's Liquid.contains: x < p.x < x + w, same in y.
  [[nodiscard]] bool contains(Vec2 p) const {
    return p.x > x && p.x < x + w && p.y > y && p.y < y + h;
  }
};

// A canvas edge. y points down: top is y = 0, bottom is y = height.
enum class Edge { left, right, top, bottom };

// Whether a circle of this radius at position touches a canvas edge of a
// width x height canvas within tolerance (book 2.4: y > height - radius - 1).
[[nodiscard]] bool touches_edge(Edge edge, Vec2 position, double radius, double width,
                                double height, double tolerance);

// Read-only view of the bodies' state that forces are evaluated at. During a
// multi-stage integrator step the positions and velocities are the stage's.
// (The columns are calder/body_columns.hpp's.)
struct BodyView : BodyColumnsOf<std::span<const double>> {
  [[nodiscard]] std::size_t size() const { return x.size(); }
  [[nodiscard]] Vec2 position(std::size_t i) const { return {x[i], y[i]}; }
  [[nodiscard]] Vec2 velocity(std::size_t i) const { return {vx[i], vy[i]}; }
  // The body's own friction coefficient, or fallback when it has none.
  [[nodiscard]] double friction_or(std::size_t i, double fallback) const;
};

// Everything a field may read while it acts.
struct FieldContext {
  BodyView bodies;
  double time = 0.0;  // simulation time of the state in `bodies`
  double dt = 1.0;
  double width = 640.0;
  double height = 240.0;
  const Noise* noise = nullptr;
  // The world's fast methods of MutualAttraction (calder/backends.hpp; null:
  // the process default).
  MutualAttractionBackend mutual_attraction = nullptr;
};

// --- made-up forces ---

struct Gravity {
  Vec2 g{0.0, 0.1};
  bool scale_by_mass = false;  // true: force g * mass, same fall for every mass (example 2.3)
  bool enabled = true;
};

struct Wind {
  Vec2 force{0.1, 0.0};
  bool enabled = true;
};

// Horizontal wind from Perlin noise over simulation time (see noise_wind).
struct NoiseWind {
  double strength = 0.1;
  double rate = 0.01;
  double offset = 0.0;
  bool enabled = true;
  // false: the wind at time t is noise(offset + t * rate). true: offset is
  // where the noise is read now, and the world adds rate to it after every
  // step, as a sketch's `noiseX += 0.01` (the sum drifts from offset + t * rate
  // in the last bits; exercise 2.1).
  bool accumulate = false;
};

struct Helium {
  double lift = 0.1;
  bool enabled = true;
};

// A fan at a point blowing away from it, falling off linearly to zero at reach.
struct Fan {
  Vec2 position{};
  double strength = 1.0;
  double reach = 200.0;
  bool enabled = true;
};

// Pushes bodies back from the canvas edges (exercise 2.3), see edge_force.
struct EdgeForce {
  double strength = 1.0;
  double margin = 50.0;
  bool enabled = true;
};

// --- modeled forces ---

// Kinetic friction on bodies touching a surface (the canvas edge `surface`,
// within `tolerance` as World::touching tells). A body's own friction
// coefficient (BodyDef::friction) replaces mu.
struct Friction {
  double mu = 0.1;
  double normal = 1.0;
  Edge surface = Edge::bottom;
  double tolerance = 1.0;
  // The book's friction can't hold a body still: near rest one step's
  // friction overshoots and the body creeps back and forth. true limits it
  // (as limit_drag does) so that it stops the body instead of reversing it.
  bool never_reverse = false;
  bool enabled = true;
};

// A liquid region: quadratic drag on bodies strictly inside it (example 2.5).
struct Liquid {
  Rect region{0.0, 120.0, 640.0, 120.0};
  double c = 0.1;
  bool never_reverse = false;  // limit the drag so it never reverses a velocity in one step
  bool enabled = true;

  [[nodiscard]] bool contains(Vec2 position) const { return region.contains(position); }
  // The drag on a body with this velocity and frontal area (book: calculateDrag).
  [[nodiscard]] Vec2 calculate_drag(Vec2 velocity, double area = 1.0) const {
    return drag(velocity, c, area);
  }
};

// Quadratic drag everywhere (air).
struct Drag {
  double c = 0.01;
  bool never_reverse = false;
  bool enabled = true;
};

// Lift perpendicular to the velocity (exercise 2.10).
struct Lift {
  double coefficient = 0.01;
  bool enabled = true;
};

// A fixed point attractor (a repulsor when law.G < 0). Not a body: it never
// moves by itself, and trajectories don't list it.
struct Attractor {
  Vec2 position{320.0, 120.0};
  double mass = 20.0;
  AttractionLaw law{};
  bool enabled = true;

  // The force it exerts on a body (book: attractor.attract(mover)).
  [[nodiscard]] Vec2 attract(Vec2 body_position, double body_mass) const {
    return attraction(position, mass, body_position, body_mass, law);
  }
};

// The order in which mutual attraction adds up its forces (it decides the
// last bits, and so whether a sketch is reproduced exactly).
enum class PairOrder {
  // Each pair once, +F on one body and exactly -F on the other: Newton's
  // third law holds exactly and momentum is conserved (the default).
  pairwise,
  // For each body i in order: the central body (if any) pulls i, then i pulls
  // every other body (exercise 2.16's galaxy).
  by_source,
};

// A fixed heavy body that is not a mover (the galaxy's sun): it pulls every
// body under the same law and is never moved.
struct CentralBody {
  Vec2 position{};
  double mass = 500.0;
};

// How mutual attraction is summed.
enum class NBodyMethod {
  // The core's loops in the order PairOrder sets: bit-faithful to the book's
  // sketches, Newton's third law exact. Any law.
  exact,
  // The same O(n^2) sum by calder::nbody's vectorised, threaded kernels
  // (different last bits; the book clamp, the squared clamp or Plummer).
  direct,
  // O(n log n) on a quadtree (calder::nbody), approximate: see theta.
  barnes_hut,
};

// Every body attracts every other (the n-body problem). In a world updated
// simultaneously all forces come from one state (see PairOrder). In a world
// updated sequentially (example 2.9), body i feels all others at their current
// positions, including the ones already moved this step.
struct MutualAttraction {
  AttractionLaw law{};
  PairOrder order = PairOrder::pairwise;
  std::optional<CentralBody> central = std::nullopt;
  NBodyMethod method = NBodyMethod::exact;
  double theta = 0.5;             // barnes_hut: opening angle in [0, 1]
  bool single_precision = false;  // direct, barnes_hut: pair sums in float32
  int threads = 0;                // direct, barnes_hut: 0 = every core
  bool enabled = true;
};

// Any force of the user's: called once per body, returns the force on body i.
using CustomForceFunction =
    std::function<Vec2(const FieldContext& context, std::size_t body_index)>;
struct CustomForce {
  CustomForceFunction force;
  bool enabled = true;
};

using Field = std::variant<Gravity, Wind, NoiseWind, Helium, Fan, EdgeForce, Friction, Liquid, Drag,
                           Lift, Attractor, MutualAttraction, CustomForce>;

// Throws calder::Error naming the field and parameter when a field's
// parameters are out of range (negative drag, zero reach, NaN, ...).
void validate(const Field& field);

// A field's name as error messages and scene files spell it ("gravity", ...).
const char* field_name(const Field& field);

// Adds the field's acceleration (force / mass, one body at a time) to
// (ax, ay) for bodies [first, last). Does nothing when the field is disabled.
// MutualAttraction over all bodies uses the pairwise (third-law) form; over a
// sub-range, each target feels every other body in index order.
void accumulate(const Field& field, const FieldContext& context, std::size_t first,
                std::size_t last, std::span<double> ax, std::span<double> ay);

}  // namespace calder
