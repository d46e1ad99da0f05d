// SPDX-License-Identifier: MIT
// The README's first sketch (example 2.1), built against an installed calder:
// the install test runs it headless and checks the GIF it writes.
#include <calder/calder.hpp>
#include <calder/sketch.hpp>

class Forces : public calder::Sketch {
  calder::World world{{.width = 640, .height = 240}};
  calder::Mover mover = world.add_mover({.position = {320, 30}, .mass = 1});

  void setup() override { create_canvas(640, 240); }

  void draw() override {
    background(255);
    mover.apply_force({0, 0.1});                          // gravity
    if (mouse_is_pressed()) mover.apply_force({0.1, 0});  // wind
    mover.update();
    mover.check_edges(calder::Boundary::bounce(1.0, false, {.top = false}));
    stroke(0);
    fill(127, 127);
    circle(mover.position().x, mover.position().y, 48);
  }
};

int main(int argc, char** argv) { return calder::run_sketch<Forces>(argc, argv); }
