// SPDX-License-Identifier: MIT
// Example 2.3: Gravity Scaled by Mass. Gravity times each mover's mass makes
// heavy and light movers fall together; wind (while the mouse is held down)
// still moves the light one more. The edges count the radius.
//
//   example_2_3_gravity_scaled_by_mass [--gif FILE | --trajectory FILE ...]
#include <calder/calder.hpp>
#include <calder/sketch.hpp>

class GravityScaledByMass : public calder::Sketch {
  calder::World world{{.width = 640, .height = 240}};
  calder::Mover mover_a = world.add_mover({.position = {200, 30}, .mass = 10, .radius = 10 * 8});
  calder::Mover mover_b = world.add_mover({.position = {440, 30}, .mass = 2, .radius = 2 * 8});
  const calder::Boundary edges = calder::Boundary::bounce(1.0, true, {.top = false});

  void setup() override {
    create_canvas(640, 240);
    record(world);
  }

  void draw() override {
    background(255);

    const calder::Vec2 gravity{0, 0.1};
    for (calder::Mover* m : {&mover_a, &mover_b}) {
      m->apply_force(calder::gravity(gravity, m->mass(), true));  // gravity * mass
    }
    if (mouse_is_pressed()) {
      const calder::Vec2 wind{0.1, 0};
      mover_a.apply_force(wind);
      mover_b.apply_force(wind);
    }
    for (calder::Mover* m : {&mover_a, &mover_b}) {
      m->update();
      m->check_edges(edges);
      show(*m);
    }
  }

  void show(const calder::Mover& m) {
    stroke(0);
    stroke_weight(2);
    fill(127, 127);
    circle(m.position().x, m.position().y, m.radius() * 2);
  }
};

int main(int argc, char** argv) { return calder::run_sketch<GravityScaledByMass>(argc, argv); }
