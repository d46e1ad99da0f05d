// SPDX-License-Identifier: MIT
// calder::sketch's window (SDL2): the one window loop, event handling and
// frame timer of calder. The canvas is drawn by Cairo and shown as a texture.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <string>

#define SDL_MAIN_HANDLED
#include <SDL.h>

#include "calder/error.hpp"
#include "calder/fixed_step.hpp"
#include "runner.hpp"

namespace calder {

namespace {

constexpr int kMaxDrawsPerFrame = 16;  // catching up after a slow frame; more is dropped

bool env_set(const char* name) {
  const char* value = std::getenv(name);
  return value != nullptr && *value != '\0';
}

std::string sdl_error() {
  const char* error = SDL_GetError();
  return (error != nullptr && *error != '\0') ? std::string(error) : std::string("unknown error");
}

struct SdlVideo {
  SdlVideo() = default;
  ~SdlVideo() { SDL_Quit(); }
  SdlVideo(const SdlVideo&) = delete;
  SdlVideo& operator=(const SdlVideo&) = delete;
};
struct DestroyWindow {
  void operator()(SDL_Window* w) const { SDL_DestroyWindow(w); }
};
struct DestroyRenderer {
  void operator()(SDL_Renderer* r) const { SDL_DestroyRenderer(r); }
};
struct DestroyTexture {
  void operator()(SDL_Texture* t) const { SDL_DestroyTexture(t); }
};

// p5's `key` for a key press: the character, or the key's name.
std::string key_name(const SDL_Keysym& sym) {
  switch (sym.sym) {
    case SDLK_RETURN:
    case SDLK_KP_ENTER:
      return "Enter";
    case SDLK_ESCAPE:
      return "Escape";
    case SDLK_BACKSPACE:
      return "Backspace";
    case SDLK_TAB:
      return "Tab";
    case SDLK_DELETE:
      return "Delete";
    case SDLK_LEFT:
      return "ArrowLeft";
    case SDLK_RIGHT:
      return "ArrowRight";
    case SDLK_UP:
      return "ArrowUp";
    case SDLK_DOWN:
      return "ArrowDown";
    case SDLK_KP_PLUS:
      return "+";
    case SDLK_KP_MINUS:
      return "-";
    case SDLK_KP_PERIOD:
      return ".";
    default:
      break;
  }
  if (sym.sym >= 32 && sym.sym < 127) {
    char c = static_cast<char>(sym.sym);
    const bool shift = (sym.mod & KMOD_SHIFT) != 0;
    if (shift && c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
    if (shift && c == '=') c = '+';
    return std::string(1, c);
  }
  const char* name = SDL_GetKeyName(sym.sym);
  return name != nullptr ? name : "";
}

class Window {
 public:
  explicit Window(SketchRunner& runner) : runner_(runner) {}

  void run() {
    init();
    runner_.open_window = [this](int width, int height) { return open(width, height); };
    runner_.setup();
    runner_.open_window = nullptr;
    texture_.reset(SDL_CreateTexture(renderer_.get(), SDL_PIXELFORMAT_ARGB8888,
                                     SDL_TEXTUREACCESS_STREAMING, runner_.canvas().pixel_width(),
                                     runner_.canvas().pixel_height()));
    if (!texture_) throw RunError("cannot create an SDL texture: " + sdl_error());
    SDL_SetTextureBlendMode(texture_.get(), SDL_BLENDMODE_NONE);
    loop();
    runner_.finish();
  }

 private:
  void init() {
    const std::string reason = sketch_no_display_reason();
    if (!reason.empty()) throw InputError(reason);
    if (!env_set("SDL_VIDEODRIVER")) {
      SDL_SetHint(SDL_HINT_VIDEODRIVER, env_set("WAYLAND_DISPLAY") ? "wayland,x11" : "x11");
    }
    SDL_SetHint(SDL_HINT_MOUSE_FOCUS_CLICKTHROUGH, "1");
    SDL_SetHint(SDL_HINT_VIDEO_X11_NET_WM_BYPASS_COMPOSITOR, "0");
    if (SDL_Init(SDL_INIT_VIDEO) != 0) {
      const std::string reason_sdl = sdl_error();
      SDL_Quit();
      throw InputError("no display: " + reason_sdl);
    }
    video_ = std::make_unique<SdlVideo>();
    // With DISPLAY set but no server behind it, SDL falls back to a driver
    // that shows nothing: only for who asks for it by SDL_VIDEODRIVER.
    const char* driver = SDL_GetCurrentVideoDriver();
    const std::string driver_name = driver != nullptr ? driver : "";
    if (!env_set("SDL_VIDEODRIVER") && driver_name != "x11" && driver_name != "wayland") {
      const char* display = std::getenv("DISPLAY");
      throw InputError("no display: cannot connect to DISPLAY '" +
                       detail::printable(display != nullptr ? display : "") +
                       "' (SDL found only its '" + driver_name + "' driver)");
    }
  }

  // Opens the window for a canvas of width x height; returns the display's
  // pixels per window point.
  double open(int width, int height) {
    const double scale = runner_.options().scale;
    const int w = std::max(1, static_cast<int>(std::lround(width * scale)));
    const int h = std::max(1, static_cast<int>(std::lround(height * scale)));
    window_.reset(SDL_CreateWindow(runner_.title().c_str(), SDL_WINDOWPOS_CENTERED,
                                   SDL_WINDOWPOS_CENTERED, w, h,
                                   SDL_WINDOW_SHOWN | SDL_WINDOW_ALLOW_HIGHDPI));
    if (!window_) throw InputError("no display: cannot open a window: " + sdl_error());
    shown_title_ = runner_.title();
    renderer_.reset(SDL_CreateRenderer(window_.get(), -1,
                                       SDL_RENDERER_ACCELERATED | SDL_RENDERER_PRESENTVSYNC));
    if (!renderer_) renderer_.reset(SDL_CreateRenderer(window_.get(), -1, SDL_RENDERER_SOFTWARE));
    if (!renderer_) throw RunError("cannot create an SDL renderer: " + sdl_error());
    SDL_RendererInfo info{};
    if (SDL_GetRendererInfo(renderer_.get(), &info) == 0) {
      vsync_ = (info.flags & SDL_RENDERER_PRESENTVSYNC) != 0;
    }
    SDL_DisplayMode mode{};
    if (SDL_GetWindowDisplayMode(window_.get(), &mode) == 0 && mode.refresh_rate > 0) {
      refresh_rate_ = mode.refresh_rate;
    }
    int pixels_w = w;
    int pixels_h = h;
    if (SDL_GetRendererOutputSize(renderer_.get(), &pixels_w, &pixels_h) != 0) pixels_w = w;
    points_per_canvas_pixel_ = scale;
    return pixels_w > 0 ? static_cast<double>(pixels_w) / w : 1.0;
  }

  void loop() {
    const double frequency = static_cast<double>(SDL_GetPerformanceFrequency());
    const Uint64 start = SDL_GetPerformanceCounter();
    Uint64 last = start;
    FixedStep pacer(runner_.frame_rate(), kMaxDrawsPerFrame);
    bool running = !runner_.finished();
    bool shown = false;  // the texture shows the canvas
    while (running) {
      if (runner_.options().poll) runner_.options().poll();
      SDL_Event event;
      while (SDL_PollEvent(&event) != 0) {
        if (event.type == SDL_QUIT) running = false;
        if (event.type == SDL_WINDOWEVENT && event.window.event == SDL_WINDOWEVENT_EXPOSED) {
          shown = false;
        }
        // An event function may draw on the canvas (a key that redraws).
        if (handle(event)) shown = false;
      }
      const Uint64 now = SDL_GetPerformanceCounter();
      const double elapsed = std::min(static_cast<double>(now - last) / frequency, 0.25);
      last = now;
      const auto& exit_after = runner_.options().exit_after_seconds;
      if (exit_after && static_cast<double>(now - start) / frequency >= *exit_after) {
        running = false;
      }
      if (pacer.steps_per_second() != runner_.frame_rate()) {
        pacer.set_steps_per_second(runner_.frame_rate());
      }
      if (running) {
        pacer.advance(elapsed, [&] {
          if (!runner_.wants_draw()) return;
          runner_.draw_frame();
          shown = false;
        });
        // A redraw() asked between frames (a key while paused) is drawn now.
        if (!runner_.looping() && runner_.wants_draw()) {
          runner_.draw_frame();
          shown = false;
        }
      }
      if (runner_.finished()) running = false;
      if (runner_.title() != shown_title_) {
        SDL_SetWindowTitle(window_.get(), runner_.title().c_str());
        shown_title_ = runner_.title();
      }
      if (!shown) {
        const Canvas& canvas = runner_.canvas();
        SDL_UpdateTexture(texture_.get(), nullptr, canvas.argb32_data(), canvas.stride());
        shown = true;
      }
      SDL_RenderClear(renderer_.get());
      SDL_RenderCopy(renderer_.get(), texture_.get(), nullptr, nullptr);
      SDL_RenderPresent(renderer_.get());
      const bool hidden =
          (SDL_GetWindowFlags(window_.get()) & (SDL_WINDOW_MINIMIZED | SDL_WINDOW_HIDDEN)) != 0;
      if (!vsync_ || hidden) {
        // No vsync to wait for: wait out the rest of a display frame.
        const double spent = static_cast<double>(SDL_GetPerformanceCounter() - now) / frequency;
        const double wait = 1.0 / refresh_rate_ - spent;
        if (wait > 0.0) SDL_Delay(static_cast<Uint32>(wait * 1000.0));
      }
    }
  }

  // Hands an event to the sketch; true when one of its functions ran.
  bool handle(const SDL_Event& event) {
    const double s = points_per_canvas_pixel_;
    switch (event.type) {
      case SDL_KEYDOWN:
        runner_.key_down(key_name(event.key.keysym), event.key.repeat != 0);
        return true;
      case SDL_MOUSEMOTION:
        runner_.mouse_moved(event.motion.x / s, event.motion.y / s);
        return true;
      case SDL_MOUSEBUTTONDOWN:
        if (event.button.button != SDL_BUTTON_LEFT) return false;
        runner_.mouse_down(event.button.x / s, event.button.y / s);
        return true;
      case SDL_MOUSEBUTTONUP:
        if (event.button.button != SDL_BUTTON_LEFT) return false;
        runner_.mouse_up(event.button.x / s, event.button.y / s);
        return true;
      default:
        return false;
    }
  }

  SketchRunner& runner_;
  std::unique_ptr<SdlVideo> video_;
  std::unique_ptr<SDL_Window, DestroyWindow> window_;
  std::unique_ptr<SDL_Renderer, DestroyRenderer> renderer_;
  std::unique_ptr<SDL_Texture, DestroyTexture> texture_;
  std::string shown_title_;
  bool vsync_ = false;
  int refresh_rate_ = 60;
  double points_per_canvas_pixel_ = 1.0;
};

}  // namespace

std::string sketch_no_display_reason() {
  if (!env_set("SDL_VIDEODRIVER") && !env_set("DISPLAY") && !env_set("WAYLAND_DISPLAY")) {
    return "no display: neither DISPLAY nor WAYLAND_DISPLAY is set";
  }
  return "";
}

bool sketch_has_window() { return true; }

void run_sketch_window(SketchRunner& runner) {
  Window window(runner);
  window.run();
}

}  // namespace calder
