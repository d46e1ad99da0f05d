// SPDX-License-Identifier: MIT
// Example 2.1: Forces. A mover falls under gravity; while the mouse is held
// down (here: frames 100 to 160, as in the p5.js reference run), wind pushes
// it right. It bounces off the left, right and bottom edges.
// Prints the trajectory as CSV: frame,body,x,y,vx,vy.
#include <calder/calder.hpp>
#include <iostream>

int main() {
  calder::World world({.width = 640, .height = 240});
  calder::Mover mover = world.add_mover({.position = {320, 30}, .mass = 1});
  const calder::Boundary edges = calder::Boundary::bounce(1.0, false, {.top = false});

  calder::TrajectoryWriter out(std::cout);
  out.write(0, world);
  for (int frame = 1; frame <= 600; ++frame) {
    const bool mouse_is_pressed = frame >= 100 && frame <= 160;

    const calder::Vec2 gravity{0, 0.1};
    mover.apply_force(gravity);
    if (mouse_is_pressed) {
      const calder::Vec2 wind{0.1, 0};
      mover.apply_force(wind);
    }
    mover.update();
    mover.check_edges(edges);

    out.write(frame, world);
  }
}
