// SPDX-License-Identifier: MIT
// Example 2.4: Including Friction. A mover bounces and slides to a stop on
// the floor: friction (-c v-hat, c = 0.1) while it touches the bottom edge.
// Wind pushes it right while the mouse is held down.
//
//   example_2_4_including_friction [--gif FILE | --trajectory FILE ...]
#include <calder/calder.hpp>
#include <calder/sketch.hpp>

class IncludingFriction : public calder::Sketch {
  calder::World world{{.width = 640, .height = 240}};
  calder::Mover mover = world.add_mover({.position = {320, 30}, .mass = 5, .radius = 40});
  const calder::Boundary bounce_edges = calder::Boundary::bounce(0.9, true, {.top = false});

  void setup() override {
    create_canvas(640, 240);
    record(world);
  }

  void draw() override {
    background(255);

    const calder::Vec2 gravity{0, 1};
    mover.apply_force(gravity);
    if (mouse_is_pressed()) {
      const calder::Vec2 wind{0.5, 0};
      mover.apply_force(wind);
    }
    if (mover.contact_edge()) {
      const double c = 0.1;
      mover.apply_force(calder::friction(mover.velocity(), c));
    }
    mover.check_edges(bounce_edges);  // the book bounces before the update
    mover.update();
    show(mover);
  }

  void show(const calder::Mover& m) {
    stroke(0);
    stroke_weight(2);
    fill(127, 127);
    circle(m.position().x, m.position().y, m.radius() * 2);
  }
};

int main(int argc, char** argv) { return calder::run_sketch<IncludingFriction>(argc, argv); }
