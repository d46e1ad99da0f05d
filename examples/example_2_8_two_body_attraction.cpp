// SPDX-License-Identifier: MIT
// Example 2.8: Two-Body Attraction. Two equal bodies started in opposite
// directions pull on each other and orbit their common centre.
//
//   example_2_8_two_body_attraction [--gif FILE | --trajectory FILE ...]
#include <calder/calder.hpp>
#include <calder/sketch.hpp>
#include <cmath>

class TwoBodies : public calder::Sketch {
  calder::World world{{.width = 640, .height = 240}};
  calder::Mover body_a = world.add_mover({.position = {320, 40}, .velocity = {1, 0}, .mass = 8});
  calder::Mover body_b = world.add_mover({.position = {320, 200}, .velocity = {-1, 0}, .mass = 8});
  // This sketch multiplies the masses first: G * (mA * mB) / (d * d).
  const calder::AttractionLaw law =
      calder::AttractionLaw::book(1, 5, 25, calder::MassProduct::masses_first);

  void setup() override {
    create_canvas(640, 240);
    record(world);
  }

  void draw() override {
    background(255);
    // Both forces come from the positions before this frame's updates.
    const calder::Vec2 force_on_b = body_a.attract(body_b, law);
    const calder::Vec2 force_on_a = body_b.attract(body_a, law);
    body_b.apply_force(force_on_b);
    body_a.apply_force(force_on_a);
    body_a.update();
    body_b.update();
    show(body_a);
    show(body_b);
  }

  // The book's Body: r = sqrt(mass) * 2, drawn as a circle of diameter 2r.
  void show(const calder::Mover& b) {
    stroke(0);
    stroke_weight(2);
    fill(127, 127);
    circle(b.position().x, b.position().y, std::sqrt(b.mass()) * 2 * 2);
  }
};

int main(int argc, char** argv) { return calder::run_sketch<TwoBodies>(argc, argv); }
