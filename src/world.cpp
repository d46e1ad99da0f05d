// SPDX-License-Identifier: MIT
#include "calder/world.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <utility>

#include "calder/error.hpp"
#include "integrate.hpp"

namespace calder {

namespace {

constexpr double kNoFriction = std::numeric_limits<double>::quiet_NaN();

// "(the world has 1 body)", "(the world has 0 bodies)": the end of an out-of-range message.
std::string world_has(std::size_t count, const char* one, const char* many) {
  return " (the world has " + std::to_string(count) + " " + (count == 1 ? one : many) + ")";
}

void require_finite_vec(Vec2 v, const char* where, const char* what) {
  detail::require_finite(v.x, where, what);
  detail::require_finite(v.y, where, what);
}

// BodyDef::validate's rules, inline so that World::add_bodies' loop over
// many bodies compiles to compares and branches.
inline void validate_body(const BodyDef& def, const char* where) {
  require_finite_vec(def.position, where, "position");
  require_finite_vec(def.velocity, where, "velocity");
  detail::require_positive(def.mass, where, "mass");
  detail::require_non_negative(def.radius, where, "radius");
  if (def.friction) detail::require_non_negative(*def.friction, where, "friction");
  detail::require_non_negative(def.drag_area, where, "drag_area");
}

}  // namespace

void BodyDef::validate(const char* where) const { validate_body(*this, where); }

void Boundary::validate(const char* where) const {
  const std::string w = std::string(where) + ": boundary";
  detail::require_non_negative(restitution, w.c_str(), "restitution");
  detail::require_non_negative(inset, w.c_str(), "inset");
}

World::World(const WorldDef& def) : def_(def), random_(def.seed), noise_(def.seed) {
  detail::require_positive(def.width, "World", "width");
  detail::require_positive(def.height, "World", "height");
  detail::require_positive(def.dt, "World", "dt");
  def.boundary.validate("World");
  detail::require_non_negative(def.max_speed, "World", "max_speed");
  if (def.threads < 0 || def.threads > max_threads) {
    throw InvalidArgument("World: threads must be between 0 and " + std::to_string(max_threads) +
                          " (got " + std::to_string(def.threads) + ")");
  }
}

std::size_t World::checked(BodyId id, const char* where) const {
  if (id.index >= bodies_.x.size()) {
    throw InvalidArgument(std::string(where) + ": no body with id " + std::to_string(id.index) +
                          world_has(bodies_.x.size(), "body", "bodies"));
  }
  return id.index;
}

BodyId World::add_body(const BodyDef& def) {
  def.validate("World::add_body");
  if (bodies_.x.size() >= UINT32_MAX) throw InvalidArgument("World::add_body: too many bodies");
  const BodyId id{static_cast<std::uint32_t>(bodies_.x.size())};
  append(def);
  return id;
}

namespace {

// A body as one value per column (accelerations 0), and back: the one place
// that knows how BodyDef's fields map onto the columns.
BodyColumnsOf<double> row_of(const BodyDef& def) {
  return {.x = def.position.x,
          .y = def.position.y,
          .vx = def.velocity.x,
          .vy = def.velocity.y,
          .mass = def.mass,
          .radius = def.radius,
          .friction = def.friction ? *def.friction : kNoFriction,
          .drag_area = def.drag_area,
          .ax = 0.0,
          .ay = 0.0};
}

BodyDef body_of(const BodyColumnsOf<double>& row) {
  return {.position = {row.x, row.y},
          .velocity = {row.vx, row.vy},
          .mass = row.mass,
          .radius = row.radius,
          .friction = std::isnan(row.friction) ? std::nullopt : std::optional<double>(row.friction),
          .drag_area = row.drag_area};
}

}  // namespace

BodyId World::add_bodies(const BodyColumns& columns) {
  if (!columns.ax.empty() || !columns.ay.empty()) {
    throw InvalidArgument("World::add_bodies: ax and ay are not inputs (accelerations start at 0)");
  }
  std::size_t n = 0;
  for_each_column([&n](const char*, std::span<const double> c) { n = std::max(n, c.size()); },
                  columns);
  for_each_column(
      [n](const char* name, std::span<const double> column) {
        if (column.size() > 1 && column.size() != n) {
          throw InvalidArgument(std::string("World::add_bodies: ") + name + " has " +
                                std::to_string(column.size()) + " values, expected " +
                                std::to_string(n) + ", 1 or none");
        }
      },
      columns);
  const BodyColumnsOf<double> defaults = row_of(BodyDef{});
  // Each column read through a pointer and a step: 1 for its own values, 0
  // for one value for all (or the default).
  BodyColumnsOf<const double*> from{};
  BodyColumnsOf<std::size_t> step{};
  for_each_column(
      [n](const char*, const double*& p, std::size_t& s, std::span<const double> column,
          const double& fallback) {
        p = column.empty() ? &fallback : column.data();
        s = column.size() == n && n > 1 ? 1 : 0;
      },
      from, step, columns, defaults);
  std::size_t i = 0;
  try {
    for (; i < n; ++i) {
      BodyColumnsOf<double> row{};
      for_each_column(
          [i](const char*, double& to, const double* p, std::size_t s) { to = p[i * s]; }, row,
          from, step);
      validate_body(body_of(row), "World::add_body");
    }
  } catch (const Error& e) {
    rethrow_with_context(e, "World::add_bodies: body " + std::to_string(i) + ": ");
  }
  const std::size_t count = body_count();
  if (n > UINT32_MAX - count) throw InvalidArgument("World::add_bodies: too many bodies");
  const BodyId first{static_cast<std::uint32_t>(count)};
  // Room once for the batch, still geometric so that many small batches stay linear.
  const std::size_t room = std::max(count + n, 2 * count);
  for_each_column(
      [n, room](const char*, std::vector<double>& array, std::span<const double> column,
                double fallback) {
        array.reserve(room);
        if (column.size() == n && n > 1) {
          array.insert(array.end(), column.begin(), column.end());
        } else {
          array.insert(array.end(), n, column.empty() ? fallback : column[0]);
        }
      },
      bodies_, columns, defaults);
  return first;
}

void World::append(const BodyDef& def) {
  for_each_column(
      [](const char*, std::vector<double>& array, double value) { array.push_back(value); },
      bodies_, row_of(def));
}

Mover World::add_mover(const BodyDef& def) { return {*this, add_body(def)}; }

Mover World::mover(BodyId id) {
  checked(id, "World::mover");
  return {*this, id};
}

BodyId World::body(std::size_t index) const {
  if (index >= bodies_.x.size()) {
    throw InvalidArgument("World::body: index " + std::to_string(index) + " out of range" +
                          world_has(bodies_.x.size(), "body", "bodies"));
  }
  return BodyId{static_cast<std::uint32_t>(index)};
}

void World::clear_bodies() {
  for_each_column([](const char*, std::vector<double>& array) { array.clear(); }, bodies_);
}

Vec2 World::position(BodyId id) const {
  const std::size_t i = checked(id, "World::position");
  return {bodies_.x[i], bodies_.y[i]};
}
Vec2 World::velocity(BodyId id) const {
  const std::size_t i = checked(id, "World::velocity");
  return {bodies_.vx[i], bodies_.vy[i]};
}
Vec2 World::acceleration(BodyId id) const {
  const std::size_t i = checked(id, "World::acceleration");
  return {bodies_.ax[i], bodies_.ay[i]};
}
double World::mass(BodyId id) const { return bodies_.mass[checked(id, "World::mass")]; }
double World::radius(BodyId id) const { return bodies_.radius[checked(id, "World::radius")]; }
std::optional<double> World::friction(BodyId id) const {
  const double f = bodies_.friction[checked(id, "World::friction")];
  return std::isnan(f) ? std::nullopt : std::optional<double>(f);
}
double World::drag_area(BodyId id) const {
  return bodies_.drag_area[checked(id, "World::drag_area")];
}

void World::set_position(BodyId id, Vec2 position) {
  const std::size_t i = checked(id, "World::set_position");
  require_finite_vec(position, "World::set_position", "position");
  bodies_.x[i] = position.x;
  bodies_.y[i] = position.y;
}
void World::set_velocity(BodyId id, Vec2 velocity) {
  const std::size_t i = checked(id, "World::set_velocity");
  require_finite_vec(velocity, "World::set_velocity", "velocity");
  bodies_.vx[i] = velocity.x;
  bodies_.vy[i] = velocity.y;
}
void World::set_mass(BodyId id, double mass) {
  const std::size_t i = checked(id, "World::set_mass");
  detail::require_positive(mass, "World::set_mass", "mass");
  bodies_.mass[i] = mass;
}
void World::set_radius(BodyId id, double radius) {
  const std::size_t i = checked(id, "World::set_radius");
  detail::require_non_negative(radius, "World::set_radius", "radius");
  bodies_.radius[i] = radius;
}
void World::set_friction(BodyId id, std::optional<double> mu) {
  const std::size_t i = checked(id, "World::set_friction");
  if (mu) detail::require_non_negative(*mu, "World::set_friction", "friction");
  bodies_.friction[i] = mu ? *mu : kNoFriction;
}
void World::set_drag_area(BodyId id, double area) {
  const std::size_t i = checked(id, "World::set_drag_area");
  detail::require_non_negative(area, "World::set_drag_area", "drag_area");
  bodies_.drag_area[i] = area;
}

void World::apply_force(BodyId id, Vec2 force) {
  const std::size_t i = checked(id, "World::apply_force");
  require_finite_vec(force, "World::apply_force", "force");
  // p5: acceleration.add(p5.Vector.div(force, mass)), one force at a time.
  const double ax = bodies_.ax[i] + force.x / bodies_.mass[i];
  const double ay = bodies_.ay[i] + force.y / bodies_.mass[i];
  if (!std::isfinite(ax) || !std::isfinite(ay)) {
    throw InvalidArgument("World::apply_force: force (" + detail::format_number(force.x) + ", " +
                          detail::format_number(force.y) + ") on body " + std::to_string(i) +
                          " of mass " + detail::format_number(bodies_.mass[i]) +
                          " gives a non-finite acceleration");
  }
  bodies_.ax[i] = ax;
  bodies_.ay[i] = ay;
}

void World::update(BodyId id) {
  const std::size_t i = checked(id, "World::update");
  double x = bodies_.x[i];
  double y = bodies_.y[i];
  double vx = bodies_.vx[i];
  double vy = bodies_.vy[i];
  double ax = bodies_.ax[i];
  double ay = bodies_.ay[i];
  detail::book_update(x, y, vx, vy, ax, ay, def_.dt, def_.max_speed);
  if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(vx) || !std::isfinite(vy)) {
    throw RunError("World::update: body " + std::to_string(i) +
                   " would get a non-finite position or velocity (overflow); left unchanged");
  }
  bodies_.x[i] = x;
  bodies_.y[i] = y;
  bodies_.vx[i] = vx;
  bodies_.vy[i] = vy;
  bodies_.ax[i] = ax;
  bodies_.ay[i] = ay;
}

void World::apply_boundary(BodyId id) { apply_boundary(id, def_.boundary); }

void World::apply_boundary(BodyId id, const Boundary& boundary) {
  const std::size_t i = checked(id, "World::apply_boundary");
  boundary.validate("World::apply_boundary");
  boundary_one(i, boundary);
}

void World::boundary_one(std::size_t i, const Boundary& b) {
  const double r = b.use_radius ? bodies_.radius[i] : 0.0;
  const double w = def_.width;
  const double h = def_.height;
  switch (b.kind) {
    case BoundaryKind::none:
      return;
    case BoundaryKind::bounce: {
      // The book's order: right before left, bottom before top; clamp, then reverse.
      const double reverse = -b.restitution;
      const double near = r + b.inset;  // the walls, in from each side
      if (b.edges.right && bodies_.x[i] > w - near) {
        bodies_.x[i] = w - near;
        bodies_.vx[i] *= reverse;
      } else if (b.edges.left && bodies_.x[i] < near) {
        bodies_.x[i] = near;
        bodies_.vx[i] *= reverse;
      }
      if (b.edges.bottom && bodies_.y[i] > h - near) {
        bodies_.y[i] = h - near;
        bodies_.vy[i] *= reverse;
      } else if (b.edges.top && bodies_.y[i] < near) {
        bodies_.y[i] = near;
        bodies_.vy[i] *= reverse;
      }
      return;
    }
    case BoundaryKind::wrap:
      if (!b.periodic) {
        // The book's two checks per axis (exercise 2.1: if (x > width) x = 0; if (x < 0) x =
        // width).
        auto to_other_side = [](double& v, double lo, double hi) {
          if (v > hi) v = lo;
          if (v < lo) v = hi;
        };
        // 0 - r: +0 rather than -0 when r is 0, as the sketch's x = 0.
        if (b.edges.left || b.edges.right) to_other_side(bodies_.x[i], 0.0 - r, w + r);
        if (b.edges.top || b.edges.bottom) to_other_side(bodies_.y[i], 0.0 - r, h + r);
        return;
      }
      if (b.edges.left || b.edges.right)
        bodies_.x[i] = detail::wrap_coordinate(bodies_.x[i], -r, w + r);
      if (b.edges.top || b.edges.bottom)
        bodies_.y[i] = detail::wrap_coordinate(bodies_.y[i], -r, h + r);
      return;
  }
}

bool World::touching(BodyId id, Edge edge, double tolerance) const {
  const std::size_t i = checked(id, "World::touching");
  detail::require_finite(tolerance, "World::touching", "tolerance");
  return touches_edge(edge, {bodies_.x[i], bodies_.y[i]}, bodies_.radius[i], def_.width,
                      def_.height, tolerance);
}

void World::set_dt(double dt) {
  detail::require_positive(dt, "World::set_dt", "dt");
  def_.dt = dt;
}

void World::set_boundary(const Boundary& boundary) {
  boundary.validate("World::set_boundary");
  def_.boundary = boundary;
}

BodyView World::bodies() const {
  BodyView view;
  for_each_column(
      [](const char*, std::span<const double>& to, const std::vector<double>& from) { to = from; },
      view, bodies_);
  return view;
}

void World::restore(double time, std::int64_t step_count, std::span<const double> ax,
                    std::span<const double> ay) {
  detail::require_finite(time, "World::restore", "time");
  if (step_count < 0 || step_count > max_step_count) {
    throw InvalidArgument("World::restore: step_count must be between 0 and 2^53 (got " +
                          std::to_string(step_count) + ")");
  }
  if (ax.size() != body_count() || ay.size() != body_count()) {
    throw InvalidArgument("World::restore: ax and ay need " + std::to_string(body_count()) +
                          " values (got " + std::to_string(ax.size()) + " and " +
                          std::to_string(ay.size()) + ")");
  }
  for (std::size_t i = 0; i < ax.size(); ++i) {
    detail::require_finite(ax[i], "World::restore", "ax");
    detail::require_finite(ay[i], "World::restore", "ay");
  }
  bodies_.ax.assign(ax.begin(), ax.end());
  bodies_.ay.assign(ay.begin(), ay.end());
  time_ = time;
  step_count_ = step_count;
}

FieldContext World::context(const BodyView& view, double time) const {
  FieldContext c;
  c.bodies = view;
  c.time = time;
  c.dt = def_.dt;
  c.width = def_.width;
  c.height = def_.height;
  c.noise = &noise_;
  c.mutual_attraction = def_.backends.mutual_attraction;
  return c;
}

void World::accumulate_fields(const FieldContext& context, std::size_t first, std::size_t last,
                              std::span<double> ax, std::span<double> ay) const {
  for (const Field& field : fields_) accumulate(field, context, first, last, ax, ay);
}

void World::check_finite(const char* where) const {
  for (std::size_t i = 0; i < bodies_.x.size(); ++i) {
    if (!std::isfinite(bodies_.x[i]) || !std::isfinite(bodies_.y[i]) ||
        !std::isfinite(bodies_.vx[i]) || !std::isfinite(bodies_.vy[i])) {
      throw RunError(
          std::string(where) + ": body " + std::to_string(i) +
          " has a non-finite position or velocity after step " + std::to_string(step_count_ + 1) +
          " (x " + detail::format_number(bodies_.x[i]) + ", y " +
          detail::format_number(bodies_.y[i]) + ", vx " + detail::format_number(bodies_.vx[i]) +
          ", vy " + detail::format_number(bodies_.vy[i]) + ")");
    }
  }
}

Field& World::add_field(Field field) {
  try {
    validate(field);
  } catch (const Error& e) {
    rethrow_with_context(e, "World::add: ");
  }
  return fields_.emplace_back(std::move(field));
}

Field& World::field(std::size_t index) {
  if (index >= fields_.size()) {
    throw InvalidArgument("World::field: index " + std::to_string(index) + " out of range" +
                          world_has(fields_.size(), "field", "fields"));
  }
  return fields_[index];
}

void World::set_threads(int threads) {
  if (threads < 0 || threads > max_threads) {
    throw InvalidArgument("World::set_threads: threads must be between 0 and " +
                          std::to_string(max_threads) + " (got " + std::to_string(threads) + ")");
  }
  def_.threads = threads;
}

}  // namespace calder
