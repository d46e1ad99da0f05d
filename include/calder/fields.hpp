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
#include <string>
#include <tuple>
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

// Barnes-Hut's opening angle unless a field or calder::nbody's options say
// otherwise: the largest of 0.8, 0.75, 0.7, ... whose RMS relative force error
// on a uniform disk of 10^6 bodies is clearly below 1e-3 with multipoles to
// fourth order (6.4e-4; 0.75 gives 1.0e-3: docs/PERFORMANCE.md, "Barnes-Hut").
// The clamped laws, summed with monopoles, err more (calder/nbody.hpp).
inline constexpr double kDefaultTheta = 0.7;

// Every body attracts every other (the n-body problem). In a world updated
// simultaneously all forces come from one state (see PairOrder). In a world
// updated sequentially (example 2.9), body i feels all others at their current
// positions, including the ones already moved this step.
struct MutualAttraction {
  AttractionLaw law{};
  PairOrder order = PairOrder::pairwise;
  std::optional<CentralBody> central = std::nullopt;
  NBodyMethod method = NBodyMethod::exact;
  double theta = kDefaultTheta;   // barnes_hut: opening angle in [0, 1]
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

// --- every field kind described once ---
//
// FieldKind<F> describes the field kind F: its name and its parameters, each
// with its scene-file key, the values it accepts and when a file lists it.
// field_name, validate, accumulate, the scene reader and the TOML writer all
// work from it (they std::visit Field, so a kind without a FieldKind doesn't
// compile).

// The values a parameter accepts (every number of a Vec2 or a Rect: finite).
enum class Range {
  finite,
  positive,
  non_negative,
  // [0, 1]. A scene file's reader checks >= 0 at the value, validate the rest.
  unit_interval,
};

template <class F, class T>
struct Parameter {
  const char* key;  // in scene files and messages
  T F::*member;
  Range range = Range::finite;
  // When to_toml writes it (nullptr: always; false: left out, so the default applies).
  bool (*written)(const F&) = nullptr;
};

// Specialised for every alternative of Field below. Besides name and
// parameters a kind may have:
//   static constexpr bool in_scene_files = false;  // C++ code, no scene-file form
//   static constexpr auto position = &F::position; // it can follow the mouse
//   static void check(const F&, const std::string& where);  // rules across parameters
//   // The force on body i, for a kind that acts on each body on its own
//   // (the others have their own branch in accumulate).
//   static Vec2 force(const F&, const FieldContext&, std::size_t i);
template <class F>
struct FieldKind;

namespace field_kind_detail {
template <class F, class T>
F owner_of(T F::*);
constexpr bool fast_method(const MutualAttraction& f) { return f.method != NBodyMethod::exact; }
}  // namespace field_kind_detail

// Parameter::written for a parameter written only when it is not the default.
template <auto member>
constexpr bool differs(const decltype(field_kind_detail::owner_of(member))& field) {
  using F = decltype(field_kind_detail::owner_of(member));
  return !(field.*member == F{}.*member);
}

template <>
struct FieldKind<Gravity> {
  static constexpr const char* name = "gravity";
  static constexpr auto parameters = std::tuple{
      Parameter<Gravity, Vec2>{"g", &Gravity::g},
      Parameter<Gravity, bool>{"scale_by_mass", &Gravity::scale_by_mass},
  };
};

template <>
struct FieldKind<Wind> {
  static constexpr const char* name = "wind";
  static constexpr auto parameters = std::tuple{Parameter<Wind, Vec2>{"force", &Wind::force}};
};

template <>
struct FieldKind<NoiseWind> {
  static constexpr const char* name = "noise_wind";
  static constexpr auto parameters = std::tuple{
      Parameter<NoiseWind, double>{"strength", &NoiseWind::strength},
      Parameter<NoiseWind, double>{"rate", &NoiseWind::rate},
      Parameter<NoiseWind, double>{"offset", &NoiseWind::offset},
      Parameter<NoiseWind, bool>{"accumulate", &NoiseWind::accumulate, Range::finite,
                                 differs<&NoiseWind::accumulate>},
  };
};

template <>
struct FieldKind<Helium> {
  static constexpr const char* name = "helium";
  static constexpr auto parameters = std::tuple{Parameter<Helium, double>{"lift", &Helium::lift}};
};

template <>
struct FieldKind<Fan> {
  static constexpr const char* name = "fan";
  static constexpr auto parameters = std::tuple{
      Parameter<Fan, Vec2>{"position", &Fan::position},
      Parameter<Fan, double>{"strength", &Fan::strength},
      Parameter<Fan, double>{"reach", &Fan::reach, Range::positive},
  };
  static constexpr auto position = &Fan::position;
  static Vec2 force(const Fan& f, const FieldContext& c, std::size_t i) {
    return fan(f.position, c.bodies.position(i), f.strength, f.reach);
  }
};

template <>
struct FieldKind<EdgeForce> {
  static constexpr const char* name = "edge_force";
  static constexpr auto parameters = std::tuple{
      Parameter<EdgeForce, double>{"strength", &EdgeForce::strength},
      Parameter<EdgeForce, double>{"margin", &EdgeForce::margin, Range::positive},
  };
  static Vec2 force(const EdgeForce& f, const FieldContext& c, std::size_t i) {
    return edge_force(c.bodies.position(i), c.width, c.height, f.strength, f.margin);
  }
};

template <>
struct FieldKind<Friction> {
  static constexpr const char* name = "friction";
  static constexpr auto parameters = std::tuple{
      Parameter<Friction, double>{"mu", &Friction::mu, Range::non_negative},
      Parameter<Friction, double>{"normal", &Friction::normal, Range::non_negative},
      Parameter<Friction, Edge>{"surface", &Friction::surface},
      Parameter<Friction, double>{"tolerance", &Friction::tolerance, Range::non_negative},
      Parameter<Friction, bool>{"never_reverse", &Friction::never_reverse},
  };
};

template <>
struct FieldKind<Liquid> {
  static constexpr const char* name = "liquid";
  static constexpr auto parameters = std::tuple{
      Parameter<Liquid, Rect>{"region", &Liquid::region},  // w and h >= 0
      Parameter<Liquid, double>{"c", &Liquid::c, Range::non_negative},
      Parameter<Liquid, bool>{"never_reverse", &Liquid::never_reverse},
  };
};

template <>
struct FieldKind<Drag> {
  static constexpr const char* name = "drag";
  static constexpr auto parameters = std::tuple{
      Parameter<Drag, double>{"c", &Drag::c, Range::non_negative},
      Parameter<Drag, bool>{"never_reverse", &Drag::never_reverse},
  };
  static Vec2 force(const Drag& f, const FieldContext& c, std::size_t i) {
    const BodyView& b = c.bodies;
    const Vec2 force = drag(b.velocity(i), f.c, b.drag_area[i]);
    return f.never_reverse ? limit_drag(force, b.velocity(i), b.mass[i], c.dt) : force;
  }
};

template <>
struct FieldKind<Lift> {
  static constexpr const char* name = "lift";
  static constexpr auto parameters =
      std::tuple{Parameter<Lift, double>{"coefficient", &Lift::coefficient}};
  static Vec2 force(const Lift& f, const FieldContext& c, std::size_t i) {
    return lift(c.bodies.velocity(i), f.coefficient);
  }
};

template <>
struct FieldKind<Attractor> {
  static constexpr const char* name = "attractor";
  static constexpr auto parameters = std::tuple{
      Parameter<Attractor, Vec2>{"position", &Attractor::position},
      Parameter<Attractor, double>{"mass", &Attractor::mass, Range::positive},
      Parameter<Attractor, AttractionLaw>{"law", &Attractor::law},
  };
  static constexpr auto position = &Attractor::position;
  static Vec2 force(const Attractor& f, const FieldContext& c, std::size_t i) {
    return f.attract(c.bodies.position(i), c.bodies.mass[i]);
  }
};

template <>
struct FieldKind<MutualAttraction> {
  static constexpr const char* name = "mutual_attraction";
  using M = MutualAttraction;
  static constexpr auto parameters = std::tuple{
      Parameter<M, AttractionLaw>{"law", &M::law},
      Parameter<M, PairOrder>{"order", &M::order},
      Parameter<M, NBodyMethod>{"method", &M::method, Range::finite,
                                field_kind_detail::fast_method},
      Parameter<M, double>{"theta", &M::theta, Range::unit_interval,
                           field_kind_detail::fast_method},
      Parameter<M, bool>{"single_precision", &M::single_precision, Range::finite,
                         field_kind_detail::fast_method},
      Parameter<M, int>{"threads", &M::threads, Range::non_negative,
                        field_kind_detail::fast_method},
      Parameter<M, std::optional<CentralBody>>{"central", &M::central},  // position, mass > 0
  };
  // The fast methods support the inverse-square law only.
  static void check(const MutualAttraction& field, const std::string& where);
};

template <>
struct FieldKind<CustomForce> {
  static constexpr const char* name = "custom_force";
  static constexpr auto parameters = std::tuple{};
  static constexpr bool in_scene_files = false;
  // The force function is not empty.
  static void check(const CustomForce& field, const std::string& where);
};

// Whether a scene file can hold this kind of field.
template <class F>
constexpr bool in_scene_files() {
  if constexpr (requires { FieldKind<F>::in_scene_files; }) {
    return FieldKind<F>::in_scene_files;
  } else {
    return true;
  }
}

// Whether this kind has a position that can follow the mouse (FieldKind::position).
template <class F>
constexpr bool has_position() {
  return requires { FieldKind<F>::position; };
}

// Adds the field's acceleration (force / mass, one body at a time) to
// (ax, ay) for bodies [first, last). Does nothing when the field is disabled.
// MutualAttraction over all bodies uses the pairwise (third-law) form; over a
// sub-range, each target feels every other body in index order.
void accumulate(const Field& field, const FieldContext& context, std::size_t first,
                std::size_t last, std::span<double> ax, std::span<double> ay);

}  // namespace calder
