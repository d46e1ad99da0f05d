// SPDX-License-Identifier: MIT
// Example 2.9: n Bodies. Ten bodies of random mass at random places attract
// one another, each updated right after its forces, as in the book.
//
//   example_2_9_n_bodies [--seed S] [--gif FILE | --trajectory FILE ...]
//   (the same bits as `calder run example-2.9 --seed S`)
#include <calder/calder.hpp>
#include <calder/sketch.hpp>
#include <vector>

class NBodies : public calder::Sketch {
  calder::World world{{.width = 640, .height = 240}};
  std::vector<calder::Mover> bodies;
  const calder::AttractionLaw law =
      calder::AttractionLaw::book(1, 5, 25, calder::MassProduct::left_to_right);

  void setup() override {
    create_canvas(640, 240);
    for (int i = 0; i < 10; ++i) {
      const double x = random(width());
      const double y = random(height());
      const double mass = random(0.1, 2);
      bodies.push_back(world.add_mover({.position = {x, y}, .mass = mass, .radius = mass * 8}));
    }
    record(world);
  }

  void draw() override {
    background(255);
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      for (std::size_t j = 0; j < bodies.size(); ++j) {
        if (i != j) bodies[i].apply_force(bodies[j].attract(bodies[i], law));
      }
      bodies[i].update();
      show(bodies[i]);
    }
  }

  void show(const calder::Mover& b) {
    stroke(0);
    stroke_weight(2);
    fill(127, 127);
    circle(b.position().x, b.position().y, b.mass() * 16);
  }
};

int main(int argc, char** argv) { return calder::run_sketch<NBodies>(argc, argv); }
