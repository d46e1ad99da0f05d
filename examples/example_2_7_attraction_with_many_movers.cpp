// SPDX-License-Identifier: MIT
// Example 2.7: Attraction with Many Movers. Ten movers of random mass at
// random places, all started to the right at speed 1, fall around one
// attractor (mass 20, G = 1, d clamped to [5, 25]); drag it with the mouse.
//
//   example_2_7_attraction_with_many_movers [--seed S] [--gif FILE | --trajectory FILE ...]
//   (the same bits as `calder run example-2.7 --seed S`)
#include <calder/calder.hpp>
#include <calder/sketch.hpp>
#include <vector>

class ManyMovers : public calder::Sketch {
  calder::World world{{.width = 640, .height = 240}};
  std::vector<calder::Mover> movers;
  calder::Attractor attractor{
      .position = {320, 120},
      .mass = 20,
      .law = calder::AttractionLaw::book(1, 5, 25, calder::MassProduct::left_to_right)};
  bool dragging = false;
  calder::Vec2 drag_offset;

  void setup() override {
    create_canvas(640, 240);
    for (int i = 0; i < 10; ++i) {
      // new Mover(random(width), random(height), random(0.5, 3)): drawn in that order.
      const double x = random(width());
      const double y = random(height());
      const double mass = random(0.5, 3);
      movers.push_back(world.add_mover(
          {.position = {x, y}, .velocity = {1, 0}, .mass = mass, .radius = mass * 8}));
    }
    record(world);
  }

  void draw() override {
    background(255);
    show(attractor);
    for (calder::Mover& mover : movers) {
      const calder::Vec2 force = attractor.attract(mover.position(), mover.mass());
      mover.apply_force(force);
      mover.update();
      show(mover);
    }
  }

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

int main(int argc, char** argv) { return calder::run_sketch<ManyMovers>(argc, argv); }
