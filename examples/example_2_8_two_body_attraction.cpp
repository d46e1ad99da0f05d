// SPDX-License-Identifier: MIT
// Example 2.8: Two-Body Attraction. Two bodies of equal mass attract each
// other (G = 1, distance clamped to [5, 25]) and, starting with opposite
// velocities, orbit their common centre.
// Prints the trajectory as CSV: frame,body,x,y,vx,vy.
#include <calder/calder.hpp>
#include <iostream>

int main() {
  calder::World world({.width = 640, .height = 240});
  calder::Mover body_a = world.add_mover({.position = {320, 40}, .velocity = {1, 0}, .mass = 8});
  calder::Mover body_b = world.add_mover({.position = {320, 200}, .velocity = {-1, 0}, .mass = 8});
  // This sketch multiplies the masses first: G * (mA * mB) / (d * d).
  const calder::AttractionLaw law =
      calder::AttractionLaw::book(1, 5, 25, calder::MassProduct::masses_first);

  calder::TrajectoryWriter out(std::cout);
  out.write(0, world);
  for (int frame = 1; frame <= 600; ++frame) {
    // Both forces come from the positions before this frame's updates.
    const calder::Vec2 force_on_b = body_a.attract(body_b, law);
    const calder::Vec2 force_on_a = body_b.attract(body_a, law);
    body_b.apply_force(force_on_b);
    body_a.apply_force(force_on_a);
    body_a.update();
    body_b.update();

    out.write(frame, world);
  }
}
