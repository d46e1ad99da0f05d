// SPDX-License-Identifier: MIT
// Example 2.6: Attraction. A fixed attractor of mass 20 pulls a mover of
// mass 2 with G * M * m / d^2 (G = 1, d clamped to [5, 25]); the mover,
// started sideways, swings around it.
// Prints the trajectory as CSV: frame,body,x,y,vx,vy
// (same bits as `calder run example-2.6`).
#include <calder/calder.hpp>
#include <iostream>

int main() {
  calder::World world({.width = 640, .height = 240});
  calder::Mover mover =
      world.add_mover({.position = {300, 50}, .velocity = {1, 0}, .mass = 2, .radius = 16});
  // The attractor is not a moving body: it only exerts a force.
  const calder::Attractor attractor{
      .position = {320, 120},
      .mass = 20,
      .law = calder::AttractionLaw::book(1, 5, 25, calder::MassProduct::left_to_right)};

  calder::TrajectoryWriter out(std::cout);
  out.write(0, world);
  for (int frame = 1; frame <= 600; ++frame) {
    const calder::Vec2 force = attractor.attract(mover.position(), mover.mass());
    mover.apply_force(force);
    mover.update();
    out.write(frame, world);
  }
}
