// SPDX-License-Identifier: MIT
// calder::sketch's runner: one frame of a sketch (its input, draw() and
// outputs), shared by the headless loop (runner.cpp) and the window's
// (window.cpp). Not installed.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <sstream>
#include <string>

#include "../output/output.hpp"
#include "calder/render.hpp"
#include "calder/sketch.hpp"
#include "calder/trajectory.hpp"

namespace calder {

class SketchRunner {
 public:
  SketchRunner(Sketch& sketch, const SketchOptions& options);
  ~SketchRunner();
  SketchRunner(const SketchRunner&) = delete;
  SketchRunner& operator=(const SketchRunner&) = delete;

  // Seeds the sketch's generators, runs setup() and makes sure there is a
  // canvas (100 x 100 without create_canvas), then writes frame 0 of the
  // trajectory.
  void setup();
  // create_canvas: the window (when one is shown) opens at this size.
  void create_canvas(int width, int height);
  // One frame: the scripted mouse's events, draw(), then the outputs.
  void draw_frame();
  // Whether another draw() is due now (looping, or a redraw() asked), and
  // whether the sketch or --frames ended the run.
  [[nodiscard]] bool wants_draw() const;
  [[nodiscard]] bool finished() const;
  // Writes what is left (the GIF's end, the trajectory).
  void finish();

  // The live mouse and keys (a window's events), in canvas pixels; ignored
  // while the mouse is scripted.
  void mouse_moved(double x, double y);
  void mouse_down(double x, double y);
  void mouse_up(double x, double y);
  void key_down(const std::string& key, bool repeat);

  Sketch& sketch() { return sketch_; }
  [[nodiscard]] double frame_rate() const { return sketch_.frame_rate_; }
  [[nodiscard]] bool looping() const { return sketch_.looping_; }
  const SketchOptions& options() const { return options_; }
  Canvas& canvas();
  [[nodiscard]] bool has_canvas() const { return canvas_.has_value(); }
  // The window's title as the sketch last set it.
  [[nodiscard]] const std::string& title() const { return title_; }
  void set_title(const std::string& title) { title_ = title; }

  // Set by the window before setup(): opens a window for a canvas of
  // width x height canvas pixels and returns the display's pixels per
  // window point (2 on a HiDPI display).
  std::function<double(int width, int height)> open_window;

 private:
  [[nodiscard]] bool scripted_pressed(std::int64_t frame) const;
  void write_outputs();

  Sketch& sketch_;
  const SketchOptions& options_;
  std::optional<Canvas> canvas_;
  std::optional<GifWriter> gif_;
  std::optional<output::AtomicFolder> png_;
  std::ostringstream trajectory_text_;
  std::optional<TrajectoryWriter> trajectory_;
  std::string title_;
  Vec2 last_frame_mouse_{};
  bool live_pressed_ = false;
};

// A window for the sketch until it closes (window.cpp); throws
// calder::Error without a display.
void run_sketch_window(SketchRunner& runner);
// Why there is no window to open here ("" when there may be one).
std::string sketch_no_display_reason();

}  // namespace calder
