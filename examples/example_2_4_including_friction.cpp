// SPDX-License-Identifier: MIT
// Example 2.4: Including Friction. A mover falls, bounces with 90% of its
// speed, and slides along the floor; while it touches the floor, friction
// (-mu v-hat, mu = 0.1) slows it down.
// Prints the trajectory as CSV: frame,body,x,y,vx,vy.
#include <calder/calder.hpp>
#include <iostream>

int main() {
  calder::World world({.width = 640, .height = 240});
  calder::Mover mover = world.add_mover({.position = {320, 30}, .mass = 5, .radius = 40});
  const calder::Boundary bounce_edges = calder::Boundary::bounce(0.9, true, {.top = false});

  calder::TrajectoryWriter out(std::cout);
  out.write(0, world);
  for (int frame = 1; frame <= 600; ++frame) {
    const bool mouse_is_pressed = frame >= 100 && frame <= 160;

    const calder::Vec2 gravity{0, 1};
    mover.apply_force(gravity);
    if (mouse_is_pressed) {
      const calder::Vec2 wind{0.5, 0};
      mover.apply_force(wind);
    }
    if (mover.contact_edge()) {
      const double c = 0.1;
      mover.apply_force(calder::friction(mover.velocity(), c));
    }
    mover.check_edges(bounce_edges);  // the book bounces before the update
    mover.update();

    out.write(frame, world);
  }
}
