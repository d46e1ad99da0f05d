// SPDX-License-Identifier: MIT
#include "window_command.hpp"

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
#include "calder/render.hpp"
#include "calder/sketch.hpp"
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

std::string timestamp() {
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  std::array<char, 32> text{};
  std::strftime(text.data(), text.size(), "%Y%m%d-%H%M%S", &local);
  return text.data();
}

// `calder window`: a sketch that runs a scene and draws it, on calder::sketch's
// window loop. Its keys and the live mouse drive the simulation.
class SceneSketch : public Sketch {
 public:
  SceneSketch(const WindowOptions& options, const PreparedInput& input, std::ostream& out,
              std::ostream& err, const InterruptGuard& interrupt)
      : options_(options),
        input_(input),
        out_(out),
        err_(err),
        interrupt_(interrupt),
        simulation_(start_simulation(input)),
        style_(make_style(input.scene, options.style)),
        size_(canvas_size(std::nullopt, options.scale, input.scene)),
        speed_(options.speed ? parse_speed(*options.speed) : 1.0),
        scripted_(!options.input.mouse_pressed.empty() || options.input.mouse.has_value()) {
    start_hud(style_, simulation_);
    if (options.input.frames) frame_limit_ = input.scene.frames;
    if (options.screenshot) check_output_path("--screenshot", *options.screenshot);
  }

  [[nodiscard]] const CanvasSize& size() const { return size_; }

 private:
  void setup() override;
  void draw() override;
  void mouse_pressed() override;
  void key_pressed() override;
  void on_exit() override;

  void step_once();
  void draw_scene();
  void apply_speed();
  // Trails and recordings need every step drawn; otherwise once a frame.
  [[nodiscard]] bool drawn_each_step() const { return style_.trails || recording_.has_value(); }
  void update_title();
  void save_png();
  void toggle_recording();
  void stop_recording();
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
  const InterruptGuard& interrupt_;
  Simulation simulation_;
  RenderStyle style_;
  CanvasSize size_;
  double speed_;
  bool scripted_;
  std::optional<std::int64_t> frame_limit_;

  bool paused_ = false;
  double step_credit_ = 0.0;  // steps due in the next frames (speed above 1)
  // A press is held for the next step even if the button is released before
  // it (a quick click still resets 2.5).
  bool pending_press_ = false;
  double press_x_ = 0.0;
  double press_y_ = 0.0;

  std::optional<GifWriter> recording_;
};

void SceneSketch::setup() {
  update_title();  // the window opens with it
  apply_speed();
  create_canvas(size_.width, size_.height);
  if (!options_.quiet) {
    err_ << "calder window " << detail::printable(simulation_.scene().name, 200) << ": "
         << window_help() << '\n';
    err_.flush();
  }
  draw_scene();
  if (at_frame_limit()) exit_sketch();
}

void SceneSketch::draw() {
  interrupt_.check();  // the recording's temporary goes with the destructors
  // Above speed 1 a frame takes several steps (their credit carries over for
  // speeds like 1.5) and is drawn once; below it the frame rate is lower.
  step_credit_ += std::max(speed_, 1.0);
  bool stepped = false;
  while (step_credit_ >= 1.0 && !at_frame_limit()) {
    step_credit_ -= 1.0;
    step_once();
    stepped = true;
  }
  if (stepped && !drawn_each_step()) draw_scene();
  if (at_frame_limit()) exit_sketch();
}

void SceneSketch::apply_speed() { frame_rate(kStepsPerSecond * std::min(speed_, 1.0)); }

void SceneSketch::update_title() {
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
  window_title(title);
}

void SceneSketch::mouse_pressed() {
  press_x_ = mouse_x();
  press_y_ = mouse_y();
  pending_press_ = true;
}

void SceneSketch::key_pressed() {
  std::string k = key();
  if (k.size() == 1 && k[0] >= 'A' && k[0] <= 'Z') k[0] = static_cast<char>(k[0] - 'A' + 'a');
  const bool repeat = key_repeated();
  if (k == "q" || k == "Escape") {
    exit_sketch();
  } else if (k == " ") {
    if (repeat) return;
    paused_ = !paused_;
    if (paused_) {
      no_loop();
    } else {
      loop();
    }
    update_title();
  } else if (k == ".") {
    if (paused_ && !at_frame_limit()) {
      step_once();
      if (!drawn_each_step()) draw_scene();
      update_title();
    }
  } else if (k == "r") {
    if (repeat) return;
    simulation_ = start_simulation(input_);
    canvas().clear();
    pending_press_ = false;
    step_credit_ = 0.0;
    draw_scene();
    update_title();
  } else if (k == "f") {
    if (repeat) return;
    style_.show_forces = !style_.show_forces;
    draw_scene();
  } else if (k == "t") {
    if (repeat) return;
    style_.trails = !style_.trails;
    draw_scene();
  } else if (k == "s") {
    if (!repeat) save_png();
  } else if (k == "g") {
    if (!repeat) toggle_recording();
  } else if (k == "k") {  // keep: a snapshot to go on from (calder window FILE, calder run FILE)
    if (repeat) return;
    try {
      note("saved " + save_window_snapshot(simulation_, file_stem()));
    } catch (const Error& e) {
      warn(e.what());
    }
  } else if (k == "+" || k == "=") {
    speed_ = std::min(speed_ * 2.0, max_speed);
    apply_speed();
    update_title();
  } else if (k == "-") {
    speed_ = std::max(speed_ / 2.0, min_speed);
    apply_speed();
    update_title();
  }
}

void SceneSketch::step_once() {
  const Vec2 origin = simulation_.scene().origin;
  InputState input;
  input.mouse_pressed = mouse_is_pressed() || pending_press_;
  // The mouse is in canvas pixels already (the runner divides by the scale).
  input.mouse = pending_press_ ? window_to_physics(press_x_, press_y_, 1.0, origin)
                               : window_to_physics(mouse_x(), mouse_y(), 1.0, origin);
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
  if (drawn_each_step()) draw_scene();
  if (recording_ && simulation_.frame() % kGifEvery == 0) {
    try {
      recording_->add_frame(canvas());
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

void SceneSketch::draw_scene() {
  try {
    canvas().draw(simulation_.world(), simulation_.scene(), style_, simulation_.frame());
  } catch (const Error& e) {
    throw_run_failure(e, input_.source, simulation_.frame());
  }
}

void SceneSketch::save_png() {
  char frame[24];
  std::snprintf(frame, sizeof frame, "%06lld", static_cast<long long>(simulation_.frame()));
  const std::string path = file_stem() + "-" + frame + ".png";
  try {
    canvas().write_png(path);
    note("saved " + path);
  } catch (const Error& e) {
    warn(e.what());
  }
}

void SceneSketch::toggle_recording() {
  if (recording_) {
    stop_recording();
    return;
  }
  const std::string path = file_stem() + "-" + timestamp() + ".gif";
  try {
    recording_.emplace(path, canvas().pixel_width(), canvas().pixel_height(), kGifFps);
    recording_->add_frame(canvas());
    note("recording " + path + " (g stops)");
  } catch (const Error& e) {
    recording_.reset();
    warn(e.what());
  }
  update_title();
}

void SceneSketch::stop_recording() {
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

void SceneSketch::on_exit() {
  stop_recording();
  if (options_.screenshot) {
    try {
      canvas().write_png(*options_.screenshot);
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
  SceneSketch sketch(options, input, out, err, interrupt);
  SketchOptions run;
  run.mode = SketchOptions::Mode::window;
  run.scale = sketch.size().scale;
  run.exit_after_seconds = options.exit_after_seconds
                               ? std::optional(parse_seconds(*options.exit_after_seconds))
                               : std::nullopt;
  run.quiet = true;
  run.program = "calder";
  run.poll = [&interrupt] { interrupt.check(); };
  run_sketch(sketch, run);
}

}  // namespace calder::app
