// SPDX-License-Identifier: MIT
// calder: scenes, worlds described as data, and the simulation that runs them.
//
// A Scene says everything needed to start and drive a world: the canvas, the
// integrator, the bodies (explicit, or generated with the p5-compatible
// generator in the book's order of draws), the fields, the boundary, and how
// the scene reacts to the mouse (wind while pressed, a fan at the mouse, a
// draggable attractor, a reset on click). Built-in scenes (every example of
// chapter 2) and scene files (calder/scene_file.hpp) both produce Scenes; the
// `calder` command, the window and the tests all run them through Simulation.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "calder/fields.hpp"
#include "calder/random.hpp"
#include "calder/vec2.hpp"
#include "calder/world.hpp"

namespace calder {

// A per-body value: fixed, drawn uniformly in [min, max) with p5's
// random(min, max), or start + step * index (e.g. 40 + i * 70).
struct Draw {
  enum class Kind { fixed, uniform, linear };
  Kind kind = Kind::fixed;
  double value = 0.0;  // fixed: the value; linear: the start
  double min = 0.0;    // uniform
  double max = 0.0;    // uniform
  double step = 0.0;   // linear

  static Draw fixed(double value) { return {Kind::fixed, value, 0.0, 0.0, 0.0}; }
  static Draw uniform(double min, double max) { return {Kind::uniform, 0.0, min, max, 0.0}; }
  static Draw linear(double start, double step) { return {Kind::linear, start, 0.0, 0.0, step}; }
  // The value for the index-th body; draws from rng only when uniform.
  double sample(Random& rng, std::size_t index) const;
};

// How a body's radius follows from its mass: k, k * mass (book: mass * 8),
// or k * sqrt(mass) (exercise 2.11, the galaxy).
struct RadiusRule {
  enum class Kind { fixed, per_mass, per_sqrt_mass };
  Kind kind = Kind::fixed;
  double k = 0.0;
  double radius_for(double mass) const;
};

// A group of bodies generated in order.
//
// Layout::grid draws, per body and in this order, x, y, mass, vx, vy (only
// the non-fixed ones draw), the order of `new Mover(random(width),
// random(height), random(0.5, 3))`.
//
// Layout::orbit places bodies around `center` like exercise 2.16: per body a
// direction random2d(), a speed, a distance and a mass, in that order; the
// position is center + direction * distance and the velocity is the
// direction turned by +90 degrees (clockwise on a y-down canvas) times speed.
struct BodyGroup {
  enum class Layout { grid, orbit };
  Layout layout = Layout::grid;
  std::size_t count = 1;
  Draw x = Draw::fixed(0.0);
  Draw y = Draw::fixed(0.0);
  Draw mass = Draw::fixed(1.0);
  Draw vx = Draw::fixed(0.0);
  Draw vy = Draw::fixed(0.0);
  // Layout::orbit only.
  Vec2 center{};
  Draw distance = Draw::fixed(100.0);
  Draw speed = Draw::fixed(1.0);
  RadiusRule radius{};
  std::optional<double> friction = std::nullopt;
  double drag_area = 1.0;
};

// How a field follows the mouse.
struct FieldBinding {
  bool while_pressed = false;  // enabled only while the mouse is pressed (the book's wind)
  bool follow_mouse = false;   // a Fan or Attractor placed at the mouse every frame
  bool draggable = false;      // an Attractor grabbed within `mass` pixels and dragged (2.6)
};

// Whether a field can follow the mouse: a kind with a position (FieldKind::position).
bool can_follow_mouse(const Field& field);
// The kinds that can, as messages list them ("a fan or an attractor").
std::string kinds_following_mouse();
// Whether a field can be dragged: an Attractor, grabbed within `mass` pixels.
bool can_be_dragged(const Field& field);

struct SceneField {
  Field field;
  FieldBinding binding{};
  bool visible = true;  // drawn (an attractor, a liquid); exercise 2.12 hides its attractors
};

// Frames (draw() numbers, 1-based, inclusive) during which the mouse is held.
struct FrameRange {
  std::int64_t first = 0;
  std::int64_t last = 0;
};

// Where the mouse is from a frame on (a scripted path).
struct MouseMove {
  std::int64_t frame = 0;
  Vec2 position{};
};

// Scripted input for headless runs; the window supplies live input instead.
struct InputScript {
  std::vector<FrameRange> mouse_pressed;
  Vec2 mouse{};                  // the mouse position before any move
  std::vector<MouseMove> moves;  // sorted by frame
  // Whether the mouse is held during draw() number `frame`, and where it is.
  [[nodiscard]] bool pressed_at(std::int64_t frame) const;
  [[nodiscard]] Vec2 mouse_at(std::int64_t frame) const;
};

// What a mouse press does besides the fields' bindings.
enum class PressAction {
  none,
  reset,  // rebuild the bodies (example 2.5)
  toss,   // grab the body under the mouse, carry it, release it with the mouse's velocity
          // (exercise 2.7)
};

// How the scene wants to be drawn; the renderer reads it, the physics doesn't.
struct SceneLook {
  bool trails = false;        // fade instead of clearing: p5 background(255, trail_alpha)
  double trail_alpha = 50.0;  // 0..255
  double body_gray = 127.0;   // p5 fill(body_gray, body_alpha), 0..255
  double body_alpha = 127.0;
  bool squares = false;  // bodies as squares of side 2 * radius (exercise 2.9's boxes)
};

// Limits that keep a typo from asking for the impossible.
constexpr std::int64_t max_frames = 10'000'000;
constexpr std::size_t max_bodies = 10'000'000;

struct Scene {
  std::string name;         // "example-2.5"
  std::string description;  // one line
  WorldDef world{};         // canvas, dt, integrator, update order, boundary, seed
  std::vector<BodyGroup> bodies;
  std::vector<SceneField> fields;
  std::int64_t frames = 600;
  PressAction on_press = PressAction::none;
  InputScript input{};
  // Where the physics origin sits on the canvas (the galaxy draws with
  // translate(width / 2, height / 2)); only drawing uses it.
  Vec2 origin{};
  SceneLook look{};
  // A boundary rule applied to every body at the start of each frame, before
  // the forces: a sketch that checks its edges first thing in draw()
  // (exercise 2.1's ceiling). Its timing is not used. Kind none: no rule.
  Boundary edges_first{};

  // Throws calder::Error naming the scene and the field for anything out of
  // range (counts, masses, ranges, NaN, field parameters).
  void validate() const;
};

// The input of one frame.
struct InputState {
  bool mouse_pressed = false;
  Vec2 mouse{};
};

// What a Simulation carries from one frame to the next besides its scene and
// its world: the frame counter and the mouse as the last frame left it (held
// or not, where, the body being tossed, the attractors being dragged). A
// snapshot (calder/snapshot.hpp) saves it with the scene and the world.
struct SimulationProgress {
  struct Grab {
    std::size_t field = 0;  // an attractor of the scene, dragged by the mouse
    Vec2 offset{};          // from the mouse to the attractor
  };
  std::int64_t frame = 0;
  bool was_pressed = false;
  Vec2 last_mouse{};
  std::optional<std::size_t> tossed;  // the body held by the mouse (PressAction::toss)
  Vec2 toss_offset{};
  std::vector<Grab> grabs;
};

// Runs a scene: builds the world (seeding the generator first, then drawing
// the bodies in order, as p5's setup() would after randomSeed), and steps it
// one frame at a time with the mouse's events applied first, as p5 fires
// mousePressed / mouseDragged / mouseReleased before draw().
class Simulation {
 public:
  // seed replaces the scene's seed (calder run --seed); scene().world.seed
  // is then that seed.
  explicit Simulation(Scene scene, std::optional<std::uint32_t> seed = std::nullopt);
  // Resumes a run (a snapshot, calder/snapshot.hpp): its scene, its world as
  // it was (field k the scene's field k) and its progress; no setup is run.
  // Throws calder::Error when they don't fit together (restore_progress).
  Simulation(Scene scene, World world, const SimulationProgress& progress);

  // One frame with this input: press, drag and release events, the fields'
  // bindings, then one world step.
  void step(const InputState& input);
  // One frame with the scene's scripted input for the next frame number.
  void step();

  // Replaces the bodies by these (calder run --state), in order.
  void set_bodies(const std::vector<BodyDef>& bodies);
  // Rebuilds the bodies from the scene's groups, continuing the generator
  // (the book's reset() on mouse press).
  void reset_bodies();

  [[nodiscard]] World& world() { return world_; }
  [[nodiscard]] const World& world() const { return world_; }
  [[nodiscard]] const Scene& scene() const { return scene_; }
  // Frames stepped so far (0 right after setup).
  [[nodiscard]] std::int64_t frame() const { return frame_; }

  // The frame counter and the mouse's state (SimulationProgress).
  [[nodiscard]] SimulationProgress progress() const;
  // Puts back a progress saved from a simulation of the same scene. Throws
  // calder::Error, changing nothing, for a frame outside 0..max_frames, a tossed body or a
  // dragged field that this simulation doesn't have, or a non-finite value.
  void restore_progress(const SimulationProgress& progress);

 private:
  // An attractor held by the mouse (not calder::Drag, the fluid-drag field).
  struct Grab {
    std::size_t field = 0;
    Vec2 offset{};
  };
  void handle_press(Vec2 mouse);

  Scene scene_;
  World world_;  // its field k is the scene's field k
  std::int64_t frame_ = 0;
  bool was_pressed_ = false;
  Vec2 last_mouse_{};
  std::optional<std::size_t> tossed_;  // the body held by the mouse (PressAction::toss)
  Vec2 toss_offset_{};
  std::vector<Grab> grabs_;
};

// --- built-in scenes: every example of the chapter ---

struct SceneInfo {
  std::string name;
  std::string description;
};

// The built-in scenes, in the book's order.
const std::vector<SceneInfo>& builtin_scenes();
// The built-in scene of that name; throws calder::InputError
// (unknown_scene_message) if there is none.
Scene builtin_scene(const std::string& name);
// Whether `name` is a built-in scene's.
bool is_builtin_scene(std::string_view name);
// The one-line error for a name that is no built-in scene, as every front end
// gives it: "unknown scene 'NAME' (did you mean 'NEAR'?): not a built-in scene
// (the names)", NEAR the built-in scene or `also` candidate (scene files, say)
// that NAME is a likely typo of, if any.
std::string unknown_scene_message(std::string_view name,
                                  const std::vector<std::string_view>& also = {});

}  // namespace calder
