// SPDX-License-Identifier: MIT
// calder in the browser: the engine's scenes behind embind, for web/calder.js.
//
// A WebSimulation is one running scene. The page draws from zero-copy views of
// the world's arrays (typed_memory_view over the WebAssembly heap); a view is
// only good until the heap grows or the world's vectors reallocate, so the JS
// side asks for fresh views after every call that can do either (load, step,
// reset, forces). Every calder::Error reaches JavaScript as an Error with the
// C++ message (calder.js turns the thrown string into one).
#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <array>
#include <cinttypes>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "calder/backends.hpp"
#include "calder/bulk.hpp"
#include "calder/diagnostics.hpp"
#include "calder/error.hpp"
#include "calder/nbody.hpp"
#include "calder/render.hpp"
#include "calder/scene.hpp"
#include "calder/scene_file.hpp"
#include "calder/snapshot.hpp"
#include "calder/trajectory.hpp"

namespace calder::web {

using emscripten::val;

namespace {

// Scene text is anything with a line break, a '=' or a '[': no scene name has them.
bool looks_like_toml(const std::string& source) {
  return source.find_first_of("\n=[") != std::string::npos;
}

Scene scene_from(const std::string& source, const std::string& source_name) {
  if (source.empty()) throw Error("the scene name is empty");
  if (looks_like_toml(source)) return parse_scene(source, source_name);
  if (is_builtin_scene(source)) return builtin_scene(source);
  throw Error(unknown_scene_message(source));
}

// The seed as `calder run --seed` takes it: an integer from 0 to 2^32 - 1.
std::uint32_t seed_from(const val& seed) {
  const double value = seed.isNumber() ? seed.as<double>() : std::nan("");
  const std::string shown = seed.isNumber() || seed.isString()
                                ? seed.call<std::string>("toString")
                                : std::string(seed.typeOf().as<std::string>());
  if (seed.isString()) {
    const std::string text = seed.as<std::string>();
    if (!text.empty() && text.find_first_not_of("0123456789") == std::string::npos &&
        text.size() <= 10) {
      const double parsed = std::stod(text);
      if (parsed <= 4294967295.0) return static_cast<std::uint32_t>(parsed);
    }
  } else if (std::isfinite(value) && value >= 0.0 && value <= 4294967295.0 &&
             value == std::floor(value)) {
    return static_cast<std::uint32_t>(value);
  }
  throw Error("seed: expected an integer from 0 to 4294967295, got '" + shown + "'");
}

// "A-B" or "A" frame ranges, as --mouse-pressed takes them, from [[a, b], ...].
std::vector<FrameRange> ranges_from(const val& list) {
  std::vector<FrameRange> ranges;
  const auto length = list["length"].as<unsigned>();
  for (unsigned i = 0; i < length; ++i) {
    const val range = list[i];
    const auto first = static_cast<std::int64_t>(range[0].as<double>());
    const auto last = static_cast<std::int64_t>(range[1].as<double>());
    if (first < 1 || last < first) {
      throw Error("mousePressed: expected frame ranges A-B with 1 <= A <= B, got " +
                  std::to_string(first) + "-" + std::to_string(last));
    }
    ranges.push_back({first, last});
  }
  return ranges;
}

val color_of(const Color& c) {
  val out = val::array();
  out.call<void>("push", c.r);
  out.call<void>("push", c.g);
  out.call<void>("push", c.b);
  out.call<void>("push", c.a);
  return out;
}

// Runs f, turning what C++ throws into a JS string that calder.js rethrows as an Error.
template <class F>
auto guarded(F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const std::exception& e) {
    val(std::string(e.what())).throw_();
  }
  __builtin_unreachable();
}

}  // namespace

class WebSimulation {
 public:
  // source: a built-in scene's name or scene text (TOML). options: seed,
  // count (bodies of the first group: the scenes made to scale), name (the
  // file named in error messages), mousePressed [[a, b], ...], mouse [x, y].
  WebSimulation(const std::string& source, const val& options)
      : simulation_(guarded([&] { return make(source, options); })) {}

  void step(int count) {
    guarded([&] {
      for (int i = 0; i < count; ++i) simulation_.step();
    });
  }
  void step_input(int count, bool pressed, double mouse_x, double mouse_y) {
    guarded([&] {
      const InputState input{pressed, {mouse_x, mouse_y}};
      for (int i = 0; i < count; ++i) simulation_.step(input);
    });
  }
  void reset_bodies() {
    guarded([&] {
      simulation_.reset_bodies();
      start_energy_ = watched_energy(simulation_.world());  // new bodies: a new start
    });
  }

  [[nodiscard]] double frame() const { return static_cast<double>(simulation_.frame()); }
  [[nodiscard]] double frames() const { return static_cast<double>(simulation_.scene().frames); }
  [[nodiscard]] std::size_t body_count() const { return simulation_.world().body_count(); }
  [[nodiscard]] std::string state_hash_text() const {
    return calder::state_hash_text(simulation_.world());
  }
  [[nodiscard]] double seed() const { return seed_; }
  // The HUD's energy (calder::displayed_energy, as the command and the
  // renderer show it): {kinetic, potential (NaN where the fields have none),
  // total, exact, error}; its pairs bounded, so that a frame's cost does not
  // grow as N^2 (past kHudEnergyPairs pairs a sampled estimate, exact false).
  // error: the relative error since the start while exact (calder::hud_text's
  // rule), NaN where the energy isn't watched.
  [[nodiscard]] val energy() const {
    const DisplayedEnergy e = displayed_energy(simulation_.world());
    val out = val::object();
    out.set("kinetic", e.kinetic);
    out.set("potential",
            e.has_potential ? e.potential.value : std::numeric_limits<double>::quiet_NaN());
    out.set("total", e.total());
    out.set("exact", e.exact());
    out.set("error", e.exact() && std::isfinite(start_energy_)
                         ? relative_energy_error(start_energy_, e.total())
                         : std::numeric_limits<double>::quiet_NaN());
    return out;
  }

  // Zero-copy views of the bodies; stale after the heap grows or bodies change.
  [[nodiscard]] val view(const std::string& which) const {
    const BodyView b = simulation_.world().bodies();
    const auto of = [](std::span<const double> s) {
      return val(emscripten::typed_memory_view(s.size(), s.data()));
    };
    if (which == "x") return of(b.x);
    if (which == "y") return of(b.y);
    if (which == "vx") return of(b.vx);
    if (which == "vy") return of(b.vy);
    if (which == "mass") return of(b.mass);
    if (which == "radius") return of(b.radius);
    val(std::string("view: no array '") + which + "' (x, y, vx, vy, mass, radius)").throw_();
    return val::undefined();
  }

  // Each field's force on each body (field-major: fx then fy, k * 2n + i), the
  // way `calder render --forces` computes them; a view, stale like the others.
  [[nodiscard]] val forces() {
    return guarded([&] {
      const World& world = simulation_.world();
      const BodyView bodies = world.bodies();
      const std::size_t n = bodies.size();
      const std::size_t k_count = world.fields().size();
      forces_.assign(2 * k_count * n, 0.0);
      ax_.resize(n);
      ay_.resize(n);
      const FieldContext context{bodies,        world.time(),   world.dt(),
                                 world.width(), world.height(), &world.noise()};
      for (std::size_t k = 0; k < k_count; ++k) {
        std::fill(ax_.begin(), ax_.end(), 0.0);
        std::fill(ay_.begin(), ay_.end(), 0.0);
        accumulate(world.fields()[k], context, 0, n, std::span<double>(ax_),
                   std::span<double>(ay_));
        for (std::size_t i = 0; i < n; ++i) {
          forces_[2 * k * n + i] = ax_[i] * bodies.mass[i];
          forces_[2 * k * n + n + i] = ay_[i] * bodies.mass[i];
        }
      }
      return val(emscripten::typed_memory_view(forces_.size(), forces_.data()));
    });
  }

  // What the page draws besides the bodies: canvas, origin, look (the
  // renderer's book_style) and the fields with their bindings.
  [[nodiscard]] val describe() const {
    const Scene& scene = simulation_.scene();
    const World& world = simulation_.world();
    const RenderStyle style = book_style(scene);
    val out = val::object();
    out.set("name", scene.name);
    out.set("description", scene.description);
    out.set("frames", static_cast<double>(scene.frames));  // the default run's length
    out.set("width", world.width());
    out.set("height", world.height());
    out.set("originX", scene.origin.x);
    out.set("originY", scene.origin.y);
    out.set("pressAction", std::string(scene.on_press == PressAction::reset  ? "reset"
                                       : scene.on_press == PressAction::toss ? "toss"
                                                                             : "none"));
    val look = val::object();
    look.set("background", color_of(style.background));
    look.set("trails", style.trails);
    look.set("trailAlpha", style.trail_alpha);
    look.set("bodyFill", color_of(style.body_fill));
    look.set("bodyStroke", color_of(style.body_stroke));
    look.set("bodyStrokeWeight", style.body_stroke_weight);
    look.set("squares", style.squares);
    look.set("liquidFill", color_of(style.liquid_fill));
    look.set("attractorFill", color_of(style.attractor_fill));
    look.set("attractorStroke", color_of(style.attractor_stroke));
    look.set("attractorStrokeWeight", style.attractor_stroke_weight);
    look.set("attractorDiameterPerMass", style.attractor_diameter_per_mass);
    look.set("forceScale", style.force_scale);
    look.set("velocityScale", style.velocity_scale);
    look.set("vectorWeight", style.vector_weight);
    look.set("netForceColor", color_of(style.net_force_color));
    look.set("velocityColor", color_of(style.velocity_color));
    val colors = val::array();
    for (const Color& c : style.field_colors) colors.call<void>("push", color_of(c));
    look.set("fieldColors", colors);
    out.set("look", look);

    val fields = val::array();
    for (std::size_t k = 0; k < world.fields().size(); ++k) {
      const Field& field = world.fields()[k];
      val f = val::object();
      f.set("type", std::string(field_name(field)));
      const SceneField& scene_field = scene.fields[k];
      f.set("visible", scene_field.visible);
      f.set("whilePressed", scene_field.binding.while_pressed);
      f.set("followMouse", scene_field.binding.follow_mouse);
      f.set("draggable", scene_field.binding.draggable);
      std::visit(
          [&](const auto& v) {
            using T = std::decay_t<decltype(v)>;
            if constexpr (!std::is_same_v<T, CustomForce>) f.set("enabled", v.enabled);
            if constexpr (std::is_same_v<T, Liquid>) {
              f.set("x", v.region.x);
              f.set("y", v.region.y);
              f.set("w", v.region.w);
              f.set("h", v.region.h);
            } else if constexpr (std::is_same_v<T, Attractor>) {
              f.set("x", v.position.x);
              f.set("y", v.position.y);
              f.set("mass", v.mass);
            } else if constexpr (std::is_same_v<T, Fan>) {
              f.set("x", v.position.x);
              f.set("y", v.position.y);
              f.set("reach", v.reach);
            }
          },
          field);
      fields.call<void>("push", f);
    }
    out.set("fields", fields);
    return out;
  }

  // A snapshot of the run (docs/SNAPSHOTS.md), a Uint8Array of its own.
  [[nodiscard]] val snapshot() const {
    return guarded([&] {
      const Bytes bytes = to_snapshot(simulation_);
      return val(emscripten::typed_memory_view(bytes.size(), bytes.data())).call<val>("slice");
    });
  }

  // The running scene as scene text (calder::to_toml), seed and size included.
  [[nodiscard]] std::string toml() const {
    return guarded([&] {
      Scene scene = simulation_.scene();
      scene.world.seed = seed_;
      return to_toml(scene);
    });
  }

 private:
  Simulation make(const std::string& source, const val& options) {
    const val name = options["name"];
    const val snapshot = options["snapshot"];  // a snapshot's bytes: the run goes on from it
    if (!snapshot.isUndefined() && !snapshot.isNull()) {
      Simulation resumed =
          simulation_from_snapshot(emscripten::convertJSArrayToNumberVector<std::uint8_t>(snapshot),
                                   name.isString() ? name.as<std::string>() : "snapshot");
      seed_ = resumed.scene().world.seed;
      return resumed;
    }
    Scene scene = scene_from(source, name.isString() ? name.as<std::string>() : "scene.toml");
    const val seed = options["seed"];
    if (!seed.isUndefined() && !seed.isNull()) {
      scene.world.seed = seed_from(seed);
    }
    seed_ = scene.world.seed;
    const val count = options["count"];
    if (!count.isUndefined() && !count.isNull()) {
      const double n = count.isNumber() ? count.as<double>() : -1.0;
      if (scene.bodies.empty() || !(n >= 1.0 && n <= 1'000'000.0) || n != std::floor(n)) {
        throw Error("count: expected an integer from 1 to 1000000 for a scene with bodies");
      }
      scene.bodies.front().count = static_cast<std::size_t>(n);
    }
    const val method = options["method"];
    if (!method.isUndefined() && !method.isNull()) set_method(scene, method);
    const val pressed = options["mousePressed"];
    if (pressed.isArray()) scene.input.mouse_pressed = ranges_from(pressed);
    const val mouse = options["mouse"];
    if (mouse.isArray()) {
      scene.input.mouse = {mouse[0].as<double>(), mouse[1].as<double>()};
      scene.input.moves.clear();
    }
    scene.validate();
    return Simulation(std::move(scene));
  }

  // The n-body method of every mutual attraction (scene files' names). The
  // fast ones sum all pairs from one state: a sequential world (example 2.9)
  // becomes simultaneous.
  static void set_method(Scene& scene, const val& method) {
    const std::string name = method.isString() ? method.as<std::string>() : std::string("?");
    std::optional<NBodyMethod> chosen;
    std::string names;
    for (const NBodyMethodName& choice : kNBodyMethodNames) {
      if (choice.name == name) chosen = choice.value;
      names += names.empty() ? "" : ", ";
      names += choice.name;
    }
    if (!chosen) throw Error("method: expected one of " + names + ", got '" + name + "'");
    for (SceneField& field : scene.fields) {
      if (auto* mutual = std::get_if<MutualAttraction>(&field.field)) mutual->method = *chosen;
    }
    if (*chosen != NBodyMethod::exact) scene.world.update_order = UpdateOrder::simultaneous;
  }

  std::uint32_t seed_ = 0;
  Simulation simulation_;
  double start_energy_ = start_energy(simulation_);  // the HUD's error is measured from it
  std::vector<double> forces_, ax_, ay_;
};

val scene_list() {
  val out = val::array();
  for (const SceneInfo& info : builtin_scenes()) {
    val s = val::object();
    s.set("name", info.name);
    s.set("description", info.description);
    out.call<void>("push", s);
  }
  return out;
}

// The instruction sets of the kernels the module was built with.
val kernel_names() {
  val out = val::object();
  out.set("bulk", std::string(calder::bulk::kernel_name()));
  out.set("nbody", std::string(calder::nbody::kernel_name()));
  return out;
}

EMSCRIPTEN_BINDINGS(calder_web) {
  // The page names its kernels itself. Natively, linking calder::bulk and
  // calder::nbody registers them (docs/DESIGN.md); in this WebAssembly module
  // the worlds found no default that way, so the page does not rely on it.
  calder::set_step_batch_backend(calder::bulk::step_batch);
  calder::set_mutual_attraction_backend(calder::nbody::mutual_attraction);
  emscripten::function("scenes", &scene_list);
  emscripten::function("kernels", &kernel_names);
  emscripten::class_<WebSimulation>("Simulation")
      .constructor<const std::string&, const val&>()
      .function("step", &WebSimulation::step)
      .function("stepInput", &WebSimulation::step_input)
      .function("resetBodies", &WebSimulation::reset_bodies)
      .function("frame", &WebSimulation::frame)
      .function("frames", &WebSimulation::frames)
      .function("bodyCount", &WebSimulation::body_count)
      .function("stateHash", &WebSimulation::state_hash_text)
      .function("seed", &WebSimulation::seed)
      .function("energy", &WebSimulation::energy)
      .function("view", &WebSimulation::view)
      .function("forces", &WebSimulation::forces)
      .function("describe", &WebSimulation::describe)
      .function("toml", &WebSimulation::toml)
      .function("snapshot", &WebSimulation::snapshot);
}

}  // namespace calder::web
