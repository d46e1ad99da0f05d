// SPDX-License-Identifier: MIT
// Example 2.6: Attraction. A mover orbits an attractor (mass 20, G = 1, the
// distance clamped to [5, 25]); drag the attractor with the mouse.
//
//   example_2_6_attraction [--gif FILE | --trajectory FILE ...]
#include <calder/calder.hpp>
#include <calder/sketch.hpp>

class Attraction : public calder::Sketch {
  calder::World world{{.width = 640, .height = 240}};
  calder::Mover mover =
      world.add_mover({.position = {300, 50}, .velocity = {1, 0}, .mass = 2, .radius = 16});
  // The attractor is not a moving body: it only exerts a force.
  calder::Attractor attractor{
      .position = {320, 120},
      .mass = 20,
      .law = calder::AttractionLaw::book(1, 5, 25, calder::MassProduct::left_to_right)};
  bool dragging = false;
  calder::Vec2 drag_offset;

  void setup() override {
    create_canvas(640, 240);
    record(world);
  }

  void draw() override {
    background(255);
    const calder::Vec2 force = attractor.attract(mover.position(), mover.mass());
    mover.apply_force(force);
    mover.update();
    show(attractor);
    show(mover);
  }

  // The attractor follows the mouse while it is dragged.
  void mouse_pressed() override {
    const calder::Vec2 mouse{mouse_x(), mouse_y()};
    if (calder::dist(mouse, attractor.position) < attractor.mass) {
      dragging = true;
      drag_offset = attractor.position - mouse;
    }
  }
  void mouse_dragged() override {
    if (dragging) attractor.position = calder::Vec2{mouse_x(), mouse_y()} + drag_offset;
  }
  void mouse_released() override { dragging = false; }

  void show(const calder::Attractor& a) {
    stroke(0);
    stroke_weight(4);
    fill(175, 200);
    circle(a.position.x, a.position.y, a.mass * 2);
  }

  void show(const calder::Mover& m) {
    stroke(0);
    stroke_weight(2);
    fill(127, 127);
    circle(m.position().x, m.position().y, m.mass() * 16);
  }
};

int main(int argc, char** argv) { return calder::run_sketch<Attraction>(argc, argv); }
