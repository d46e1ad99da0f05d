// SPDX-License-Identifier: MIT
// Example 2.1: Forces. A mover falls under gravity; while the mouse is held
// down, wind pushes it right. It bounces off the left, right and bottom edges.
//
//   example_2_1_forces                       a window (click and hold for wind)
//   example_2_1_forces --gif forces.gif      headless: 600 frames as a GIF
//   example_2_1_forces --mouse-pressed 100-160 --trajectory -
//                                            the p5.js reference run, as CSV
#include <calder/calder.hpp>
#include <calder/sketch.hpp>

class Forces : public calder::Sketch {
  calder::World world{{.width = 640, .height = 240}};
  calder::Mover mover = world.add_mover({.position = {320, 30}, .mass = 1});
  const calder::Boundary edges = calder::Boundary::bounce(1.0, false, {.top = false});

  void setup() override {
    create_canvas(640, 240);
    record(world);
  }

  void draw() override {
    background(255);

    const calder::Vec2 gravity{0, 0.1};
    mover.apply_force(gravity);
    if (mouse_is_pressed()) {
      const calder::Vec2 wind{0.1, 0};
      mover.apply_force(wind);
    }
    mover.update();
    mover.check_edges(edges);
    show(mover);
  }

  void show(const calder::Mover& m) {
    stroke(0);
    stroke_weight(2);
    fill(127, 127);
    circle(m.position().x, m.position().y, 48);
  }
};

int main(int argc, char** argv) { return calder::run_sketch<Forces>(argc, argv); }
