// SPDX-License-Identifier: MIT
// Example 2.5: Fluid Resistance. Nine movers of random mass fall from the
// top; in the liquid (the lower half) drag (-c |v|^2 v-hat, c = 0.1) slows
// them, the light ones most. They bounce off the floor with 90% of their speed.
// Prints the trajectory as CSV: frame,body,x,y,vx,vy.
//
//   example_2_5_fluid_resistance [seed]   (default 1; same bits as
//                                          `calder run example-2.5 --seed <seed>`)
#include <calder/calder.hpp>
#include <cstdlib>
#include <iostream>
#include <vector>

int main(int argc, char** argv) {
  const auto seed = static_cast<std::uint32_t>(argc > 1 ? std::strtoul(argv[1], nullptr, 10) : 1);
  calder::World world({.width = 640, .height = 240, .seed = seed});  // randomSeed(seed)
  std::vector<calder::Mover> movers;
  for (int i = 0; i < 9; ++i) {
    const double mass = world.random().random(0.5, 3);
    movers.push_back(
        world.add_mover({.position = {40.0 + i * 70.0, 0}, .mass = mass, .radius = mass * 8}));
  }
  const calder::Liquid liquid{.region = {0, 120, 640, 120}, .c = 0.1};
  const calder::Boundary floor_only =
      calder::Boundary::bounce(0.9, true, {.left = false, .right = false, .top = false});

  calder::TrajectoryWriter out(std::cout);
  out.write(0, world);
  for (int frame = 1; frame <= 600; ++frame) {
    for (calder::Mover& mover : movers) {
      if (liquid.contains(mover.position())) {
        mover.apply_force(liquid.calculate_drag(mover.velocity()));
      }
      const calder::Vec2 gravity{0, 0.1 * mover.mass()};  // scaled by mass
      mover.apply_force(gravity);
      mover.update();
      mover.check_edges(floor_only);
    }
    out.write(frame, world);
  }
}
