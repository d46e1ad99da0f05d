// SPDX-License-Identifier: MIT
// Example 2.5: Fluid Resistance. Nine movers of random mass fall from the
// top; in the liquid (the lower half) drag (-c |v|^2 v-hat, c = 0.1) slows
// them, the light ones most. They bounce off the floor with 90% of their
// speed. A click starts them again with new masses.
//
//   example_2_5_fluid_resistance [--seed S] [--gif FILE | --trajectory FILE ...]
//   (the same bits as `calder run example-2.5 --seed S`)
#include <calder/calder.hpp>
#include <calder/sketch.hpp>
#include <vector>

class FluidResistance : public calder::Sketch {
  calder::World world{{.width = 640, .height = 240}};
  std::vector<calder::Mover> movers;
  const calder::Liquid liquid{.region = {0, 120, 640, 120}, .c = 0.1};
  const calder::Boundary floor_only =
      calder::Boundary::bounce(0.9, true, {.left = false, .right = false, .top = false});

  void setup() override {
    create_canvas(640, 240);
    reset();
    record(world);
  }

  void draw() override {
    background(255);
    show(liquid);
    for (calder::Mover& mover : movers) {
      if (liquid.contains(mover.position())) {
        mover.apply_force(liquid.calculate_drag(mover.velocity()));
      }
      const calder::Vec2 gravity{0, 0.1 * mover.mass()};  // scaled by mass
      mover.apply_force(gravity);
      mover.update();
      mover.check_edges(floor_only);
      show(mover);
    }
  }

  void mouse_pressed() override { reset(); }

  // Nine movers in a row at the top, each of a random mass.
  void reset() {
    world.clear_bodies();
    movers.clear();
    for (int i = 0; i < 9; ++i) {
      const double mass = random(0.5, 3);
      movers.push_back(
          world.add_mover({.position = {40.0 + i * 70.0, 0}, .mass = mass, .radius = mass * 8}));
    }
  }

  void show(const calder::Liquid& l) {
    no_stroke();
    fill(200);
    rect(l.region.x, l.region.y, l.region.w, l.region.h);
  }

  void show(const calder::Mover& m) {
    stroke(0);
    stroke_weight(2);
    fill(127, 127);
    circle(m.position().x, m.position().y, m.mass() * 16);
  }
};

int main(int argc, char** argv) { return calder::run_sketch<FluidResistance>(argc, argv); }
