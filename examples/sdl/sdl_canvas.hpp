// SPDX-License-Identifier: MIT
// The little SDL2 drawing layer of the "draw it yourself" examples: a
// window, filled circles with an outline (triangle fans for
// SDL_RenderGeometry), filled rectangles, and the --frames N --screenshot
// out.bmp option, under which the last frame is saved as a 24-bit BMP and
// every shape of it is printed ("circle X Y R r g b" and "rect X Y W H r g b",
// pixels rounded, the fill colour) for a test to check the pixels against.
#pragma once

#include <SDL.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

namespace sdl_canvas {

struct Options {
  long frames = -1;  // -1: until the window closes
  std::string screenshot;
};

// Reads --frames N and --screenshot FILE; exits with status 2 and a
// one-line message on anything else.
inline Options parse_options(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--frames" && i + 1 < argc) {
      char* end = nullptr;
      options.frames = std::strtol(argv[++i], &end, 10);
      if (*end != '\0' || options.frames < 1 || options.frames > 1000000) {
        std::fprintf(stderr, "%s: --frames needs 1..1000000 (got '%s')\n", argv[0], argv[i]);
        std::exit(2);
      }
    } else if (arg == "--screenshot" && i + 1 < argc) {
      options.screenshot = argv[++i];
    } else {
      std::fprintf(stderr, "usage: %s [--frames N] [--screenshot out.bmp]\n", argv[0]);
      std::exit(2);
    }
  }
  if (!options.screenshot.empty() && options.frames < 0) {
    std::fprintf(stderr, "%s: --screenshot needs --frames\n", argv[0]);
    std::exit(2);
  }
  return options;
}

class Window {
 public:
  Window(const char* title, int width, int height, Options options)
      : width_(width), height_(height), options_(std::move(options)) {
    if (SDL_Init(SDL_INIT_VIDEO) != 0) fail("SDL_Init");
    window_ =
        SDL_CreateWindow(title, SDL_WINDOWPOS_UNDEFINED, SDL_WINDOWPOS_UNDEFINED, width, height, 0);
    if (window_ == nullptr) fail("SDL_CreateWindow");
    renderer_ = SDL_CreateRenderer(window_, -1, 0);
    if (renderer_ == nullptr) fail("SDL_CreateRenderer");
  }
  ~Window() {
    if (renderer_ != nullptr) SDL_DestroyRenderer(renderer_);
    if (window_ != nullptr) SDL_DestroyWindow(window_);
    SDL_Quit();
  }
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  // Starts frame `frame` (1, 2, ...); false once the window is closed or the
  // frames asked for are done.
  bool next_frame(long frame) {
    SDL_Event event;
    while (SDL_PollEvent(&event)) {
      if (event.type == SDL_QUIT) return false;
    }
    if (options_.frames >= 0 && frame > options_.frames) return false;
    capturing_ = frame == options_.frames && !options_.screenshot.empty();
    vertices_.clear();
    SDL_SetRenderDrawColor(renderer_, 255, 255, 255, 255);
    SDL_RenderClear(renderer_);
    return true;
  }

  // A disc of radius r in `fill` inside a black outline `outline` pixels wide.
  void circle(double x, double y, double r, double outline, SDL_Color fill) {
    disc(x, y, r + outline / 2, SDL_Color{0, 0, 0, 255});
    disc(x, y, r - outline / 2, fill);
    if (capturing_) {
      std::printf("circle %ld %ld %ld %d %d %d\n", std::lround(x), std::lround(y), std::lround(r),
                  fill.r, fill.g, fill.b);
    }
  }

  void rect(double x, double y, double w, double h, SDL_Color fill) {
    flush();  // keep the drawing order
    const SDL_FRect r{static_cast<float>(x), static_cast<float>(y), static_cast<float>(w),
                      static_cast<float>(h)};
    SDL_SetRenderDrawColor(renderer_, fill.r, fill.g, fill.b, fill.a);
    SDL_RenderFillRectF(renderer_, &r);
    if (capturing_) {
      std::printf("rect %ld %ld %ld %ld %d %d %d\n", std::lround(x), std::lround(y), std::lround(w),
                  std::lround(h), fill.r, fill.g, fill.b);
    }
  }

  // Draws what is queued, saves the screenshot on its frame, and shows it.
  void end_frame() {
    flush();
    if (capturing_) save_screenshot();
    SDL_RenderPresent(renderer_);
    if (options_.frames < 0) SDL_Delay(16);  // about 60 frames a second on screen
  }

 private:
  [[noreturn]] static void fail(const char* what) {
    std::fprintf(stderr, "sdl_canvas: %s: %s\n", what, SDL_GetError());
    std::exit(1);
  }

  // A filled disc as a fan of triangles, queued for one SDL_RenderGeometry.
  void disc(double x, double y, double r, SDL_Color color) {
    constexpr int kSegments = 48;
    const double step = 2.0 * M_PI / kSegments;
    auto vertex = [&](double vx, double vy) {
      vertices_.push_back({{static_cast<float>(vx), static_cast<float>(vy)}, color, {0, 0}});
    };
    for (int k = 0; k < kSegments; ++k) {
      vertex(x, y);
      vertex(x + r * std::cos(k * step), y + r * std::sin(k * step));
      vertex(x + r * std::cos((k + 1) * step), y + r * std::sin((k + 1) * step));
    }
  }

  void flush() {
    if (vertices_.empty()) return;
    if (SDL_RenderGeometry(renderer_, nullptr, vertices_.data(), static_cast<int>(vertices_.size()),
                           nullptr, 0) != 0) {
      fail("SDL_RenderGeometry");
    }
    vertices_.clear();
  }

  // Reads the frame back before it is presented (the back buffer holds it).
  void save_screenshot() {
    std::vector<unsigned char> pixels(static_cast<std::size_t>(width_ * height_ * 3));
    if (SDL_RenderReadPixels(renderer_, nullptr, SDL_PIXELFORMAT_BGR24, pixels.data(),
                             width_ * 3) != 0) {
      fail("SDL_RenderReadPixels");
    }
    SDL_Surface* surface = SDL_CreateRGBSurfaceWithFormatFrom(pixels.data(), width_, height_, 24,
                                                              width_ * 3, SDL_PIXELFORMAT_BGR24);
    if (surface == nullptr || SDL_SaveBMP(surface, options_.screenshot.c_str()) != 0) {
      fail("cannot save the screenshot");
    }
    SDL_FreeSurface(surface);
  }

  int width_;
  int height_;
  Options options_;
  SDL_Window* window_ = nullptr;
  SDL_Renderer* renderer_ = nullptr;
  std::vector<SDL_Vertex> vertices_;
  bool capturing_ = false;
};

}  // namespace sdl_canvas
