// SPDX-License-Identifier: MIT
// Draw it yourself, with a liquid: example 2.5's nine movers falling into
// water, as a World with fields (Liquid, Gravity scaled by mass, a floor to
// bounce on) drawn with SDL2 from the world's arrays and the liquid's
// rectangle. No scene and no Cairo; sdl_canvas.hpp holds the SDL part.
//
//   draw_it_yourself_liquid [--frames N --screenshot out.bmp]
#include <calder/calder.hpp>

#include "sdl_canvas.hpp"

int main(int argc, char** argv) {
  const sdl_canvas::Options options = sdl_canvas::parse_options(argc, argv);

  calder::World world({.width = 640,
                       .height = 240,
                       .boundary = calder::Boundary::bounce(
                           0.9, true, {.left = false, .right = false, .top = false}),
                       .seed = 1});
  for (int i = 0; i < 9; ++i) {
    const double mass = world.random().random(0.5, 3);
    world.add_body({.position = {40.0 + i * 70.0, 0}, .mass = mass, .radius = mass * 8});
  }
  const calder::Liquid& liquid = world.add(calder::Liquid{.region = {0, 120, 640, 120}, .c = 0.1});
  world.add(calder::Gravity{.g = {0, 0.1}, .scale_by_mass = true});

  sdl_canvas::Window window("calder: draw it yourself, with a liquid", 640, 240, options);
  for (long frame = 1; window.next_frame(frame); ++frame) {
    world.step();
    const calder::Rect& water = liquid.region;
    window.rect(water.x, water.y, water.w, water.h, {200, 200, 200, 255});
    const calder::BodyView bodies = world.bodies();
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      window.circle(bodies.x[i], bodies.y[i], bodies.radius[i], 2, {127, 127, 127, 255});
    }
    window.end_frame();
  }
}
