// SPDX-License-Identifier: MIT
// calder::sketch's runner: the flags, one frame (input, draw(), outputs) and
// the headless loop.
#include "runner.hpp"

#include <cerrno>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>
#include <system_error>

#include "../output/output.hpp"
#include "calder/error.hpp"

namespace calder {

namespace {

constexpr std::int64_t kDefaultHeadlessFrames = 600;
constexpr std::int64_t kMaxFrames = 10'000'000;
constexpr int kDefaultCanvasSide = 100;  // p5's canvas without createCanvas

std::string quote(const std::string& text) { return "'" + detail::printable(text, 80) + "'"; }

std::optional<double> to_number(const std::string& text) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text[0]))) return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(value)) {
    return std::nullopt;
  }
  return value;
}

std::optional<std::int64_t> to_integer(const std::string& text) {
  if (text.empty() || !(std::isdigit(static_cast<unsigned char>(text[0])) != 0)) {
    return std::nullopt;
  }
  char* end = nullptr;
  errno = 0;
  const long long value = std::strtoll(text.c_str(), &end, 10);
  if (end != text.c_str() + text.size() || errno == ERANGE) return std::nullopt;
  return static_cast<std::int64_t>(value);
}

std::int64_t parse_count(const std::string& flag, const std::string& text, std::int64_t low,
                         std::int64_t high) {
  const std::optional<std::int64_t> value = to_integer(text);
  if (!value || *value < low || *value > high) {
    throw InputError(flag + ": expected an integer from " + std::to_string(low) + " to " +
                     std::to_string(high) + ", got " + quote(text));
  }
  return *value;
}

double parse_range(const std::string& flag, const std::string& text, double low, double high,
                   const char* what) {
  const std::optional<double> value = to_number(text);
  if (!value || !(*value > low && *value <= high)) {
    throw InputError(flag + ": expected " + what + ", got " + quote(text));
  }
  return *value;
}

Vec2 parse_point(const std::string& flag, const std::string& text) {
  const std::size_t comma = text.find(',');
  if (comma != std::string::npos) {
    const std::optional<double> x = to_number(text.substr(0, comma));
    const std::optional<double> y = to_number(text.substr(comma + 1));
    if (x && y) return {*x, *y};
  }
  throw InputError(flag + ": expected X,Y (two finite numbers), got " + quote(text));
}

std::pair<std::int64_t, std::int64_t> parse_frames_range(const std::string& flag,
                                                         const std::string& text) {
  const std::size_t dash = text.find('-');
  if (dash != std::string::npos) {
    const std::optional<std::int64_t> a = to_integer(text.substr(0, dash));
    const std::optional<std::int64_t> b = to_integer(text.substr(dash + 1));
    if (a && b && *a >= 1 && *b >= *a && *b <= kMaxFrames) return {*a, *b};
  }
  throw InputError(flag + ": expected A-B, frames with 1 <= A <= B <= " +
                   std::to_string(kMaxFrames) + ", got " + quote(text));
}

// The parent folder of an output file must exist (nothing is made for it).
void check_output_file(const std::string& flag, const std::string& path) {
  if (path.empty()) throw InputError(flag + ": expected a file name, got ''");
  if (flag == "--trajectory" && path == "-") return;
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw InputError(flag + ": " + quote(path) + " is a folder");
  const fs::path parent = fs::path(path).parent_path();
  if (!parent.empty() && !fs::is_directory(parent, ec)) {
    throw InputError(flag + ": no folder " + quote(parent.string()) + " for " + quote(path));
  }
}

}  // namespace

std::string sketch_usage(const std::string& program) {
  return "usage: " + program +
         " [flags]\n"
         "With a display the sketch opens a window; headless it draws frames to files.\n"
         "  --frames N          draw N frames (headless default 600; a window: until closed)\n"
         "  --gif FILE          write every frame to an animated GIF (headless)\n"
         "  --png DIR           write DIR/frame-000001.png, ... one a frame (headless)\n"
         "  --trajectory FILE   the recorded world's state each frame as CSV, - for stdout\n"
         "  --scale S           pixel density, in (0, 8] (default 1; a window: times the "
         "display's)\n"
         "  --fps F             the GIF's frames per second, 0.01 to 100 (default 30)\n"
         "  --every K           --gif and --png take frames K, 2K, ... (default 1)\n"
         "  --mouse-pressed A-B the mouse held in frames A to B (repeatable; replaces the live "
         "mouse)\n"
         "  --mouse X,Y         the mouse at X,Y (canvas pixels; replaces the live mouse)\n"
         "  --seed S            seed of random() and noise(), 0 to 4294967295 (default 1)\n"
         "  --window            a window, or an error without a display\n"
         "  --headless          no window (with --frames: draw and write nothing else)\n"
         "  --exit-after-seconds S  close the window after S seconds\n"
         "  --quiet             don't report what was written\n"
         "  --help              this text\n";
}

SketchOptions parse_sketch_options(int argc, const char* const* argv, bool* help) {
  SketchOptions options;
  if (argc > 0 && argv[0] != nullptr) {
    options.program = std::filesystem::path(argv[0]).filename().string();
  }
  if (help != nullptr) *help = false;
  for (int i = 1; i < argc; ++i) {
    std::string flag = argv[i];
    std::optional<std::string> inline_value;
    if (const std::size_t eq = flag.find('=');
        flag.rfind("--", 0) == 0 && eq != std::string::npos) {
      inline_value = flag.substr(eq + 1);
      flag = flag.substr(0, eq);
    }
    const auto value = [&]() -> std::string {
      if (inline_value) return *inline_value;
      if (i + 1 >= argc) throw InputError(flag + ": expects a value");
      return argv[++i];
    };
    const auto no_value = [&] {
      if (inline_value) throw InputError(flag + ": takes no value");
    };
    if (flag == "--help" || flag == "-h") {
      if (help != nullptr) *help = true;
      return options;
    } else if (flag == "--frames") {
      options.frames = parse_count(flag, value(), 0, kMaxFrames);
    } else if (flag == "--gif") {
      options.gif = value();
      check_output_file(flag, *options.gif);
    } else if (flag == "--png") {
      options.png = value();
      if (options.png->empty()) throw InputError("--png: expected a folder, got ''");
    } else if (flag == "--trajectory") {
      options.trajectory = value();
      check_output_file(flag, *options.trajectory);
    } else if (flag == "--scale") {
      options.scale = parse_range(flag, value(), 0.0, Canvas::max_scale, "a number in (0, 8]");
    } else if (flag == "--fps") {
      const double fps = parse_range(flag, value(), 0.0, 100.0, "a number from 0.01 to 100");
      if (fps < 0.01) throw InputError("--fps: expected a number from 0.01 to 100");
      options.gif_fps = fps;
    } else if (flag == "--every") {
      options.every = parse_count(flag, value(), 1, kMaxFrames);
    } else if (flag == "--mouse-pressed") {
      options.mouse_pressed.push_back(parse_frames_range(flag, value()));
    } else if (flag == "--mouse") {
      options.mouse = parse_point(flag, value());
    } else if (flag == "--seed") {
      options.seed = static_cast<std::uint32_t>(parse_count(flag, value(), 0, 4294967295LL));
    } else if (flag == "--window") {
      no_value();
      options.mode = SketchOptions::Mode::window;
    } else if (flag == "--headless") {
      no_value();
      options.mode = SketchOptions::Mode::headless;
    } else if (flag == "--exit-after-seconds") {
      options.exit_after_seconds =
          parse_range(flag, value(), 0.0, 1e6, "a number > 0 and <= 1000000");
    } else if (flag == "--quiet" || flag == "-q") {
      no_value();
      options.quiet = true;
    } else {
      throw InputError("unknown flag " + quote(flag) + " (--help lists them)");
    }
  }
  if (options.mode == SketchOptions::Mode::window && (options.gif || options.png)) {
    throw InputError("--window: --gif and --png are headless; a window saves with save_frame()");
  }
  return options;
}

// --- one frame -------------------------------------------------------------------

SketchRunner::SketchRunner(Sketch& sketch, const SketchOptions& options)
    : sketch_(sketch), options_(options), title_(options.program) {
  if (sketch_.runner_ != nullptr) throw Error("run_sketch: this sketch is already running");
  sketch_.runner_ = this;
}

SketchRunner::~SketchRunner() { sketch_.runner_ = nullptr; }

void SketchRunner::create_canvas(int width, int height) {
  if (canvas_) throw Error("create_canvas: the canvas exists already (call it once, in setup())");
  double density = options_.scale;
  if (open_window) density *= open_window(width, height);
  try {
    canvas_.emplace(width, height, std::min(density, Canvas::max_scale));
  } catch (const Error& e) {
    throw Error(std::string("create_canvas: ") + e.what());
  }
}

Canvas& SketchRunner::canvas() {
  if (!canvas_) create_canvas(kDefaultCanvasSide, kDefaultCanvasSide);
  return *canvas_;
}

void SketchRunner::setup() {
  sketch_.seed_ = options_.seed;
  sketch_.random_.random_seed(options_.seed);
  sketch_.noise_.noise_seed(options_.seed);
  if (options_.mouse) sketch_.mouse_ = *options_.mouse;
  last_frame_mouse_ = sketch_.mouse_;
  sketch_.pmouse_ = sketch_.mouse_;
  sketch_.setup();
  (void)canvas();
  // Every output checked against the others before any is made (the output
  // module's policy, as for calder render).
  std::vector<output::NamedPath> outputs;
  if (options_.gif) outputs.push_back({"--gif", *options_.gif});
  if (options_.png) outputs.push_back({"--png", *options_.png, output::Kind::folder});
  if (options_.trajectory && *options_.trajectory != "-") {
    outputs.push_back({"--trajectory", *options_.trajectory});
  }
  output::check_outputs({}, outputs);
  if (options_.gif)
    gif_.emplace(*options_.gif, canvas_->pixel_width(), canvas_->pixel_height(), options_.gif_fps);
  if (options_.png) {
    png_.emplace("--png", *options_.png, is_frame_png_name, "a PNG file of an earlier run");
  }
  if (options_.trajectory) {
    if (sketch_.recorded_ == nullptr) {
      throw InputError("--trajectory: this sketch records no world (it calls record() in setup())");
    }
    trajectory_.emplace(*options_.trajectory == "-" ? std::cout : trajectory_text_);
    trajectory_->write(0, *sketch_.recorded_);
  }
}

bool SketchRunner::scripted_pressed(std::int64_t frame) const {
  for (const auto& [a, b] : options_.mouse_pressed) {
    if (frame >= a && frame <= b) return true;
  }
  return false;
}

bool SketchRunner::wants_draw() const {
  return !finished() && (sketch_.looping_ || sketch_.redraw_);
}

bool SketchRunner::finished() const {
  return sketch_.exit_ || (options_.frames && sketch_.frame_count_ >= *options_.frames);
}

void SketchRunner::draw_frame() {
  Sketch& s = sketch_;
  const std::int64_t frame = s.frame_count_ + 1;
  if (!options_.mouse_pressed.empty()) {
    // The scripted mouse: its presses and releases come before the frame's
    // draw(), as p5's events come between frames.
    const bool pressed = scripted_pressed(frame);
    if (pressed != s.mouse_is_pressed_) {
      s.mouse_is_pressed_ = pressed;
      if (pressed) {
        s.mouse_pressed();
      } else {
        s.mouse_released();
      }
    }
  }
  s.frame_count_ = frame;
  s.redraw_ = false;
  s.pmouse_ = last_frame_mouse_;
  s.transform_ = Transform{};
  s.saved_.clear();
  s.draw();
  last_frame_mouse_ = s.mouse_;
  write_outputs();
}

void SketchRunner::write_outputs() {
  const std::int64_t frame = sketch_.frame_count_;
  if (trajectory_) trajectory_->write(frame, *sketch_.recorded_);
  if (frame % options_.every != 0) return;
  if (gif_) gif_->add_frame(*canvas_);
  if (png_) png_->write(frame_png_name(frame), canvas_->encode_png());
}

void SketchRunner::finish() {
  sketch_.on_exit();
  if (gif_ && gif_->frame_count() == 0) {
    throw InputError("--gif: no frame was drawn (--frames 0, or no_loop() in setup())");
  }
  if (gif_) gif_->finish();
  if (png_) png_->commit();
  if (options_.trajectory && *options_.trajectory != "-") {
    output::AtomicFile file("--trajectory", *options_.trajectory);
    const std::string text = trajectory_text_.str();
    file.write_all(text.data(), text.size());
    file.commit();
  } else if (options_.trajectory) {
    std::cout.flush();
    if (!std::cout) throw Error("--trajectory: cannot write to stdout");
  }
  if (!options_.quiet && (gif_ || options_.png)) {
    std::string line = options_.program + ": " + std::to_string(sketch_.frame_count_) +
                       (sketch_.frame_count_ == 1 ? " frame" : " frames");
    if (gif_) line += ", " + *options_.gif;
    if (options_.png) line += ", " + std::to_string(png_->count()) + " PNGs in " + *options_.png;
    std::cerr << line << '\n';
  }
}

void SketchRunner::mouse_moved(double x, double y) {
  if (!options_.mouse_pressed.empty() || options_.mouse) return;
  sketch_.mouse_ = {x, y};
  if (live_pressed_) sketch_.mouse_dragged();
}

void SketchRunner::mouse_down(double x, double y) {
  if (!options_.mouse_pressed.empty() || options_.mouse) return;
  sketch_.mouse_ = {x, y};
  live_pressed_ = true;
  sketch_.mouse_is_pressed_ = true;
  sketch_.mouse_pressed();
}

void SketchRunner::mouse_up(double x, double y) {
  if (!options_.mouse_pressed.empty() || options_.mouse) return;
  sketch_.mouse_ = {x, y};
  live_pressed_ = false;
  sketch_.mouse_is_pressed_ = false;
  sketch_.mouse_released();
}

void SketchRunner::key_down(const std::string& key, bool repeat) {
  sketch_.key_ = key;
  sketch_.key_repeated_ = repeat;
  sketch_.key_pressed();
}

// --- running -----------------------------------------------------------------------

namespace {

void run_headless(SketchRunner& runner) {
  runner.setup();
  while (runner.wants_draw()) {
    if (runner.options().poll) runner.options().poll();
    runner.draw_frame();
  }
  runner.finish();
}

bool wants_window(const SketchOptions& options) {
  switch (options.mode) {
    case SketchOptions::Mode::window:
      return true;
    case SketchOptions::Mode::headless:
      return false;
    case SketchOptions::Mode::automatic:
      break;
  }
  return !(options.gif || options.png || options.trajectory);
}

}  // namespace

void run_sketch(Sketch& sketch, const SketchOptions& options) {
  SketchOptions resolved = options;
  const bool window = wants_window(options);
  if (!window && !resolved.frames) resolved.frames = kDefaultHeadlessFrames;
  SketchRunner runner(sketch, resolved);
  if (window) {
    run_sketch_window(runner);
  } else {
    run_headless(runner);
  }
}

int run_sketch(Sketch& sketch, int argc, char** argv) {
  SketchOptions options;
  if (argc > 0 && argv[0] != nullptr) {
    options.program = std::filesystem::path(argv[0]).filename().string();
  }
  try {
    bool help = false;
    options = parse_sketch_options(argc, argv, &help);
    if (help) {
      std::cout << sketch_usage(options.program);
      return 0;
    }
    if (wants_window(options)) {
      const std::string reason = sketch_no_display_reason();
      if (!reason.empty()) {
        std::cerr << options.program << ": " << reason
                  << "; run headless with --gif FILE, --png DIR or --trajectory FILE (--help)\n";
        return 2;
      }
    }
  } catch (const Error& e) {
    std::cerr << options.program << ": " << e.what() << '\n';
    return 2;
  }
  try {
    run_sketch(sketch, options);
  } catch (const InputError& e) {  // an output that can't be made, no display
    std::cerr << options.program << ": " << e.what() << '\n';
    return 2;
  } catch (const std::exception& e) {
    std::cerr << options.program << ": " << e.what() << '\n';
    return 1;
  }
  return 0;
}

}  // namespace calder
