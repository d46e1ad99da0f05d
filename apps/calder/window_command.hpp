// SPDX-License-Identifier: MIT
// calder command: `calder window`, a scene in an SDL2 window, in real time,
// with the book's mouse interactions.
//
//   calder window example-2.7            drag the attractor
//   calder window exercise-2.16 --scale 1.5 --speed 2
//
// The command is a sketch (calder/sketch.hpp) on calder::sketch's window
// loop: the display shows at its own rate (vsync); physics advances in fixed
// steps, 60 a second times --speed (the runner's calder::FixedStep), each one
// Simulation::step(InputState{pressed, mouse}) with the live mouse, in the
// scene's physics coordinates (canvas pixels - scene origin). With
// --mouse-pressed or --mouse the scene's scripted input is replayed instead.
//
// Keys: space pause, . one step (paused), r reset, f forces, t trails,
// s save a PNG, g start/stop a GIF, k save a snapshot (snapshot_io.hpp:
// `calder window FILE` opens it), + / - speed (x2, /2; 1/8 to 8), q or Esc
// quit.
//
// For automation: --frames N stops after N steps, --exit-after-seconds S
// after S seconds, --screenshot FILE writes the last frame, --print-state
// prints the final state (print_state below).
//
// Without a display (no DISPLAY or WAYLAND_DISPLAY, or SDL can't start its
// video), one line "calder: no display: <reason>" and exit 2. SDL_VIDEODRIVER,
// when set, picks SDL's driver (e.g. "dummy" or "offscreen", which need no
// display) and skips the check of DISPLAY / WAYLAND_DISPLAY.
#pragma once

#include <optional>
#include <ostream>
#include <string>

#include "calder/scene.hpp"
#include "calder/vec2.hpp"
#include "render_command.hpp"
#include "run_options.hpp"

namespace CLI {
class App;
}

namespace calder::app {

// Simulation speed limits (--speed, the + and - keys).
constexpr double min_speed = 0.125;
constexpr double max_speed = 8.0;

struct WindowOptions {
  InputOptions input;
  StyleOptions style;
  std::optional<std::string> scale;
  std::optional<std::string> speed;
  std::optional<std::string> screenshot;
  std::optional<std::string> exit_after_seconds;
  bool print_state = false;
  bool quiet = false;
};

// Adds the `window` verb with its flags to the application.
CLI::App* add_window_command(CLI::App& app, WindowOptions& options);

// Opens the window and runs until quit (or --frames / --exit-after-seconds).
// Throws InputError for bad flags or no display (exit 2), RunError when a step
// or a write at exit fails (exit 1).
void window_command(const WindowOptions& options, std::ostream& out, std::ostream& err);

// The keys, one line (printed at start, and in the window's title).
const char* window_help();

// A point of the window (pixels) in the scene's physics coordinates.
Vec2 window_to_physics(double x, double y, double scale, Vec2 origin);

// --print-state: the frame, the origin, each attractor field (numbered from 0
// in the scene's order of fields; its position in physics coordinates and
// mass), each body (position, radius) and the state hash, e.g.
//   frame 240
//   origin 0 0
//   attractor 0 200 80 mass 20
//   body 0 301.5 96.25 radius 12.5
//   state_hash 0123456789abcdef
void print_state(std::ostream& out, const Simulation& simulation);

}  // namespace calder::app
