// SPDX-License-Identifier: MIT
// Draw it yourself: example 2.7's world (ten movers around an attractor)
// built with calder's API and drawn straight from the world's arrays with
// SDL2 (SDL_RenderGeometry triangles), no scene and no Cairo. calder steps
// the physics; everything on screen is this file's.
//
//   draw_it_yourself                                  a window, until closed
//   draw_it_yourself --frames N --screenshot out.bmp  N frames, then the last
//                       one saved as a 24-bit BMP, and the bodies printed as
//                       "body X Y R" lines (pixels, rounded), the attractor as
//                       "attractor X Y R"; runs under SDL_VIDEODRIVER=dummy
#include <SDL.h>

#include <calder/calder.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace {

constexpr int kWidth = 640;
constexpr int kHeight = 240;

// A filled disc as a fan of triangles, appended to a vertex list.
void add_disc(std::vector<SDL_Vertex>& vertices, double x, double y, double r, SDL_Color color) {
  constexpr int kSegments = 48;
  const double step = 2.0 * M_PI / kSegments;
  for (int k = 0; k < kSegments; ++k) {
    const double a = k * step;
    const double b = (k + 1) * step;
    vertices.push_back({{static_cast<float>(x), static_cast<float>(y)}, color, {0, 0}});
    vertices.push_back(
        {{static_cast<float>(x + r * std::cos(a)), static_cast<float>(y + r * std::sin(a))},
         color,
         {0, 0}});
    vertices.push_back(
        {{static_cast<float>(x + r * std::cos(b)), static_cast<float>(y + r * std::sin(b))},
         color,
         {0, 0}});
  }
}

// A circle with an outline: a black disc, then the fill inside it.
void add_circle(std::vector<SDL_Vertex>& vertices, double x, double y, double r, double outline,
                SDL_Color fill) {
  add_disc(vertices, x, y, r + outline / 2, SDL_Color{0, 0, 0, 255});
  add_disc(vertices, x, y, r - outline / 2, fill);
}

int fail(const char* what) {
  std::fprintf(stderr, "draw_it_yourself: %s: %s\n", what, SDL_GetError());
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  long frames = -1;  // -1: until the window closes
  std::string screenshot;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--frames" && i + 1 < argc) {
      char* end = nullptr;
      frames = std::strtol(argv[++i], &end, 10);
      if (*end != '\0' || frames < 1 || frames > 1000000) {
        std::fprintf(stderr, "draw_it_yourself: --frames needs 1..1000000 (got '%s')\n", argv[i]);
        return 2;
      }
    } else if (arg == "--screenshot" && i + 1 < argc) {
      screenshot = argv[++i];
    } else {
      std::fprintf(stderr, "usage: draw_it_yourself [--frames N] [--screenshot out.bmp]\n");
      return 2;
    }
  }
  if (!screenshot.empty() && frames < 0) {
    std::fprintf(stderr, "draw_it_yourself: --screenshot needs --frames\n");
    return 2;
  }

  // The world: as example 2.7, seed 1.
  calder::World world({.width = kWidth, .height = kHeight, .seed = 1});
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

  if (SDL_Init(SDL_INIT_VIDEO) != 0) return fail("SDL_Init");
  SDL_Window* window = SDL_CreateWindow("calder: draw it yourself", SDL_WINDOWPOS_UNDEFINED,
                                        SDL_WINDOWPOS_UNDEFINED, kWidth, kHeight, 0);
  if (window == nullptr) return fail("SDL_CreateWindow");
  SDL_Renderer* renderer = SDL_CreateRenderer(window, -1, 0);
  if (renderer == nullptr) return fail("SDL_CreateRenderer");

  std::vector<SDL_Vertex> vertices;
  bool running = true;
  for (long frame = 1; running && (frames < 0 || frame <= frames); ++frame) {
    SDL_Event event;
    while (SDL_PollEvent(&event)) {
      if (event.type == SDL_QUIT) running = false;
    }
    world.step();

    // Draw from the arrays: positions, radii (BodyView), the attractor's field.
    const calder::BodyView bodies = world.bodies();
    vertices.clear();
    add_circle(vertices, attractor.position.x, attractor.position.y, attractor.mass, 4,
               SDL_Color{175, 175, 175, 255});
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      add_circle(vertices, bodies.x[i], bodies.y[i], bodies.radius[i], 2,
                 SDL_Color{127, 127, 127, 255});
    }
    SDL_SetRenderDrawColor(renderer, 255, 255, 255, 255);
    SDL_RenderClear(renderer);
    if (SDL_RenderGeometry(renderer, nullptr, vertices.data(), static_cast<int>(vertices.size()),
                           nullptr, 0) != 0) {
      return fail("SDL_RenderGeometry");
    }
    if (frame == frames && !screenshot.empty()) {
      // Read back before presenting: the back buffer holds this frame.
      std::vector<unsigned char> pixels(static_cast<std::size_t>(kWidth) * kHeight * 3);
      if (SDL_RenderReadPixels(renderer, nullptr, SDL_PIXELFORMAT_BGR24, pixels.data(),
                               kWidth * 3) != 0) {
        return fail("SDL_RenderReadPixels");
      }
      SDL_Surface* surface = SDL_CreateRGBSurfaceWithFormatFrom(pixels.data(), kWidth, kHeight, 24,
                                                                kWidth * 3, SDL_PIXELFORMAT_BGR24);
      if (surface == nullptr || SDL_SaveBMP(surface, screenshot.c_str()) != 0) {
        return fail("cannot save the screenshot");
      }
      SDL_FreeSurface(surface);
      std::printf("attractor %ld %ld %ld\n", std::lround(attractor.position.x),
                  std::lround(attractor.position.y), std::lround(attractor.mass));
      for (std::size_t i = 0; i < bodies.size(); ++i) {
        std::printf("body %ld %ld %ld\n", std::lround(bodies.x[i]), std::lround(bodies.y[i]),
                    std::lround(bodies.radius[i]));
      }
    }
    SDL_RenderPresent(renderer);
    if (frames < 0) SDL_Delay(16);  // about 60 frames a second on screen
  }
  SDL_DestroyRenderer(renderer);
  SDL_DestroyWindow(window);
  SDL_Quit();
  return 0;
}
