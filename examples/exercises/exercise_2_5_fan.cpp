// SPDX-License-Identifier: MIT
// Exercise 2.5: a fan at the mouse blows the circles away from it, strongest
// up close (strength 2, falling to 0 at 250 px), against gravity and the
// floor's friction. Move the mouse around them.
//
//   exercise_2_5_fan [--mouse X,Y] [--gif FILE | --trajectory FILE ...]
#include <calder/calder.hpp>
#include <calder/sketch.hpp>

class FanAtTheMouse : public calder::Sketch {
  calder::World world{
      {.width = 640, .height = 240, .boundary = calder::Boundary::bounce(0.6, true)}};
  calder::Fan* fan = nullptr;

  void setup() override {
    create_canvas(640, 240);
    for (int i = 0; i < 8; ++i) {
      const double mass = random(1, 3);
      world.add_mover({.position = {60.0 + i * 75.0, 200}, .mass = mass, .radius = mass * 8});
    }
    world.add(calder::Gravity{.g = {0, 0.2}, .scale_by_mass = true});
    fan = &world.add(calder::Fan{.position = {0, 120}, .strength = 2.0, .reach = 250.0});
    world.add(calder::Friction{.mu = 0.1});
    record(world);
  }

  void draw() override {
    background(255);
    fan->position = {mouse_x(), mouse_y()};
    world.step();
    // The fan's reach, and the fan itself.
    no_fill();
    stroke(0, 40);
    stroke_weight(1);
    circle(mouse_x(), mouse_y(), fan->reach * 2);
    push();
    translate(mouse_x(), mouse_y());
    rotate(static_cast<double>(frame_count()) * 0.2);
    fill(100);
    no_stroke();
    for (int blade = 0; blade < 3; ++blade) {
      triangle(0, 0, 18, -5, 18, 5);
      rotate(2.0 * 3.14159265358979 / 3.0);
    }
    pop();
    stroke(0);
    stroke_weight(2);
    fill(127, 127);
    for (std::size_t i = 0; i < world.body_count(); ++i) {
      const calder::BodyId body = world.body(i);
      circle(world.position(body).x, world.position(body).y, world.radius(body) * 2);
    }
  }
};

int main(int argc, char** argv) { return calder::run_sketch<FanAtTheMouse>(argc, argv); }
