// SPDX-License-Identifier: MIT
// Example 2.9: n Bodies. Ten bodies of random mass at random places attract
// one another (G = 1, d clamped to [5, 25]). As in the book, body i moves
// right after its forces are summed, so the bodies after it feel it moved.
// Prints the trajectory as CSV: frame,body,x,y,vx,vy.
//
//   example_2_9_n_bodies [seed]   (default 1; same bits as
//                                  `calder run example-2.9 --seed <seed>`)
#include <calder/calder.hpp>
#include <cstdlib>
#include <iostream>
#include <vector>

int main(int argc, char** argv) {
  const auto seed = static_cast<std::uint32_t>(argc > 1 ? std::strtoul(argv[1], nullptr, 10) : 1);
  calder::World world({.width = 640, .height = 240, .seed = seed});
  calder::Random& random = world.random();
  std::vector<calder::Mover> bodies;
  for (int i = 0; i < 10; ++i) {
    const double x = random.random(640);
    const double y = random.random(240);
    const double mass = random.random(0.1, 2);
    bodies.push_back(world.add_mover({.position = {x, y}, .mass = mass, .radius = mass * 8}));
  }
  const calder::AttractionLaw law =
      calder::AttractionLaw::book(1, 5, 25, calder::MassProduct::left_to_right);

  calder::TrajectoryWriter out(std::cout);
  out.write(0, world);
  for (int frame = 1; frame <= 600; ++frame) {
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      for (std::size_t j = 0; j < bodies.size(); ++j) {
        if (i != j) bodies[i].apply_force(bodies[j].attract(bodies[i], law));
      }
      bodies[i].update();
    }
    out.write(frame, world);
  }
}
