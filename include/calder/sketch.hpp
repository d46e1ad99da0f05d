// SPDX-License-Identifier: MIT
// calder: the book's sketches in C++, p5.js's setup() and draw() with its
// drawing vocabulary, in a window or headless from the same program.
//
//   (with calder/calder.hpp and calder/sketch.hpp included)
//
//   class Forces : public calder::Sketch {
//     calder::World world{{.width = 640, .height = 240}};
//     calder::Mover mover = world.add_mover({.position = {320, 30}, .mass = 1});
//
//     void setup() override { create_canvas(640, 240); }
//     void draw() override {
//       background(255);
//       mover.apply_force({0, 0.1});                        // gravity
//       if (mouse_is_pressed()) mover.apply_force({0.1, 0});  // wind
//       mover.update();
//       mover.check_edges(calder::Boundary::bounce(1.0, false, {.top = false}));
//       stroke(0);
//       stroke_weight(2);
//       fill(127, 127);
//       circle(mover.position().x, mover.position().y, 48);
//     }
//   };
//
//   int main(int argc, char** argv) { return calder::run_sketch<Forces>(argc, argv); }
//
// The runner (run_sketch) calls setup() once, then draw() once a frame: in a
// window at the sketch's frame rate, or headless (no display, or --gif,
// --png, --trajectory, --headless) as fast as it can. Every sketch takes
// the flags of `calder render` and --trajectory (docs/SKETCH.md).
//
// Drawing goes through calder::Canvas's shapes (calder/render.hpp): a circle
// a sketch draws and a body `calder render` draws are the same pixels.
// random() and noise() are p5's generators (calder/random.hpp), seeded with
// --seed (default 1) before setup(), so a sketch is the same on every run.
//
// Part of the calder::sketch library (CMake component sketch): Cairo draws,
// SDL2 shows; a build without SDL2 has the headless mode only.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "calder/random.hpp"
#include "calder/render.hpp"
#include "calder/world.hpp"

namespace calder {

class SketchRunner;

// How the runner runs a sketch: what its flags say (parse_sketch_options).
struct SketchOptions {
  enum class Mode { automatic, window, headless };
  Mode mode = Mode::automatic;
  // Frames to draw; headless without it: 600 (ten seconds of the book's
  // sketches); in a window without it: until closed.
  std::optional<std::int64_t> frames;
  std::optional<std::string> gif;         // an animated GIF of every frame
  std::optional<std::string> png;         // DIR/frame-000001.png, ... (draw() numbers)
  std::optional<std::string> trajectory;  // CSV of the recorded world, "-": stdout
  double scale = 1.0;                     // pixel density (times the display's in a window)
  double gif_fps = 30.0;                  // as `calder render --fps`
  std::int64_t every = 1;                 // --gif and --png take every K-th frame
  std::uint32_t seed = 1;
  // Scripted mouse: held in these frames (inclusive draw() numbers, 1-based)
  // and at this position; given, they replace the live mouse in a window.
  std::vector<std::pair<std::int64_t, std::int64_t>> mouse_pressed;
  std::optional<Vec2> mouse;
  std::optional<double> exit_after_seconds;  // a window closes after this long
  bool quiet = false;                        // no line on stderr about what was written
  // Called once a display frame in a window, and before each frame headless;
  // what it throws stops the run (the calder command stops on a signal).
  std::function<void()> poll;
  std::string program = "sketch";  // for messages
};

// Parses the runner's flags (argv[0] is the program). Throws calder::Error
// with one line naming the flag and the problem. --help is reported by
// `help` (and nothing else is parsed).
SketchOptions parse_sketch_options(int argc, const char* const* argv, bool* help = nullptr);
// The flags, one a line, for --help.
std::string sketch_usage(const std::string& program);

class Sketch {
 public:
  Sketch();
  virtual ~Sketch();
  Sketch(const Sketch&) = delete;
  Sketch& operator=(const Sketch&) = delete;

  // p5's functions a sketch defines.
  virtual void setup() {}
  virtual void draw() {}
  virtual void mouse_pressed() {}
  virtual void mouse_released() {}
  virtual void mouse_dragged() {}  // the mouse moved with a button held
  virtual void key_pressed() {}
  // Once, when the sketch ends (the window closed, --frames drawn,
  // exit_sketch()), the canvas still there: save what is left.
  virtual void on_exit() {}

 protected:
  // --- the canvas ---
  // createCanvas(w, h): in a window, its size in window points. Without a
  // call the canvas is 100 x 100, as in p5. Call it once, in setup().
  void create_canvas(int w, int h);
  [[nodiscard]] int width() const;
  [[nodiscard]] int height() const;
  // The image itself, for what p5 has no word for: draw a whole World in the
  // book's look (Canvas::draw), read pixels back.
  Canvas& canvas();

  // --- colour and style (0..255, as p5) ---
  void background(double gray, double alpha = 255.0);
  void background(double r, double g, double b, double alpha = 255.0);
  void background(const Color& color);
  void fill(double gray, double alpha = 255.0);
  void fill(double r, double g, double b, double alpha = 255.0);
  void fill(const Color& color);
  void no_fill();
  void stroke(double gray, double alpha = 255.0);
  void stroke(double r, double g, double b, double alpha = 255.0);
  void stroke(const Color& color);
  void no_stroke();
  void stroke_weight(double weight);
  void text_size(double size);
  [[nodiscard]] const ShapeStyle& style() const { return style_; }

  // --- shapes ---
  void circle(double x, double y, double diameter);
  void ellipse(double x, double y, double w, double h);
  void ellipse(double x, double y, double diameter) { ellipse(x, y, diameter, diameter); }
  void rect(double x, double y, double w, double h);
  void square(double x, double y, double side) { rect(x, y, side, side); }
  void line(double x1, double y1, double x2, double y2);
  void point(double x, double y);
  void triangle(double x1, double y1, double x2, double y2, double x3, double y3);
  void text(const std::string& words, double x, double y);

  // --- transforms (reset before each draw(), as in p5) ---
  void push();  // saves the transform and the style
  void pop();   // throws calder::Error without a matching push()
  void translate(double x, double y);
  void translate(Vec2 v) { translate(v.x, v.y); }
  void rotate(double angle);  // radians
  void scale(double s) { scale(s, s); }
  void scale(double sx, double sy);

  // --- input ---
  [[nodiscard]] double mouse_x() const { return mouse_.x; }
  [[nodiscard]] double mouse_y() const { return mouse_.y; }
  [[nodiscard]] double pmouse_x() const { return pmouse_.x; }
  [[nodiscard]] double pmouse_y() const { return pmouse_.y; }
  [[nodiscard]] bool mouse_is_pressed() const { return mouse_is_pressed_; }
  // The last key pressed, as p5's `key`: the character typed ("a", " ",
  // "+"), or a name ("Enter", "Escape", "ArrowLeft", "Backspace", "Tab").
  [[nodiscard]] const std::string& key() const { return key_; }
  [[nodiscard]] bool key_repeated() const { return key_repeated_; }  // held down, auto-repeating

  // --- time ---
  // draw()'s number: 1 in the first draw(), as p5's frameCount.
  [[nodiscard]] std::int64_t frame_count() const { return frame_count_; }
  void frame_rate(double fps);  // in (0, 1000]; a window's pace (headless: the GIF's is --fps)
  [[nodiscard]] double frame_rate() const { return frame_rate_; }
  void no_loop();  // no more draw(): headless stops, a window stays open
  void loop();
  void redraw();  // one more draw() while not looping
  [[nodiscard]] bool is_looping() const { return looping_; }
  void exit_sketch();  // closes the window (headless: stops) after this draw()
  // In a window: its title (default: the program's name).
  void window_title(const std::string& title);

  // --- randomness (p5's generators, seeded with --seed before setup) ---
  double random() { return random_.random(); }
  double random(double max) { return random_.random(max); }
  double random(double min, double max) { return random_.random(min, max); }
  double random_gaussian(double mean = 0.0, double sd = 1.0) {
    return random_.random_gaussian(mean, sd);
  }
  void random_seed(std::uint32_t seed) { random_.random_seed(seed); }
  [[nodiscard]] double noise(double x, double y = 0.0, double z = 0.0) const {
    return noise_.noise(x, y, z);
  }
  void noise_seed(std::uint32_t seed) { noise_.noise_seed(seed); }
  void noise_detail(int octaves, double falloff = 0.5) { noise_.noise_detail(octaves, falloff); }
  // --seed: for a World of the sketch's own (WorldDef::seed).
  [[nodiscard]] std::uint32_t seed() const { return seed_; }

  // --- output ---
  // saveFrame: the canvas as it is now, a PNG (written atomically).
  void save_frame(const std::string& path) const;
  // The world whose state --trajectory writes: after setup() (frame 0) and
  // after each draw(). It must outlive the run.
  void record(const World& world) { recorded_ = &world; }

 private:
  friend class SketchRunner;

  SketchRunner* runner_ = nullptr;
  ShapeStyle style_;
  double text_size_ = 12.0;
  Transform transform_;
  std::vector<std::pair<Transform, std::pair<ShapeStyle, double>>> saved_;
  Vec2 mouse_{};
  Vec2 pmouse_{};
  bool mouse_is_pressed_ = false;
  std::string key_;
  bool key_repeated_ = false;
  std::int64_t frame_count_ = 0;
  double frame_rate_ = 60.0;
  bool looping_ = true;
  bool redraw_ = false;
  bool exit_ = false;
  std::uint32_t seed_ = 1;
  Random random_;
  Noise noise_;
  const World* recorded_ = nullptr;
};

// Runs a sketch with options; throws calder::InputError (one line) for what
// it cannot do from the start (no display for a window, an output folder
// that cannot be made), calder::RunError or calder::Error for what fails
// while it runs, and whatever the sketch's own functions throw.
void run_sketch(Sketch& sketch, const SketchOptions& options);

// Parses the flags and runs the sketch: the exit status for main. Prints the
// usage for --help (0); one line on stderr and 2 for bad flags or no display
// with no output asked; one line and 1 for a failure while running.
int run_sketch(Sketch& sketch, int argc, char** argv);

// The same for a sketch of class S made here; once it is gone, frees what
// Cairo keeps for the process (release_render_caches), for a clean exit
// under leak checkers.
template <class S>
int run_sketch(int argc, char** argv) {
  int status = 0;
  {
    S sketch;
    status = run_sketch(sketch, argc, argv);
  }
  release_render_caches();
  return status;
}

// Whether this build of calder::sketch can open a window (SDL2 was found).
bool sketch_has_window();

}  // namespace calder
