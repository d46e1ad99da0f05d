// SPDX-License-Identifier: MIT
// calder command: `calder render`, a scene drawn to PNG frames and/or an
// animated GIF, headless; and the drawing flags it shares with `calder window`.
//
//   calder render example-2.7 --frames 300 --gif orbit.gif
//   calder render example-2.4 --png frames --every 2 --scale 2 --figure
//
// Frame 0 (the state after setup) is drawn first, then every K-th frame
// (--every K) up to --frames. PNG frames are numbered in the order written,
// DIR/frame-000000.png, frame-000001.png, ... (frame-000001.png is frame K),
// so video tools read them as a sequence.
#pragma once

#include <cstdint>
#include <optional>
#include <ostream>
#include <string>

#include "calder/render.hpp"
#include "calder/scene.hpp"
#include "run_options.hpp"

namespace CLI {
class App;
}

namespace calder::app {

// Limits of `calder render`.
constexpr std::int64_t max_render_frames = 100'000;  // --frames
constexpr std::int64_t max_output_frames = 10'000;   // PNG files or GIF frames
constexpr int max_image_side = Canvas::max_side;     // pixels, after --scale
constexpr double max_scale = Canvas::max_scale;      // --scale in (0, max_scale]
constexpr double min_fps = 0.01;                     // --fps
constexpr double max_fps = 100.0;

// --trails / --no-trails, --forces, --velocity, --hud, --figure.
struct StyleOptions {
  bool trails = false;
  bool no_trails = false;
  bool forces = false;
  bool velocity = false;
  bool hud = false;
  bool figure = false;
};

// Adds the drawing flags to a verb.
void add_style_options(CLI::App& command, StyleOptions& options);

// book_style(scene) (BookLook::figure with --figure) with the flags applied.
// Throws InputError if the style is invalid.
RenderStyle make_style(const Scene& scene, const StyleOptions& options);
// With --hud, the HUD's energy error measured from the run's start
// (calder::start_energy: a resumed run's scene at its first frame).
void start_hud(RenderStyle& style, const Simulation& simulation);

// A canvas's size in canvas pixels, and its pixel density.
struct CanvasSize {
  int width = 0;
  int height = 0;
  double scale = 1.0;
};

// --scale: a finite number in (0, 8].
double parse_scale(const std::string& flag, const std::string& text);
// --size WxH (canvas pixels; default the scene's width x height) and --scale S
// (default 1), checked so that each side of the image, round(side * S), is 1
// to 8192 pixels. Throws InputError naming the flag.
CanvasSize canvas_size(const std::optional<std::string>& size,
                       const std::optional<std::string>& scale, const Scene& scene);

// Throws InputError (naming `flag` and `path`) when the output policy refuses
// path (src/output/output.hpp; nothing is created).
void check_output_path(const std::string& flag, const std::string& path);

// The scene's name made safe for a file name (letters, digits, '.', '-', '_').
std::string file_name_part(const std::string& name);

struct RenderOptions {
  InputOptions input;
  StyleOptions style;
  std::optional<std::string> every;
  std::optional<std::string> png;  // a folder
  std::optional<std::string> gif;  // a file
  std::optional<std::string> size;
  std::optional<std::string> scale;
  std::optional<std::string> fps;
  bool quiet = false;
};

// Adds the `render` verb with its flags to the application.
CLI::App* add_render_command(CLI::App& app, RenderOptions& options);

// Runs it. What was written is reported on `out` (unless --quiet); the
// progress bar goes to `err` when standard error is a terminal. Throws
// InputError (exit 2) for bad flags or output paths that can't be written,
// RunError when a step or a write fails midway (the files this run wrote are
// removed), Interrupted on SIGINT / SIGTERM (the same).
void render_command(const RenderOptions& options, std::ostream& out, std::ostream& err);

}  // namespace calder::app
