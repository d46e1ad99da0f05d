// SPDX-License-Identifier: MIT
// calder::sketch: the drawing vocabulary of a Sketch (onto calder::Canvas's
// shapes) and its state between frames.
#include "calder/sketch.hpp"

#include <cmath>
#include <string>

#include "calder/error.hpp"
#include "runner.hpp"

namespace calder {

namespace {

Color checked_color(const char* who, double r, double g, double b, double a) {
  for (const double v : {r, g, b, a}) {
    if (!(v >= 0.0 && v <= 255.0)) {
      throw Error(std::string(who) + ": colour components must be 0 to 255 (got " +
                  detail::format_number(v) + ")");
    }
  }
  return Color::rgb(r, g, b, a);
}

}  // namespace

Sketch::Sketch() = default;
Sketch::~Sketch() = default;

static SketchRunner& require_runner(SketchRunner* runner, const char* who) {
  if (runner == nullptr) {
    throw Error(std::string("Sketch::") + who +
                ": only while the sketch runs (from setup(), draw() or an event)");
  }
  return *runner;
}

void Sketch::create_canvas(int w, int h) {
  require_runner(runner_, "create_canvas").create_canvas(w, h);
}
int Sketch::width() const { return require_runner(runner_, "width").canvas().width(); }
int Sketch::height() const { return require_runner(runner_, "height").canvas().height(); }
Canvas& Sketch::canvas() { return require_runner(runner_, "canvas").canvas(); }

void Sketch::background(double gray, double alpha) { background(gray, gray, gray, alpha); }
void Sketch::background(double r, double g, double b, double alpha) {
  background(checked_color("background", r, g, b, alpha));
}
void Sketch::background(const Color& color) { canvas().background(color); }

void Sketch::fill(double gray, double alpha) { fill(gray, gray, gray, alpha); }
void Sketch::fill(double r, double g, double b, double alpha) {
  style_.fill = checked_color("fill", r, g, b, alpha);
}
void Sketch::fill(const Color& color) { style_.fill = color; }
void Sketch::no_fill() { style_.fill = Color::none(); }
void Sketch::stroke(double gray, double alpha) { stroke(gray, gray, gray, alpha); }
void Sketch::stroke(double r, double g, double b, double alpha) {
  style_.stroke = checked_color("stroke", r, g, b, alpha);
}
void Sketch::stroke(const Color& color) { style_.stroke = color; }
void Sketch::no_stroke() { style_.stroke = Color::none(); }
void Sketch::stroke_weight(double weight) {
  if (!(weight >= 0.0 && std::isfinite(weight))) {
    throw Error("stroke_weight: expected a finite number >= 0 (got " +
                detail::format_number(weight) + ")");
  }
  style_.stroke_weight = weight;
}
void Sketch::text_size(double size) {
  if (!(size > 0.0 && std::isfinite(size))) {
    throw Error("text_size: expected a finite number > 0 (got " + detail::format_number(size) +
                ")");
  }
  text_size_ = size;
}

void Sketch::circle(double x, double y, double diameter) {
  Canvas& c = canvas();
  c.set_transform(transform_);
  c.circle(x, y, diameter, style_);
}
void Sketch::ellipse(double x, double y, double w, double h) {
  Canvas& c = canvas();
  c.set_transform(transform_);
  c.ellipse(x, y, w, h, style_);
}
void Sketch::rect(double x, double y, double w, double h) {
  Canvas& c = canvas();
  c.set_transform(transform_);
  c.rect(x, y, w, h, style_);
}
void Sketch::line(double x1, double y1, double x2, double y2) {
  Canvas& c = canvas();
  c.set_transform(transform_);
  c.line(x1, y1, x2, y2, style_);
}
void Sketch::point(double x, double y) {
  Canvas& c = canvas();
  c.set_transform(transform_);
  c.point(x, y, style_);
}
void Sketch::triangle(double x1, double y1, double x2, double y2, double x3, double y3) {
  Canvas& c = canvas();
  c.set_transform(transform_);
  c.triangle(x1, y1, x2, y2, x3, y3, style_);
}
void Sketch::text(const std::string& words, double x, double y) {
  Canvas& c = canvas();
  c.set_transform(transform_);
  c.text(words, x, y, text_size_, style_);
}

void Sketch::push() { saved_.push_back({transform_, {style_, text_size_}}); }
void Sketch::pop() {
  if (saved_.empty()) throw Error("pop: no push() to go back to");
  transform_ = saved_.back().first;
  style_ = saved_.back().second.first;
  text_size_ = saved_.back().second.second;
  saved_.pop_back();
}
void Sketch::translate(double x, double y) {
  if (!std::isfinite(x) || !std::isfinite(y)) throw Error("translate: expected finite numbers");
  transform_ = transform_.translated(x, y);
}
void Sketch::rotate(double angle) {
  if (!std::isfinite(angle)) throw Error("rotate: expected a finite angle");
  transform_ = transform_.rotated(angle);
}
void Sketch::scale(double sx, double sy) {
  if (!std::isfinite(sx) || !std::isfinite(sy)) throw Error("scale: expected finite numbers");
  transform_ = transform_.scaled(sx, sy);
}

void Sketch::frame_rate(double fps) {
  if (!(fps > 0.0 && fps <= 1000.0)) {
    throw Error("frame_rate: expected a number in (0, 1000] (got " + detail::format_number(fps) +
                ")");
  }
  frame_rate_ = fps;
}
void Sketch::no_loop() { looping_ = false; }
void Sketch::loop() { looping_ = true; }
void Sketch::redraw() { redraw_ = true; }
void Sketch::exit_sketch() { exit_ = true; }
void Sketch::window_title(const std::string& title) {
  require_runner(runner_, "window_title").set_title(title);
}

void Sketch::save_frame(const std::string& path) const {
  require_runner(runner_, "save_frame").canvas().write_png(path);
}

}  // namespace calder
