// SPDX-License-Identifier: MIT
#include "window_command.hpp"

#define SDL_MAIN_HANDLED
#include <SDL.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <array>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <memory>
#include <string>
#include <variant>

#include "calder/diagnostics.hpp"
#include "calder/error.hpp"
#include "calder/fixed_step.hpp"
#include "calder/render.hpp"
#include "calder/trajectory.hpp"
#include "calder/world.hpp"
#include "errors.hpp"
#include "output_policy.hpp"
#include "parse.hpp"
#include "progress.hpp"
#include "snapshot_io.hpp"

namespace calder::app {

namespace {

constexpr double kStepsPerSecond = 60.0;  // the sketches' frame rate, at speed 1
constexpr int kMaxStepsPerFrame = 16;     // speed 8 on a 30 Hz display; more is dropped
constexpr double kGifFps = 30.0;          // a GIF frame every other step at speed 1
constexpr std::int64_t kGifEvery = 2;
constexpr int kMaxGifFrames = 10'000;
constexpr double kMaxExitAfterSeconds = 1e6;

std::string quoted(const std::string& text) { return "'" + text + "'"; }

double parse_speed(const std::string& text) {
  const std::optional<double> value = to_double(text);
  if (!value || !(*value >= min_speed && *value <= max_speed)) {
    throw InputError("--speed: expected a number from 0.125 to 8, got " + quoted(text));
  }
  return *value;
}

double parse_seconds(const std::string& text) {
  const std::optional<double> value = to_double(text);
  if (!value || !(*value > 0.0 && *value <= kMaxExitAfterSeconds)) {
    throw InputError("--exit-after-seconds: expected a number > 0 and <= 1000000, got " +
                     quoted(text));
  }
  return *value;
}

std::string sdl_error() {
  const char* error = SDL_GetError();
  return (error != nullptr && *error != '\0') ? std::string(error) : std::string("unknown error");
}

bool env_set(const char* name) {
  const char* value = std::getenv(name);
  return value != nullptr && *value != '\0';
}

std::string timestamp() {
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  std::array<char, 32> text{};
  std::strftime(text.data(), text.size(), "%Y%m%d-%H%M%S", &local);
  return text.data();
}

// SDL's objects, released in the reverse order of creation.
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

// The running window: its state and what the keys do.
class WindowApp {
 public:
  WindowApp(const WindowOptions& options, const PreparedInput& input, std::ostream& out,
            std::ostream& err)
      : options_(options),
        input_(input),
        out_(out),
        err_(err),
        simulation_(start_simulation(input)),
        style_(make_style(input.scene, options.style)),
        size_(canvas_size(std::nullopt, options.scale, input.scene)),
        canvas_(size_.width, size_.height, size_.scale),
        speed_(options.speed ? parse_speed(*options.speed) : 1.0),
        pacer_(kStepsPerSecond * speed_, kMaxStepsPerFrame),
        scripted_(!options.input.mouse_pressed.empty() || options.input.mouse.has_value()) {
    if (options.input.frames) frame_limit_ = input.scene.frames;
    if (options.exit_after_seconds) exit_after_ = parse_seconds(*options.exit_after_seconds);
    if (options.screenshot) check_output_path("--screenshot", *options.screenshot);
  }

  // Until q, Escape, the window's close, --frames or --exit-after-seconds;
  // a terminating signal stops it at the next frame (Interrupted).
  void run(const InterruptGuard& interrupt);

 private:
  void open();
  void handle(const SDL_Event& event);
  void key(const SDL_KeyboardEvent& key);
  void step_once();
  void draw();
  void present();
  void update_title();
  void save_png();
  void toggle_recording();
  void stop_recording();
  void finish();
  [[nodiscard]] bool at_frame_limit() const {
    return frame_limit_ && simulation_.frame() >= *frame_limit_;
  }
  [[nodiscard]] std::string file_stem() const {
    return "calder-" + file_name_part(simulation_.scene().name);
  }
  void note(const std::string& line) {
    out_ << one_line(line) << '\n';
    out_.flush();
  }
  void warn(const std::string& line) {
    err_ << "calder: " << one_line(line) << '\n';
    err_.flush();
  }

  const WindowOptions& options_;
  const PreparedInput& input_;
  std::ostream& out_;
  std::ostream& err_;
  Simulation simulation_;
  RenderStyle style_;
  CanvasSize size_;
  Canvas canvas_;
  double speed_;
  FixedStep pacer_;
  bool scripted_;
  std::optional<std::int64_t> frame_limit_;
  std::optional<double> exit_after_;

  std::unique_ptr<SdlVideo> video_;
  std::unique_ptr<SDL_Window, DestroyWindow> window_;
  std::unique_ptr<SDL_Renderer, DestroyRenderer> renderer_;
  std::unique_ptr<SDL_Texture, DestroyTexture> texture_;
  bool vsync_ = false;
  int refresh_rate_ = 60;

  bool running_ = true;
  bool paused_ = false;
  bool canvas_current_ = false;   // the canvas shows the simulation's state
  bool texture_current_ = false;  // the texture shows the canvas
  // The mouse, in window pixels; a press is held for the next step even if
  // the button is released before it (a quick click still resets 2.5).
  double mouse_x_ = 0.0;
  double mouse_y_ = 0.0;
  bool button_down_ = false;
  bool pending_press_ = false;
  double press_x_ = 0.0;
  double press_y_ = 0.0;

  std::optional<GifWriter> recording_;
  std::string title_;
};

void WindowApp::open() {
  if (!env_set("SDL_VIDEODRIVER") && !env_set("DISPLAY") && !env_set("WAYLAND_DISPLAY")) {
    throw InputError("no display: neither DISPLAY nor WAYLAND_DISPLAY is set");
  }
  // Unless asked for one, only the drivers that show a window (no fallback to
  // offscreen or dummy; no Wayland probe, and its noise, without WAYLAND_DISPLAY).
  const bool driver_requested = env_set("SDL_VIDEODRIVER");
  if (!driver_requested) {
    SDL_SetHint(SDL_HINT_VIDEODRIVER, env_set("WAYLAND_DISPLAY") ? "wayland,x11" : "x11");
  }
  SDL_SetHint(SDL_HINT_MOUSE_FOCUS_CLICKTHROUGH, "1");
  SDL_SetHint(SDL_HINT_VIDEO_X11_NET_WM_BYPASS_COMPOSITOR, "0");
  if (SDL_Init(SDL_INIT_VIDEO) != 0) {
    const std::string reason = sdl_error();
    SDL_Quit();
    throw InputError("no display: " + reason);
  }
  video_ = std::make_unique<SdlVideo>();
  // With DISPLAY set but no server behind it, SDL falls back to a driver that
  // shows nothing (offscreen, dummy): a window nobody sees, running until
  // killed. Those are only for who asks for them by SDL_VIDEODRIVER.
  const char* driver = SDL_GetCurrentVideoDriver();
  const std::string driver_name = driver != nullptr ? driver : "";
  if (!driver_requested && driver_name != "x11" && driver_name != "wayland") {
    const char* display = std::getenv("DISPLAY");
    throw InputError("no display: cannot connect to DISPLAY '" +
                     detail::printable(display != nullptr ? display : "") +
                     "' (SDL found only its '" + driver_name + "' driver)");
  }
  const int width = canvas_.pixel_width();
  const int height = canvas_.pixel_height();
  window_.reset(SDL_CreateWindow("calder", SDL_WINDOWPOS_CENTERED, SDL_WINDOWPOS_CENTERED, width,
                                 height, SDL_WINDOW_SHOWN));
  if (!window_) throw InputError("no display: cannot open a window: " + sdl_error());
  renderer_.reset(
      SDL_CreateRenderer(window_.get(), -1, SDL_RENDERER_ACCELERATED | SDL_RENDERER_PRESENTVSYNC));
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
  texture_.reset(SDL_CreateTexture(renderer_.get(), SDL_PIXELFORMAT_ARGB8888,
                                   SDL_TEXTUREACCESS_STREAMING, width, height));
  if (!texture_) throw RunError("cannot create an SDL texture: " + sdl_error());
  SDL_SetTextureBlendMode(texture_.get(), SDL_BLENDMODE_NONE);
  update_title();
  if (!options_.quiet) {
    err_ << "calder window " << detail::printable(simulation_.scene().name, 200) << ": "
         << window_help() << '\n';
    err_.flush();
  }
}

void WindowApp::update_title() {
  std::string title = "calder: " + detail::printable(simulation_.scene().name, 200);
  std::string state;
  if (paused_) state += "paused at frame " + std::to_string(simulation_.frame());
  if (speed_ != 1.0) {
    if (!state.empty()) state += ", ";
    state += "speed x" + format_number(speed_);
  }
  if (recording_) {
    if (!state.empty()) state += ", ";
    state += "recording GIF";
  }
  if (!state.empty()) title += " [" + state + "]";
  title += " - ";
  title += window_help();
  if (title != title_) {
    SDL_SetWindowTitle(window_.get(), title.c_str());
    title_ = title;
  }
}

void WindowApp::run(const InterruptGuard& interrupt) {
  open();
  draw();
  const double frequency = static_cast<double>(SDL_GetPerformanceFrequency());
  const Uint64 start = SDL_GetPerformanceCounter();
  Uint64 last = start;
  if (at_frame_limit()) running_ = false;
  while (running_) {
    interrupt.check();  // the recording's temporary goes with the destructors
    SDL_Event event;
    while (SDL_PollEvent(&event) != 0) handle(event);
    const Uint64 now = SDL_GetPerformanceCounter();
    const double elapsed = std::min(static_cast<double>(now - last) / frequency, 0.25);
    last = now;
    if (exit_after_ && static_cast<double>(now - start) / frequency >= *exit_after_) {
      running_ = false;
    }
    if (running_ && !paused_) {
      pacer_.advance(elapsed, [this] {
        if (!at_frame_limit()) step_once();
      });
    }
    if (at_frame_limit()) running_ = false;
    present();
    const bool hidden =
        (SDL_GetWindowFlags(window_.get()) & (SDL_WINDOW_MINIMIZED | SDL_WINDOW_HIDDEN)) != 0;
    if (!vsync_ || hidden) {
      // No vsync (the software renderer), or nothing shown that would wait
      // for it: wait out the rest of a display frame.
      const double spent = static_cast<double>(SDL_GetPerformanceCounter() - now) / frequency;
      const double wait = 1.0 / refresh_rate_ - spent;
      if (wait > 0.0) SDL_Delay(static_cast<Uint32>(wait * 1000.0));
    }
  }
  finish();
}

void WindowApp::handle(const SDL_Event& event) {
  switch (event.type) {
    case SDL_QUIT:
      running_ = false;
      break;
    case SDL_KEYDOWN:
      key(event.key);
      break;
    case SDL_MOUSEMOTION:
      mouse_x_ = event.motion.x;
      mouse_y_ = event.motion.y;
      break;
    case SDL_MOUSEBUTTONDOWN:
      if (event.button.button == SDL_BUTTON_LEFT) {
        mouse_x_ = press_x_ = event.button.x;
        mouse_y_ = press_y_ = event.button.y;
        button_down_ = true;
        pending_press_ = true;
      }
      break;
    case SDL_MOUSEBUTTONUP:
      if (event.button.button == SDL_BUTTON_LEFT) {
        mouse_x_ = event.button.x;
        mouse_y_ = event.button.y;
        button_down_ = false;
      }
      break;
    case SDL_WINDOWEVENT:
      if (event.window.event == SDL_WINDOWEVENT_EXPOSED) texture_current_ = false;
      break;
    default:
      break;
  }
}

void WindowApp::key(const SDL_KeyboardEvent& key) {
  const SDL_Keycode code = key.keysym.sym;
  const bool repeat = key.repeat != 0;
  switch (code) {
    case SDLK_q:
    case SDLK_ESCAPE:
      running_ = false;
      break;
    case SDLK_SPACE:
      if (repeat) break;
      paused_ = !paused_;
      pacer_.reset();
      update_title();
      break;
    case SDLK_PERIOD:
    case SDLK_KP_PERIOD:
      if (paused_ && !at_frame_limit()) {
        step_once();
        update_title();
      }
      break;
    case SDLK_r:
      if (repeat) break;
      simulation_ = start_simulation(input_);
      canvas_.clear();
      canvas_current_ = false;
      pending_press_ = false;
      pacer_.reset();
      update_title();
      break;
    case SDLK_f:
      if (repeat) break;
      style_.show_forces = !style_.show_forces;
      canvas_current_ = false;
      break;
    case SDLK_t:
      if (repeat) break;
      style_.trails = !style_.trails;
      canvas_current_ = false;
      break;
    case SDLK_s:
      if (!repeat) save_png();
      break;
    case SDLK_g:
      if (!repeat) toggle_recording();
      break;
    case SDLK_k:  // keep: a snapshot to go on from (calder window FILE, calder run FILE)
      if (repeat) break;
      try {
        note("saved " + save_window_snapshot(simulation_, file_stem()));
      } catch (const Error& e) {
        warn(e.what());
      }
      break;
    case SDLK_PLUS:
    case SDLK_EQUALS:
    case SDLK_KP_PLUS:
      speed_ = std::min(speed_ * 2.0, max_speed);
      pacer_.set_steps_per_second(kStepsPerSecond * speed_);
      update_title();
      break;
    case SDLK_MINUS:
    case SDLK_KP_MINUS:
      speed_ = std::max(speed_ / 2.0, min_speed);
      pacer_.set_steps_per_second(kStepsPerSecond * speed_);
      update_title();
      break;
    default:
      break;
  }
}

void WindowApp::step_once() {
  const Vec2 origin = simulation_.scene().origin;
  InputState input;
  input.mouse_pressed = button_down_ || pending_press_;
  input.mouse = pending_press_ ? window_to_physics(press_x_, press_y_, size_.scale, origin)
                               : window_to_physics(mouse_x_, mouse_y_, size_.scale, origin);
  try {
    if (scripted_) {
      simulation_.step();
    } else {
      simulation_.step(input);
    }
  } catch (const Error& e) {
    throw_run_failure(e, input_.source, simulation_.frame() + 1);
  }
  pending_press_ = false;
  canvas_current_ = false;
  // Trails and recordings need every step drawn; otherwise once a display frame.
  if (style_.trails || recording_) draw();
  if (recording_ && simulation_.frame() % kGifEvery == 0) {
    try {
      recording_->add_frame(canvas_);
    } catch (const Error& e) {
      recording_.reset();
      warn(std::string("GIF recording stopped: ") + e.what());
      update_title();
      return;
    }
    if (recording_->frame_count() >= kMaxGifFrames) {
      stop_recording();
    }
  }
}

void WindowApp::draw() {
  try {
    canvas_.draw(simulation_.world(), simulation_.scene(), style_, simulation_.frame());
  } catch (const Error& e) {
    throw_run_failure(e, input_.source, simulation_.frame());
  }
  canvas_current_ = true;
  texture_current_ = false;
}

void WindowApp::present() {
  if (!canvas_current_) draw();
  if (!texture_current_) {
    SDL_UpdateTexture(texture_.get(), nullptr, canvas_.argb32_data(), canvas_.stride());
    texture_current_ = true;
  }
  SDL_RenderClear(renderer_.get());
  SDL_RenderCopy(renderer_.get(), texture_.get(), nullptr, nullptr);
  SDL_RenderPresent(renderer_.get());
}

void WindowApp::save_png() {
  if (!canvas_current_) draw();
  char frame[24];
  std::snprintf(frame, sizeof frame, "%06lld", static_cast<long long>(simulation_.frame()));
  const std::string path = file_stem() + "-" + frame + ".png";
  try {
    canvas_.write_png(path);
    note("saved " + path);
  } catch (const Error& e) {
    warn(e.what());
  }
}

void WindowApp::toggle_recording() {
  if (recording_) {
    stop_recording();
    return;
  }
  const std::string path = file_stem() + "-" + timestamp() + ".gif";
  try {
    recording_.emplace(path, canvas_.pixel_width(), canvas_.pixel_height(), kGifFps);
    if (!canvas_current_) draw();
    recording_->add_frame(canvas_);
    note("recording " + path + " (g stops)");
  } catch (const Error& e) {
    recording_.reset();
    warn(e.what());
  }
  update_title();
}

void WindowApp::stop_recording() {
  if (!recording_) return;
  try {
    recording_->finish();
    note("saved " + recording_->path() + " (" + std::to_string(recording_->frame_count()) +
         " frames)");
  } catch (const Error& e) {
    warn(e.what());
  }
  recording_.reset();
  update_title();
}

void WindowApp::finish() {
  stop_recording();
  if (!canvas_current_) draw();
  if (options_.screenshot) {
    try {
      canvas_.write_png(*options_.screenshot);
    } catch (const Error& e) {
      throw RunError(std::string("--screenshot: ") + e.what());
    }
  }
  if (options_.print_state) print_state(out_, simulation_);
}

}  // namespace

const char* window_help() {
  return "keys: space pause, . step, r reset, f forces, t trails, s save PNG, g record GIF, "
         "k save snapshot, +/- speed, q quit";
}

Vec2 window_to_physics(double x, double y, double scale, Vec2 origin) {
  return {x / scale - origin.x, y / scale - origin.y};
}

void print_state(std::ostream& out, const Simulation& simulation) {
  const World& world = simulation.world();
  const Vec2 origin = simulation.scene().origin;
  out << "frame " << simulation.frame() << '\n';
  out << "origin " << format_number(origin.x) << ' ' << format_number(origin.y) << '\n';
  std::size_t attractors = 0;
  for (const Field& field : world.fields()) {
    if (const auto* attractor = std::get_if<Attractor>(&field)) {
      out << "attractor " << attractors++ << ' ' << format_number(attractor->position.x) << ' '
          << format_number(attractor->position.y) << " mass " << format_number(attractor->mass)
          << '\n';
    }
  }
  for (std::size_t i = 0; i < world.body_count(); ++i) {
    const BodyId id = world.body(i);
    const Vec2 p = world.position(id);
    out << "body " << i << ' ' << format_number(p.x) << ' ' << format_number(p.y) << " radius "
        << format_number(world.radius(id)) << '\n';
  }
  out << "state_hash " << state_hash_text(world) << '\n';
}

CLI::App* add_window_command(CLI::App& app, WindowOptions& options) {
  CLI::App* window = app.add_subcommand(
      "window", "Run a scene in a window in real time, with the mouse (needs a display)");
  add_input_options(*window, options.input);
  window->get_option("--frames")
      ->description("Close the window after N steps, 0 to 10000000 (default: run until quit)");
  window
      ->add_option("--scale", options.scale,
                   "Window pixels per canvas pixel, in (0, " +
                       detail::format_number(Canvas::max_scale) + "] (default 1)")
      ->type_name("S");
  window
      ->add_option("--speed", options.speed,
                   "Simulation speed: steps of 60 a second times X, 0.125 to 8 (default 1; the "
                   "+ and - keys double and halve it)")
      ->type_name("X");
  add_style_options(*window, options.style);
  window
      ->add_option("--screenshot", options.screenshot,
                   "At exit, write the last frame as a PNG to FILE")
      ->type_name("FILE");
  window
      ->add_option("--exit-after-seconds", options.exit_after_seconds,
                   "Quit after S seconds (for automation)")
      ->type_name("S");
  window->add_flag("--print-state", options.print_state,
                   "At exit, print the frame, the attractors, the bodies and the state hash");
  window->add_flag("--quiet,-q", options.quiet, "Don't print the keys at start");
  window->footer(
      std::string("With --frames N the window closes after N steps (without it, it runs until "
                  "quit). The live mouse drives the scene's bindings (wind while pressed, drag "
                  "the attractor, ...); with --mouse-pressed or --mouse the scripted input is "
                  "replayed instead.\n") +
      window_help() +
      ".\ns saves calder-SCENE-FRAME.png, k calder-SCENE-FRAME.snap (a snapshot: `calder window "
      "FILE` opens it, r goes back to it) and g records calder-SCENE-TIME.gif in the current "
      "folder.\nWithout a display: 'calder: no display: ...' and exit 2.\n");
  return window;
}

void window_command(const WindowOptions& options, std::ostream& out, std::ostream& err) {
  if (options.scale) (void)parse_scale("--scale", *options.scale);
  if (options.speed) (void)parse_speed(*options.speed);
  if (options.exit_after_seconds) (void)parse_seconds(*options.exit_after_seconds);
  if (options.screenshot) check_output_path("--screenshot", *options.screenshot);
  const PreparedInput input = prepare_input(options.input);
  if (options.screenshot) {
    std::vector<NamedPath> inputs;
    if (std::filesystem::is_regular_file(input.source))
      inputs.push_back({"the scene file", input.source});
    if (input.state_path) inputs.push_back({"--state", *input.state_path});
    check_outputs(inputs, {{"--screenshot", *options.screenshot}});
  }
  // Installed before SDL starts, SDL leaves SIGINT and SIGTERM to it: every
  // terminating signal ends the window with exit 128 + signal, cleaned up.
  const InterruptGuard interrupt;
  WindowApp app(options, input, out, err);
  app.run(interrupt);
}

}  // namespace calder::app
