// SPDX-License-Identifier: MIT
// Example 2.2: Forces Acting on Two Objects. The same gravity and wind (while
// the mouse is held down) move a light mover more than a heavy one: a = F / m.
//
//   example_2_2_forces_acting_on_two_objects [--gif FILE | --trajectory FILE ...]
#include <calder/calder.hpp>
#include <calder/sketch.hpp>

class TwoObjects : public calder::Sketch {
  calder::World world{{.width = 640, .height = 240}};
  calder::Mover mover_a = world.add_mover({.position = {200, 30}, .mass = 10});
  calder::Mover mover_b = world.add_mover({.position = {440, 30}, .mass = 2});
  const calder::Boundary edges = calder::Boundary::bounce(1.0, false, {.top = false});

  void setup() override {
    create_canvas(640, 240);
    record(world);
  }

  void draw() override {
    background(255);

    const calder::Vec2 gravity{0, 0.1};
    mover_a.apply_force(gravity);
    mover_b.apply_force(gravity);
    if (mouse_is_pressed()) {
      const calder::Vec2 wind{0.1, 0};
      mover_a.apply_force(wind);
      mover_b.apply_force(wind);
    }
    mover_a.update();
    mover_a.check_edges(edges);
    show(mover_a);
    mover_b.update();
    mover_b.check_edges(edges);
    show(mover_b);
  }

  void show(const calder::Mover& m) {
    stroke(0);
    stroke_weight(2);
    fill(127, 127);
    circle(m.position().x, m.position().y, m.mass() * 16);
  }
};

int main(int argc, char** argv) { return calder::run_sketch<TwoObjects>(argc, argv); }
