// SPDX-License-Identifier: MIT
// Example 2.7: Attraction with Many Movers. Ten movers of random mass at
// random places, all started to the right at speed 1, fall around one
// attractor (mass 20, G = 1, d clamped to [5, 25]).
// Prints the trajectory as CSV: frame,body,x,y,vx,vy.
//
//   example_2_7_attraction_with_many_movers [seed]   (default 1; same bits as
//                                   `calder run example-2.7 --seed <seed>`)
#include <calder/calder.hpp>
#include <cstdlib>
#include <iostream>
#include <vector>

int main(int argc, char** argv) {
  const auto seed = static_cast<std::uint32_t>(argc > 1 ? std::strtoul(argv[1], nullptr, 10) : 1);
  calder::World world({.width = 640, .height = 240, .seed = seed});
  calder::Random& random = world.random();
  std::vector<calder::Mover> movers;
  for (int i = 0; i < 10; ++i) {
    // new Mover(random(width), random(height), random(0.5, 3)): drawn in that order.
    const double x = random.random(640);
    const double y = random.random(240);
    const double mass = random.random(0.5, 3);
    movers.push_back(world.add_mover(
        {.position = {x, y}, .velocity = {1, 0}, .mass = mass, .radius = mass * 8}));
  }
  const calder::Attractor attractor{
      .position = {320, 120},
      .mass = 20,
      .law = calder::AttractionLaw::book(1, 5, 25, calder::MassProduct::left_to_right)};

  calder::TrajectoryWriter out(std::cout);
  out.write(0, world);
  for (int frame = 1; frame <= 600; ++frame) {
    for (calder::Mover& mover : movers) {
      const calder::Vec2 force = attractor.attract(mover.position(), mover.mass());
      mover.apply_force(force);
      mover.update();
    }
    out.write(frame, world);
  }
}
