// SPDX-License-Identifier: MIT
// Draw it yourself: example 2.7's world (ten movers around an attractor)
// built with calder's API and drawn straight from the world's arrays with
// SDL2 (sdl_canvas.hpp: SDL_RenderGeometry triangles), no scene and no Cairo.
// calder steps the physics; everything on screen is this file's.
//
//   draw_it_yourself                                  a window, until closed
//   draw_it_yourself --frames N --screenshot out.bmp  N frames, the last one
//                       saved as a BMP and its circles printed (the ctest runs
//                       this under SDL_VIDEODRIVER=dummy and checks the pixels)
#include <calder/calder.hpp>

#include "sdl_canvas.hpp"

int main(int argc, char** argv) {
  const sdl_canvas::Options options = sdl_canvas::parse_options(argc, argv);

  // The world: as example 2.7, seed 1.
  calder::World world({.width = 640, .height = 240, .seed = 1});
  calder::Random& random = world.random();
  for (int i = 0; i < 10; ++i) {
    const double x = random.random(640);
    const double y = random.random(240);
    const double mass = random.random(0.5, 3);
    world.add_body({.position = {x, y}, .velocity = {1, 0}, .mass = mass, .radius = mass * 8});
  }
  const calder::Attractor& attractor = world.add(calder::Attractor{
      .position = {320, 120},
      .mass = 20,
      .law = calder::AttractionLaw::book(1, 5, 25, calder::MassProduct::left_to_right)});

  sdl_canvas::Window window("calder: draw it yourself", 640, 240, options);
  for (long frame = 1; window.next_frame(frame); ++frame) {
    world.step();
    // Draw from the arrays: the attractor (diameter 2 * mass), then the bodies.
    window.circle(attractor.position.x, attractor.position.y, attractor.mass, 4,
                  {175, 175, 175, 255});
    const calder::BodyView bodies = world.bodies();
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      window.circle(bodies.x[i], bodies.y[i], bodies.radius[i], 2, {127, 127, 127, 255});
    }
    window.end_frame();
  }
}
