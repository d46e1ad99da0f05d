// SPDX-License-Identifier: MIT
// Exercise 2.3: instead of bouncing off the walls, the movers are pushed back
// by an invisible force, stronger the closer they come to an edge (calder's
// EdgeForce: strength 1 at the wall, falling to 0 at 60 px). Hold the mouse
// down for wind to the right, and watch the force hold them in.
//
//   exercise_2_3_edge_force [--seed S] [--gif FILE | --trajectory FILE ...]
#include <calder/calder.hpp>
#include <calder/sketch.hpp>

class EdgeForces : public calder::Sketch {
  calder::World world{{.width = 640, .height = 240, .boundary = calder::Boundary::none()}};

  void setup() override {
    create_canvas(640, 240);
    for (int i = 0; i < 10; ++i) {
      const double mass = random(0.5, 3);
      world.add_mover({.position = {random(width()), random(height())},
                       .velocity = {random(-3, 3), random(-3, 3)},
                       .mass = mass,
                       .radius = mass * 8});
    }
    world.add(calder::EdgeForce{.strength = 1.0, .margin = 60.0});
    record(world);
  }

  void draw() override {
    background(255);
    if (mouse_is_pressed()) {
      for (std::size_t i = 0; i < world.body_count(); ++i) {
        world.apply_force(world.body(i), {0.5, 0});
      }
    }
    world.step();
    // The margin where the force acts, faintly.
    no_fill();
    stroke(0, 30);
    stroke_weight(1);
    rect(60, 60, width() - 120, height() - 120);
    stroke(0);
    stroke_weight(2);
    fill(127, 127);
    for (std::size_t i = 0; i < world.body_count(); ++i) {
      const calder::BodyId body = world.body(i);
      circle(world.position(body).x, world.position(body).y, world.radius(body) * 2);
    }
  }
};

int main(int argc, char** argv) { return calder::run_sketch<EdgeForces>(argc, argv); }
