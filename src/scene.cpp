// SPDX-License-Identifier: MIT
#include "calder/scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "calder/error.hpp"

namespace calder {

namespace {

constexpr double kHalfPi = 1.5707963267948966;  // p5's HALF_PI (Math.PI / 2)

void require_draw(const Draw& d, const std::string& where, const char* what, bool positive) {
  const std::string w = where + " " + what;
  switch (d.kind) {
    case Draw::Kind::fixed:
      if (positive) {
        detail::require_positive(d.value, w.c_str(), "value");
      } else {
        detail::require_finite(d.value, w.c_str(), "value");
      }
      return;
    case Draw::Kind::uniform:
      detail::require_finite(d.min, w.c_str(), "min");
      detail::require_finite(d.max, w.c_str(), "max");
      if (positive) {
        detail::require_positive(d.min, w.c_str(), "min");
        detail::require_positive(d.max, w.c_str(), "max");
      }
      return;
    case Draw::Kind::linear:
      detail::require_finite(d.value, w.c_str(), "start");
      detail::require_finite(d.step, w.c_str(), "step");
      return;
  }
}

// The groups of bodies of a scene, named in messages by `where`.
void validate_bodies(const std::vector<BodyGroup>& bodies, const std::string& where) {
  std::size_t total = 0;
  for (std::size_t g = 0; g < bodies.size(); ++g) {
    const BodyGroup& group = bodies[g];
    const std::string w = where + ": bodies[" + std::to_string(g) + "]";
    if (group.count > max_bodies || total + group.count > max_bodies) {
      throw Error(w + ": more than " + std::to_string(max_bodies) + " bodies");
    }
    total += group.count;
    require_draw(group.x, w, "x", false);
    require_draw(group.y, w, "y", false);
    require_draw(group.mass, w, "mass", true);
    if (group.mass.kind == Draw::Kind::linear && group.count > 0) {
      // start + i * step is monotonic in i: its ends are its extremes.
      const double last = group.mass.value + static_cast<double>(group.count - 1) * group.mass.step;
      if (!(group.mass.value > 0.0) || !(last > 0.0) || !std::isfinite(last)) {
        throw Error(w + ": mass of the first or last body would be <= 0 (masses must be > 0)");
      }
    }
    require_draw(group.vx, w, "vx", false);
    require_draw(group.vy, w, "vy", false);
    if (group.layout == BodyGroup::Layout::orbit) {
      detail::require_finite(group.center.x, w.c_str(), "center.x");
      detail::require_finite(group.center.y, w.c_str(), "center.y");
      require_draw(group.distance, w, "distance", false);
      require_draw(group.speed, w, "speed", false);
    }
    detail::require_non_negative(group.radius.k, w.c_str(), "radius");
    if (group.friction) detail::require_non_negative(*group.friction, w.c_str(), "friction");
    detail::require_non_negative(group.drag_area, w.c_str(), "drag_area");
  }
}

}  // namespace

bool can_follow_mouse(const Field& field) {
  return std::visit([](const auto& f) { return has_position<std::decay_t<decltype(f)>>(); }, field);
}

std::string kinds_following_mouse() {
  std::string out;
  const auto add = [&]<class F>() {
    if (!has_position<F>()) return;
    if (!out.empty()) out += " or ";
    const std::string name = FieldKind<F>::name;
    out +=
        (std::string_view("aeiou").find(name[0]) != std::string_view::npos ? "an " : "a ") + name;
  };
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    (add.template operator()<std::variant_alternative_t<I, Field>>(), ...);
  }
  (std::make_index_sequence<std::variant_size_v<Field>>());
  return out;
}

bool can_be_dragged(const Field& field) { return std::holds_alternative<Attractor>(field); }

double Draw::sample(Random& rng, std::size_t index) const {
  switch (kind) {
    case Kind::fixed:
      return value;
    case Kind::uniform:
      return rng.random(min, max);
    case Kind::linear:
      return value + static_cast<double>(index) * step;  // JS: start + i * step
  }
  return value;
}

double RadiusRule::radius_for(double mass) const {
  switch (kind) {
    case Kind::fixed:
      return k;
    case Kind::per_mass:
      return mass * k;
    case Kind::per_sqrt_mass:
      return std::sqrt(mass) * k;
  }
  return k;
}

bool InputScript::pressed_at(std::int64_t frame) const {
  for (const FrameRange& r : mouse_pressed) {
    if (frame >= r.first && frame <= r.last) return true;
  }
  return false;
}

Vec2 InputScript::mouse_at(std::int64_t frame) const {
  Vec2 at = mouse;
  for (const MouseMove& m : moves) {
    if (m.frame > frame) break;
    at = m.position;
  }
  return at;
}

namespace {

// The scripted mouse of a scene: press ranges, position and moves.
void validate_input(const InputScript& input, const std::string& where) {
  for (const FrameRange& r : input.mouse_pressed) {
    if (r.first < 1 || r.last < r.first) {
      throw Error(where + ": mouse_pressed range " + std::to_string(r.first) + "-" +
                  std::to_string(r.last) + " must satisfy 1 <= first <= last");
    }
  }
  detail::require_finite(input.mouse.x, where.c_str(), "mouse.x");
  detail::require_finite(input.mouse.y, where.c_str(), "mouse.y");
  std::int64_t previous = 0;
  for (const MouseMove& m : input.moves) {
    if (m.frame < previous) throw Error(where + ": mouse moves must be sorted by frame");
    previous = m.frame;
    detail::require_finite(m.position.x, where.c_str(), "mouse move x");
    detail::require_finite(m.position.y, where.c_str(), "mouse move y");
  }
}

// Whether `text` is well-formed UTF-8 (RFC 3629: no overlong forms, no
// surrogates, nothing past U+10FFFF), as a scene file's text must be.
bool valid_utf8(std::string_view text) {
  std::size_t i = 0;
  while (i < text.size()) {
    const auto c = static_cast<unsigned char>(text[i]);
    std::size_t extra = 0;
    std::uint32_t code = 0;
    std::uint32_t least = 0;
    if (c < 0x80) {
      ++i;
      continue;
    } else if ((c & 0xE0U) == 0xC0U) {
      extra = 1, code = c & 0x1FU, least = 0x80;
    } else if ((c & 0xF0U) == 0xE0U) {
      extra = 2, code = c & 0x0FU, least = 0x800;
    } else if ((c & 0xF8U) == 0xF0U) {
      extra = 3, code = c & 0x07U, least = 0x10000;
    } else {
      return false;
    }
    if (text.size() - i <= extra) return false;
    for (std::size_t k = 1; k <= extra; ++k) {
      const auto d = static_cast<unsigned char>(text[i + k]);
      if ((d & 0xC0U) != 0x80U) return false;
      code = (code << 6U) | (d & 0x3FU);
    }
    if (code < least || code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF)) return false;
    i += extra + 1;
  }
  return true;
}

}  // namespace

void Scene::validate() const {
  // A snapshot's scene is read without a scene file's text checks: its
  // texts must be what a scene file may hold.
  for (const auto& [what, text] :
       {std::pair{"name", &name}, std::pair{"description", &description}}) {
    if (!valid_utf8(*text)) {
      throw Error(std::string("scene: the ") + what + " is not valid UTF-8");
    }
  }
  const std::string where = "scene " + (name.empty() ? std::string("(unnamed)") : name);
  if (frames < 0 || frames > max_frames) {
    throw Error(where + ": frames must be between 0 and " + std::to_string(max_frames) + " (got " +
                std::to_string(frames) + ")");
  }
  detail::require_positive(world.width, where.c_str(), "width");
  detail::require_positive(world.height, where.c_str(), "height");
  detail::require_positive(world.dt, where.c_str(), "dt");
  detail::require_positive(world.tolerance, where.c_str(), "tolerance");
  world.boundary.validate(where.c_str());
  edges_first.validate((where + ": edges_first").c_str());
  detail::require_non_negative(world.max_speed, where.c_str(), "max_speed");
  if (world.max_speed > 0.0 && world.integrator != Integrator::semi_implicit_euler) {
    throw Error(where + ": max_speed needs the semi_implicit_euler integrator");
  }
  if (world.update_order == UpdateOrder::sequential &&
      world.integrator != Integrator::semi_implicit_euler) {
    throw Error(where + ": the sequential update order needs the semi_implicit_euler integrator");
  }
  if (world.arithmetic != Arithmetic::book &&
      (world.integrator != Integrator::semi_implicit_euler ||
       world.update_order != UpdateOrder::simultaneous)) {
    throw Error(where +
                ": arithmetic other than book needs the semi_implicit_euler integrator and the "
                "simultaneous update order");
  }
  if (world.threads < 0 || world.threads > max_threads) {
    throw Error(where + ": threads must be between 0 and " + std::to_string(max_threads) +
                " (got " + std::to_string(world.threads) + ")");
  }
  validate_bodies(bodies, where);
  for (std::size_t k = 0; k < fields.size(); ++k) {
    const SceneField& f = fields[k];
    const std::string w =
        where + ": fields[" + std::to_string(k) + "] (" + field_name(f.field) + ")";
    try {
      calder::validate(f.field);
    } catch (const Error& e) {
      rethrow_with_context(e, where + ": fields[" + std::to_string(k) + "]: ");
    }
    if (f.binding.follow_mouse && !can_follow_mouse(f.field)) {
      throw Error(w + ": only " + kinds_following_mouse() + " can follow the mouse");
    }
    if (f.binding.draggable && !can_be_dragged(f.field)) {
      throw Error(w + ": only an attractor can be dragged");
    }
  }
  validate_input(input, where);
  for (const double v : {look.trail_alpha, look.body_gray, look.body_alpha}) {
    if (!(v >= 0.0 && v <= 255.0)) {
      throw Error(where +
                  ": look values (trail_alpha, body_gray, body_alpha) must be in 0..255 (got " +
                  detail::format_number(v) + ")");
    }
  }
  detail::require_finite(origin.x, where.c_str(), "origin.x");
  detail::require_finite(origin.y, where.c_str(), "origin.y");
}

namespace {

Scene seeded(Scene scene, std::optional<std::uint32_t> seed) {
  scene.validate();
  if (seed) scene.world.seed = *seed;
  return scene;
}

}  // namespace

Simulation::Simulation(Scene scene, std::optional<std::uint32_t> seed)
    : scene_(seeded(std::move(scene), seed)),
      world_(scene_.world),
      last_mouse_(scene_.input.mouse) {
  for (const SceneField& f : scene_.fields) world_.add_field(f.field);
  reset_bodies();
}

Simulation::Simulation(Scene scene, World world, const SimulationProgress& progress)
    : scene_(seeded(std::move(scene), std::nullopt)), world_(std::move(world)) {
  if (world_.fields().size() != scene_.fields.size()) {
    throw InvalidArgument("Simulation: the world has " + std::to_string(world_.fields().size()) +
                          " fields, the scene " + std::to_string(scene_.fields.size()));
  }
  restore_progress(progress);
}

void Simulation::reset_bodies() {
  tossed_.reset();
  world_.clear_bodies();
  Random& rng = world_.random();
  for (const BodyGroup& group : scene_.bodies) {
    for (std::size_t i = 0; i < group.count; ++i) {
      BodyDef def;
      if (group.layout == BodyGroup::Layout::grid) {
        // Arguments evaluate left to right: x, then y, then mass (then velocity).
        def.position.x = group.x.sample(rng, i);
        def.position.y = group.y.sample(rng, i);
        def.mass = group.mass.sample(rng, i);
        def.velocity.x = group.vx.sample(rng, i);
        def.velocity.y = group.vy.sample(rng, i);
      } else {
        // Exercise 2.16: pos = random2D(); vel = pos.copy(); vel.setMag(speed);
        // pos.setMag(distance); vel.rotate(HALF_PI); m = random(...).
        Vec2 direction = rng.random2d();
        Vec2 velocity = direction;
        velocity.set_mag(group.speed.sample(rng, i));
        direction.set_mag(group.distance.sample(rng, i));
        velocity.rotate(kHalfPi);
        def.mass = group.mass.sample(rng, i);
        def.position = group.center + direction;
        def.velocity = velocity;
      }
      def.radius = group.radius.radius_for(def.mass);
      def.friction = group.friction;
      def.drag_area = group.drag_area;
      world_.add_body(def);
    }
  }
}

void Simulation::set_bodies(const std::vector<BodyDef>& bodies) {
  World fresh = world_;  // validate every body before replacing any
  fresh.clear_bodies();
  for (const BodyDef& def : bodies) fresh.add_body(def);
  world_ = std::move(fresh);
  tossed_.reset();
}

void Simulation::handle_press(Vec2 mouse) {
  if (scene_.on_press == PressAction::reset) reset_bodies();
  if (scene_.on_press == PressAction::toss) {
    // Grab the nearest body whose circle holds the mouse (at least 10 px for points).
    const BodyView b = world_.bodies();
    double best = 0.0;
    for (std::size_t i = 0; i < b.size(); ++i) {
      const double d = mouse.dist(b.position(i));
      if (d <= std::max(b.radius[i], 10.0) && (!tossed_ || d < best)) {
        tossed_ = i;
        best = d;
      }
    }
    if (tossed_) toss_offset_ = b.position(*tossed_) - mouse;
  }
  for (std::size_t k = 0; k < scene_.fields.size(); ++k) {
    if (!scene_.fields[k].binding.draggable) continue;
    auto& attractor = std::get<Attractor>(world_.field(k));
    // The book's handlePress: grab when the press is within `mass` pixels.
    if (mouse.dist(attractor.position) < attractor.mass) {
      grabs_.push_back({k, attractor.position - mouse});
    }
  }
}

void Simulation::step(const InputState& input) {
  detail::require_finite(input.mouse.x, "Simulation::step", "mouse.x");
  detail::require_finite(input.mouse.y, "Simulation::step", "mouse.y");
  if (input.mouse_pressed && !was_pressed_) handle_press(input.mouse);
  if (input.mouse_pressed) {
    // p5 fires mouseDragged only when the mouse moves; the attractor stays put
    // to the bit otherwise.
    const bool moved = input.mouse != last_mouse_;
    for (const Grab& d : grabs_) {
      if (!moved) break;
      std::get<Attractor>(world_.field(d.field)).position = input.mouse + d.offset;
    }
  } else {
    grabs_.clear();
    tossed_.reset();  // released: the body keeps the mouse's last velocity
  }
  const Vec2 mouse_velocity = (input.mouse - last_mouse_) / world_.dt();
  for (std::size_t k = 0; k < scene_.fields.size(); ++k) {
    const FieldBinding& b = scene_.fields[k].binding;
    Field& field = world_.field(k);
    if (b.while_pressed) {
      std::visit([&](auto& f) { f.enabled = input.mouse_pressed; }, field);
    }
    if (b.follow_mouse) {
      std::visit(
          [&](auto& f) {
            using Kind = FieldKind<std::decay_t<decltype(f)>>;
            if constexpr (has_position<std::decay_t<decltype(f)>>()) {
              f.*Kind::position = input.mouse;
            }
          },
          field);
    }
  }
  was_pressed_ = input.mouse_pressed;
  last_mouse_ = input.mouse;
  if (scene_.edges_first.kind != BoundaryKind::none) {
    for (std::size_t i = 0; i < world_.body_count(); ++i) {
      world_.apply_boundary(world_.body(i), scene_.edges_first);
    }
  }
  world_.step();
  if (tossed_) {
    // Held: the body sits under the mouse and moves with it.
    const BodyId id = world_.body(*tossed_);
    world_.set_position(id, input.mouse + toss_offset_);
    world_.set_velocity(id, mouse_velocity);
  }
  ++frame_;
}

SimulationProgress Simulation::progress() const {
  SimulationProgress p;
  p.frame = frame_;
  p.was_pressed = was_pressed_;
  p.last_mouse = last_mouse_;
  p.tossed = tossed_;
  p.toss_offset = toss_offset_;
  for (const Grab& g : grabs_) p.grabs.push_back({g.field, g.offset});
  return p;
}

void Simulation::restore_progress(const SimulationProgress& p) {
  const char* where = "Simulation::restore_progress";
  if (p.frame < 0 || p.frame > max_frames) {
    throw InvalidArgument(std::string(where) + ": frame must be between 0 and " +
                          std::to_string(max_frames) + " (got " + std::to_string(p.frame) + ")");
  }
  for (const Vec2 v : {p.last_mouse, p.toss_offset}) {
    detail::require_finite(v.x, where, "mouse");
    detail::require_finite(v.y, where, "mouse");
  }
  if (p.tossed && *p.tossed >= world_.body_count()) {
    throw InvalidArgument(std::string(where) + ": tossed body " + std::to_string(*p.tossed) +
                          " of " + std::to_string(world_.body_count()));
  }
  std::vector<Grab> grabs;
  for (const SimulationProgress::Grab& g : p.grabs) {
    if (g.field >= scene_.fields.size() || !scene_.fields[g.field].binding.draggable) {
      throw InvalidArgument(std::string(where) + ": field " + std::to_string(g.field) +
                            " is not a draggable attractor");
    }
    detail::require_finite(g.offset.x, where, "grab offset");
    detail::require_finite(g.offset.y, where, "grab offset");
    grabs.push_back({g.field, g.offset});
  }
  frame_ = p.frame;
  was_pressed_ = p.was_pressed;
  last_mouse_ = p.last_mouse;
  tossed_ = p.tossed;
  toss_offset_ = p.toss_offset;
  grabs_ = std::move(grabs);
}

void Simulation::step() {
  const std::int64_t next = frame_ + 1;
  step(InputState{scene_.input.pressed_at(next), scene_.input.mouse_at(next)});
}

}  // namespace calder
