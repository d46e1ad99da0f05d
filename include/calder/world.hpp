// SPDX-License-Identifier: MIT
// calder: the world, its bodies, and the book-style Mover handle.
//
// A World keeps its bodies in contiguous arrays (one array per quantity), so
// that whole-world steps run over plain memory; bodies are named by BodyId
// handles, as in Box2D. Book-style code works through Mover, a small handle
// with the book's vocabulary:
//
//   calder::World world;
//   calder::Mover mover = world.add_mover({.position = {320, 30}, .mass = 1});
//   mover.apply_force({0, 0.1});   // acceleration += force / mass
//   mover.update();                // velocity += acceleration; position += velocity
//
// or a world steps all bodies under its fields with one call, world.step().
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "calder/adaptive.hpp"
#include "calder/backends.hpp"
#include "calder/body_columns.hpp"
#include "calder/fields.hpp"
#include "calder/names.hpp"
#include "calder/random.hpp"
#include "calder/vec2.hpp"

namespace calder {

enum class Integrator {
  semi_implicit_euler,  // the book's update: v += a dt; x += v dt (first order, symplectic)
  velocity_verlet,      // kick-drift-kick, second order, symplectic for position forces
  rk4,                  // classic fourth-order Runge-Kutta
  // IAS15 (Rein & Spiegel 2015): 15th-order Gauss-Radau predictor-corrector
  // with an adaptive internal step, to machine precision for smooth forces.
  // A step() still advances exactly dt: as many internal steps as needed,
  // the last ending on the frame (calder/adaptive.hpp).
  ias15,
  // Yoshida's (1990) compositions of velocity Verlet: 4th order (3 substeps)
  // and 6th order (7 substeps, his solution A); fixed step, symplectic for
  // position forces, for long smooth runs.
  yoshida4,
  yoshida6,
};

// IAS15's default tolerance (WorldDef::tolerance): Rein & Spiegel's epsilon.
inline constexpr double kDefaultTolerance = 1e-9;

// When bodies are moved relative to the forces acting on them.
enum class UpdateOrder {
  simultaneous,  // all forces from one state, then all bodies move (default)
  sequential,    // body by body: forces on i, move i, then i + 1 (example 2.9)
};

enum class BoundaryKind { none, bounce, wrap };

// Whether the boundary rule runs after the update (examples 2.1-2.3, 2.5) or
// before it (example 2.4: forces, then bounce, then update).
enum class BoundaryTiming { after_update, before_update };

struct Edges {
  bool left = true;
  bool right = true;
  bool top = true;
  bool bottom = true;
};

// What happens at the canvas edges.
struct Boundary {
  BoundaryKind kind = BoundaryKind::none;
  // Bounce: the velocity component is multiplied by -restitution (book: 1 or 0.9).
  double restitution = 1.0;
  // Bounce when the circle's edge touches the wall, not its centre (exercise 2.4);
  // wrap once the whole circle has left. Wrapping is periodic: a body that
  // leaves by d past one side comes back d inside the other (the book's
  // chapter 1 puts it exactly on the edge instead; periodic keeps motion smooth).
  bool use_radius = false;
  Edges edges{};
  BoundaryTiming timing = BoundaryTiming::after_update;
  // Bounce: the walls stand this many pixels inside the canvas (exercise
  // 2.1's ceiling: 1, the balloon's stroke weight).
  double inset = 0.0;
  // Wrap: true, periodic (above); false, the book's rule of exercise 2.1
  // and chapter 1: a body past one side is put on the other side, x > w + r
  // gives x = -r and x < -r gives x = w + r (two separate checks; y the same).
  bool periodic = true;

  static Boundary none() { return {}; }
  static Boundary bounce(double restitution = 1.0, bool use_radius = false, Edges edges = {}) {
    return {BoundaryKind::bounce,         restitution, use_radius, edges,
            BoundaryTiming::after_update, 0.0,         true};
  }
  static Boundary wrap(bool use_radius = false) {
    return {BoundaryKind::wrap, 1.0, use_radius, {}, BoundaryTiming::after_update, 0.0, true};
  }
  void validate(const char* where) const;
};

// The arithmetic of the per-body fields (everything but mutual attraction
// and custom forces) when the world steps with calder::bulk's kernels.
enum class Arithmetic {
  // IEEE double, operation by operation in the book's order: the same bits
  // as the plain loops, so p5.js sketches are reproduced exactly. The kernels
  // (when installed) vectorise and thread it without changing any bit.
  book,
  // double, with fused multiply-adds and reciprocals (a / m as a * (1 / m),
  // (g m) / m as g): ~1e-16 relative per step from book, about twice as fast.
  float64,
  // float32 pair arithmetic and state during each batch of steps (the state
  // is kept in double between batches): ~1e-7 relative per step, for speed
  // with millions of bodies.
  float32,
};

// Every arithmetic by its name ("book", "float64", "float32"): the one list
// that scene files, the command line and messages use.
using ArithmeticName = EnumName<Arithmetic>;
inline constexpr std::array<ArithmeticName, 3> kArithmeticNames{{
    {"book", Arithmetic::book},
    {"float64", Arithmetic::float64},
    {"float32", Arithmetic::float32},
}};
// Its name in kArithmeticNames.
[[nodiscard]] constexpr std::string_view arithmetic_name(Arithmetic arithmetic) {
  return name_in(kArithmeticNames, arithmetic);
}

// The most threads a world or a mutual attraction may ask for (a scene file,
// a snapshot, the API: one check), and the most steps a world's clock counts
// (the count stays exact as a double and far from wrapping).
inline constexpr int max_threads = 1024;
inline constexpr std::int64_t max_step_count = std::int64_t{1} << 53;

// Every integrator by its name, as scene files and the command line spell it.
using IntegratorName = EnumName<Integrator>;
inline constexpr std::array<IntegratorName, 6> kIntegratorNames{{
    {"semi_implicit_euler", Integrator::semi_implicit_euler},
    {"velocity_verlet", Integrator::velocity_verlet},
    {"rk4", Integrator::rk4},
    {"ias15", Integrator::ias15},
    {"yoshida4", Integrator::yoshida4},
    {"yoshida6", Integrator::yoshida6},
}};
// Its name in kIntegratorNames.
[[nodiscard]] constexpr std::string_view integrator_name(Integrator integrator) {
  return name_in(kIntegratorNames, integrator);
}

struct WorldDef {
  double width = 640.0;
  double height = 240.0;
  double dt = 1.0;  // one frame, as in the book
  Integrator integrator = Integrator::semi_implicit_euler;
  UpdateOrder update_order = UpdateOrder::simultaneous;
  Boundary boundary{};
  std::uint32_t seed = 0;  // seeds the world's random() and noise()
  // float64 and float32 need calder::bulk's kernels (backends) and a world it has
  // kernels for (semi-implicit Euler, simultaneous, no custom force or
  // mutual attraction); World::step throws calder::Error otherwise.
  Arithmetic arithmetic = Arithmetic::book;
  // Threads of the whole-world kernels: 0 = every core, n > 0 = n, at most
  // max_threads. Results are bit-identical for any number.
  int threads = 0;
  // The book's topSpeed: > 0 limits each body's speed after v += a dt, as
  // p5's vel.limit(topSpeed) (semi_implicit_euler, book arithmetic); 0, none.
  double max_speed = 0.0;
  // The whole-world kernels of this world (calder/backends.hpp); null: the
  // process defaults, the kernels of calder::bulk and calder::nbody when the
  // program links them.
  Backends backends{};
  // ias15: the step criterion's epsilon (Pham, Rein & Spiegel 2024), > 0;
  // smaller is more accurate and slower. Other integrators ignore it.
  double tolerance = kDefaultTolerance;
};

struct BodyDef {
  Vec2 position{};
  Vec2 velocity{};
  double mass = 1.0;    // > 0
  double radius = 0.0;  // >= 0; 0: a point
  // Own friction coefficient (exercise 2.6); unset: the Friction field's mu.
  std::optional<double> friction = std::nullopt;
  double drag_area = 1.0;  // frontal area scaling drag (exercise 2.9)

  // Throws calder::Error naming `where` and the field unless add_body would
  // accept it (lets a caller check a batch before adding any of it).
  void validate(const char* where) const;
};

// Bodies as arrays, for World::add_bodies: each column holds one value per
// body, or one value for all, or none (BodyDef's default; friction NaN:
// none of its own). The accelerations (ax, ay) start at 0: not an input.
using BodyColumns = BodyColumnsOf<std::span<const double>>;

struct BodyId {
  std::uint32_t index = UINT32_MAX;
  friend bool operator==(BodyId a, BodyId b) { return a.index == b.index; }
};

class Mover;

class World {
 public:
  explicit World(const WorldDef& def = {});

  // --- bodies ---
  BodyId add_body(const BodyDef& def);
  Mover add_mover(const BodyDef& def);
  // Adds many bodies from arrays, all or none: each is checked as add_body
  // checks it (the message names its index) before any is added; the arrays
  // grow once. Returns the first's id.
  BodyId add_bodies(const BodyColumns& columns);
  Mover mover(BodyId id);
  [[nodiscard]] std::size_t body_count() const { return bodies_.x.size(); }
  [[nodiscard]] BodyId body(std::size_t index) const;  // the id of the index-th body
  void clear_bodies();

  [[nodiscard]] Vec2 position(BodyId id) const;
  [[nodiscard]] Vec2 velocity(BodyId id) const;
  // The acceleration accumulated since the last update of this body.
  [[nodiscard]] Vec2 acceleration(BodyId id) const;
  [[nodiscard]] double mass(BodyId id) const;
  [[nodiscard]] double radius(BodyId id) const;
  [[nodiscard]] std::optional<double> friction(BodyId id) const;
  [[nodiscard]] double drag_area(BodyId id) const;
  void set_position(BodyId id, Vec2 position);
  void set_velocity(BodyId id, Vec2 velocity);
  void set_mass(BodyId id, double mass);
  void set_radius(BodyId id, double radius);
  void set_friction(BodyId id, std::optional<double> mu);
  void set_drag_area(BodyId id, double area);

  // Newton's second law, one force at a time: acceleration += force / mass.
  // The caller's force is taken by value and never changed. Throws (changing
  // nothing) if the force or the resulting acceleration is not finite.
  void apply_force(BodyId id, Vec2 force);
  // The book's update() for one body: semi-implicit Euler with the world's
  // dt, then the accumulated acceleration is cleared. Throws (changing
  // nothing) if the result would not be finite.
  void update(BodyId id);
  // Applies a boundary rule (the world's, or another) to one body now.
  void apply_boundary(BodyId id);
  void apply_boundary(BodyId id, const Boundary& boundary);
  // Whether the body touches a canvas edge: within `tolerance` of it,
  // counting its radius (book 2.4: contactEdge is y > height - radius - 1).
  [[nodiscard]] bool touching(BodyId id, Edge edge, double tolerance = 1.0) const;

  // --- fields ---
  // Stores a field and returns a reference that stays valid until clear_fields().
  template <class F>
  F& add(F field) {
    return std::get<F>(add_field(Field{std::move(field)}));
  }
  // Stores a field given as the variant (scenes build these from data).
  Field& add_field(Field field);
  [[nodiscard]] const std::deque<Field>& fields() const { return fields_; }
  // The index-th field, in the order added; throws calder::Error if out of range.
  [[nodiscard]] Field& field(std::size_t index);
  void clear_fields() { fields_.clear(); }

  // --- stepping ---
  // Advances every body by dt: the accumulated forces plus the fields, the
  // integrator, the boundary rule. Either the step completes, or it throws
  // calder::Error and leaves the world exactly as it was: when a field's
  // parameters are invalid, or when a position or velocity would become NaN
  // or infinite (a custom force returning NaN, an overflow); the message
  // names the field or the body. Never a silent NaN.
  void step();
  // count steps. Large worlds (and the float64 / float32 arithmetic) go
  // through calder::bulk's kernels when installed, a batch of up to
  // kBatchSteps steps at a time, each body advanced through the whole batch
  // while it sits in cache. With book arithmetic the bits are those of
  // count calls to step(); if a step fails the world is left as step() would
  // leave it. With float64 / float32, a failed batch leaves the world as it
  // was at the batch's start.
  void step(int count);
  static constexpr int kBatchSteps = 128;

  [[nodiscard]] double time() const { return time_; }
  [[nodiscard]] std::int64_t step_count() const { return step_count_; }
  [[nodiscard]] double dt() const { return def_.dt; }
  void set_dt(double dt);
  [[nodiscard]] Integrator integrator() const { return def_.integrator; }
  void set_integrator(Integrator integrator) { def_.integrator = integrator; }
  [[nodiscard]] double tolerance() const { return def_.tolerance; }
  void set_tolerance(double tolerance);
  // What the adaptive integrator counted since the world was made (or
  // restored): internal steps, rejections, force evaluations, the smallest
  // step and the closest approach (calder/adaptive.hpp).
  [[nodiscard]] const AdaptiveStats& adaptive_stats() const { return adaptive_.stats; }
  // What it carries from one step() to the next (the internal step, the
  // predictor, the compensated sums): saved by snapshots so that a resumed
  // run is the uninterrupted one bit for bit.
  [[nodiscard]] const AdaptiveState& adaptive_state() const { return adaptive_; }
  // Puts such a state back. Throws calder::InvalidArgument, changing
  // nothing, for arrays that don't fit the bodies or a non-finite value.
  void restore_adaptive(const AdaptiveState& state);
  [[nodiscard]] UpdateOrder update_order() const { return def_.update_order; }
  void set_update_order(UpdateOrder order) { def_.update_order = order; }
  [[nodiscard]] const Boundary& boundary() const { return def_.boundary; }
  void set_boundary(const Boundary& boundary);
  [[nodiscard]] Arithmetic arithmetic() const { return def_.arithmetic; }
  void set_arithmetic(Arithmetic arithmetic) { def_.arithmetic = arithmetic; }
  [[nodiscard]] int threads() const { return def_.threads; }
  [[nodiscard]] double max_speed() const { return def_.max_speed; }
  void set_threads(int threads);
  [[nodiscard]] double width() const { return def_.width; }
  [[nodiscard]] double height() const { return def_.height; }
  // The settings the world was made with, as the setters above changed them.
  [[nodiscard]] const WorldDef& def() const { return def_; }

  // The world's p5-compatible generators, seeded with WorldDef::seed.
  Random& random() { return random_; }
  [[nodiscard]] const Random& random() const { return random_; }
  Noise& noise() { return noise_; }
  [[nodiscard]] const Noise& noise() const { return noise_; }

  // Read-only view of all bodies (contiguous arrays), e.g. for diagnostics.
  [[nodiscard]] BodyView bodies() const;

  // Puts back what a snapshot (calder/snapshot.hpp) holds beyond the bodies'
  // other columns, the fields and the generators: the clock, and the
  // accelerations accumulated since the last update (add_bodies starts them
  // at 0). Throws calder::InvalidArgument, changing nothing, for a value that
  // is not finite, a negative step count or columns of another length.
  void restore(double time, std::int64_t step_count, std::span<const double> ax,
               std::span<const double> ay);

 private:
  std::size_t checked(BodyId id, const char* where) const;
  void append(const BodyDef& def);  // a body already checked
  void save_state();
  void restore_state();
  FieldContext context(const BodyView& view, double time) const;
  void accumulate_fields(const FieldContext& context, std::size_t first, std::size_t last,
                         std::span<double> ax, std::span<double> ay) const;
  void boundary_one(std::size_t i, const Boundary& boundary);
  void step_euler_simultaneous();
  void step_euler_sequential();
  void step_multistage();
  void step_ias15();
  void ias15_substeps(double frame_dt, std::span<const double> applied_ax,
                      std::span<const double> applied_ay);
  void advance_clock();
  void step_one();
  void check_step_settings() const;
  void check_adaptive_settings() const;
  bool step_batch(int steps);
  void advance_noise(int steps);
  [[nodiscard]] std::string needs_plain_loops() const;  // "" or what the kernels lack
  void check_finite(const char* where) const;

  WorldDef def_;
  // Structure of arrays: body i is index i of each.
  BodyColumnsOf<std::vector<double>> bodies_;
  std::deque<Field> fields_;
  Random random_;
  Noise noise_;
  double time_ = 0.0;
  std::int64_t step_count_ = 0;
  AdaptiveState adaptive_;
  // Scratch space of the multi-stage integrators, and the state saved at the
  // start of a step; kept to avoid reallocation.
  std::vector<double> scratch_;
  std::vector<double> saved_;
};

// A handle to one body with the book's vocabulary. Cheap to copy; valid as
// long as its world is.
class Mover {
 public:
  Mover(World& world, BodyId id) : world_(&world), id_(id) {}

  void apply_force(Vec2 force) { world_->apply_force(id_, force); }
  void update() { world_->update(id_); }
  // The world's boundary rule now (book: checkEdges / bounceEdges).
  void check_edges() { world_->apply_boundary(id_); }
  void check_edges(const Boundary& boundary) { world_->apply_boundary(id_, boundary); }
  // Touching the bottom edge within tolerance (book: contactEdge).
  [[nodiscard]] bool contact_edge(double tolerance = 1.0) const {
    return world_->touching(id_, Edge::bottom, tolerance);
  }

  [[nodiscard]] Vec2 position() const { return world_->position(id_); }
  [[nodiscard]] Vec2 velocity() const { return world_->velocity(id_); }
  [[nodiscard]] Vec2 acceleration() const { return world_->acceleration(id_); }
  [[nodiscard]] double mass() const { return world_->mass(id_); }
  [[nodiscard]] double radius() const { return world_->radius(id_); }
  void set_position(Vec2 position) { world_->set_position(id_, position); }
  void set_velocity(Vec2 velocity) { world_->set_velocity(id_, velocity); }

  // The force this body exerts on another under a law (book: body.attract(other)).
  [[nodiscard]] Vec2 attract(const Mover& other, const AttractionLaw& law = {}) const {
    return attraction(position(), mass(), other.position(), other.mass(), law);
  }

  [[nodiscard]] BodyId id() const { return id_; }
  [[nodiscard]] World& world() const { return *world_; }

 private:
  World* world_;
  BodyId id_;
};

}  // namespace calder
