// SPDX-License-Identifier: MIT
// Example 2.3: Gravity Scaled by Mass. Gravity is a force proportional to
// mass, so the heavy and the light mover now fall together; wind (not scaled)
// still moves the light one more. Edges count the radius (mass * 8).
// Prints the trajectory as CSV: frame,body,x,y,vx,vy.
#include <calder/calder.hpp>
#include <iostream>

int main() {
  calder::World world({.width = 640, .height = 240});
  calder::Mover mover_a = world.add_mover({.position = {200, 30}, .mass = 10, .radius = 10 * 8});
  calder::Mover mover_b = world.add_mover({.position = {440, 30}, .mass = 2, .radius = 2 * 8});
  const calder::Boundary edges = calder::Boundary::bounce(1.0, true, {.top = false});

  calder::TrajectoryWriter out(std::cout);
  out.write(0, world);
  for (int frame = 1; frame <= 600; ++frame) {
    const bool mouse_is_pressed = frame >= 100 && frame <= 160;

    const calder::Vec2 gravity{0, 0.1};
    mover_a.apply_force(calder::gravity(gravity, mover_a.mass(), true));  // gravity * mass
    mover_b.apply_force(calder::gravity(gravity, mover_b.mass(), true));
    if (mouse_is_pressed) {
      const calder::Vec2 wind{0.1, 0};
      mover_a.apply_force(wind);
      mover_b.apply_force(wind);
    }
    mover_a.update();
    mover_a.check_edges(edges);
    mover_b.update();
    mover_b.check_edges(edges);

    out.write(frame, world);
  }
}
