// SPDX-License-Identifier: MIT
#include "render_command.hpp"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "calder/error.hpp"
#include "calder/trajectory.hpp"
#include "errors.hpp"
#include "parse.hpp"
#include "progress.hpp"
#include "run_command.hpp"

namespace calder::app {

namespace fs = std::filesystem;

namespace {

std::string shown(const std::string& text) { return detail::printable(text, 240); }
std::string quoted(const std::string& text) { return "'" + detail::printable(text) + "'"; }

std::int64_t parse_every(const std::string& text) {
  const std::optional<std::int64_t> value = to_int64(text);
  if (!value || *value < 1 || *value > max_render_frames) {
    throw InputError("--every: expected an integer from 1 to " + std::to_string(max_render_frames) +
                     ", got " + quoted(text));
  }
  return *value;
}

double parse_fps(const std::string& text) {
  const std::optional<double> value = to_double(text);
  if (!value || !(*value >= min_fps && *value <= max_fps)) {
    throw InputError("--fps: expected a number from 0.01 to 100, got " + quoted(text));
  }
  return *value;
}

// The text's integer if it is one from 1 to max_image_side.
std::optional<int> side(const std::string& text) {
  const std::optional<std::int64_t> value = to_int64(text);
  if (!value || *value < 1 || *value > max_image_side) return std::nullopt;
  return static_cast<int>(*value);
}

// The folder of PNG frames: created when missing. The frames are written to
// a hidden staging folder inside it (".calder-frames.XXXXXX") and moved into
// place only by commit(): a failed or interrupted run removes what it staged
// (and the folders it created) and leaves the frames of an earlier run as they
// were.
class PngFolder {
 public:
  explicit PngFolder(std::string dir) : dir_(std::move(dir)) {
    if (dir_.empty()) throw InputError("--png: the folder name is empty");
    std::error_code ec;
    std::vector<fs::path> missing;  // deepest first
    fs::path p = fs::path(dir_).lexically_normal();
    if (!p.has_filename() && p.has_parent_path()) p = p.parent_path();  // "frames/"
    const fs::path target = p;
    while (!p.empty() && !fs::exists(fs::symlink_status(p, ec))) {
      missing.push_back(p);
      if (!p.has_parent_path() || p.parent_path() == p) break;
      p = p.parent_path();
    }
    if (missing.empty() || missing.back() != p) {  // p exists: it must be a folder
      if (!fs::is_directory(p, ec)) {
        throw InputError(shown(dir_) + ": cannot write PNG frames there: " +
                         (p == target ? std::string("it is not a directory")
                                      : "'" + shown(p.string()) + "' is not a directory"));
      }
    }
    for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
      if (!fs::create_directory(*it, ec) && ec) {
        const std::string reason = ec.message();
        remove_created();
        throw InputError(shown(dir_) + ": cannot create the directory: " + reason);
      }
      created_.push_back(*it);
    }
    std::string staging = (fs::path(dir_) / ".calder-frames.XXXXXX").string();
    if (::mkdtemp(staging.data()) == nullptr) {
      const std::string reason = std::generic_category().message(errno);
      remove_created();
      throw InputError(shown(dir_) + ": cannot write PNG frames there: " + reason);
    }
    staging_ = staging;
  }

  ~PngFolder() {
    if (!committed_) discard();
  }
  PngFolder(const PngFolder&) = delete;
  PngFolder& operator=(const PngFolder&) = delete;

  // Writes frame-<index>.png (to the staging folder). A failure on the first
  // file is bad output (exit 2); later ones are a failed run (exit 1).
  void write(const Canvas& canvas, std::int64_t index) {
    char name[32];
    std::snprintf(name, sizeof name, "frame-%06lld.png", static_cast<long long>(index));
    const std::string path = (fs::path(staging_) / name).string();
    try {
      canvas.write_png(path);
    } catch (const Error& e) {
      std::string what = e.what();
      const std::size_t at = what.find(staging_);  // name the frame as it will be called
      if (at != std::string::npos) what.replace(at, staging_.size(), dir_);
      if (names_.empty()) throw InputError("--png: " + what);
      throw RunError("--png: " + what);
    }
    names_.emplace_back(name);
  }

  // Moves the staged frames into the folder (over earlier frames of the same names).
  void commit() {
    for (const std::string& name : names_) {
      const std::string from = (fs::path(staging_) / name).string();
      const std::string to = (fs::path(dir_) / name).string();
      if (std::rename(from.c_str(), to.c_str()) != 0) {
        throw RunError("--png: cannot move '" + shown(name) + "' into " + shown(dir_) + ": " +
                       std::generic_category().message(errno));
      }
    }
    std::error_code ec;
    fs::remove(staging_, ec);
    committed_ = true;
  }

  [[nodiscard]] std::size_t count() const { return names_.size(); }
  [[nodiscard]] const std::string& dir() const { return dir_; }
  [[nodiscard]] const std::string& name(std::size_t k) const { return names_.at(k); }

 private:
  void discard() noexcept {
    std::error_code ec;
    if (!staging_.empty()) fs::remove_all(staging_, ec);
    names_.clear();
    remove_created();
  }
  void remove_created() noexcept {
    std::error_code ec;
    for (auto it = created_.rbegin(); it != created_.rend(); ++it) fs::remove(*it, ec);  // if empty
    created_.clear();
  }

  std::string dir_;
  std::string staging_;
  std::vector<fs::path> created_;   // outermost first
  std::vector<std::string> names_;  // staged frames
  bool committed_ = false;
};

void draw(Canvas& canvas, const Simulation& simulation, const RenderStyle& style,
          const std::string& source) {
  try {
    canvas.draw(simulation.world(), simulation.scene(), style, simulation.frame());
  } catch (const Error& e) {
    throw_run_failure(e, source, simulation.frame());
  }
}

std::string size_text(const Canvas& canvas) {
  return std::to_string(canvas.pixel_width()) + "x" + std::to_string(canvas.pixel_height());
}

}  // namespace

void add_style_options(CLI::App& command, StyleOptions& options) {
  CLI::Option* trails =
      command.add_flag("--trails", options.trails,
                       "Fade old frames instead of clearing (p5's background(255, alpha))");
  CLI::Option* no_trails =
      command.add_flag("--no-trails", options.no_trails, "Clear the canvas every frame");
  trails->excludes(no_trails);
  command.add_flag("--forces", options.forces,
                   "Draw each field's force on each body, the net force and a legend");
  command.add_flag("--velocity", options.velocity, "Draw each body's velocity");
  command.add_flag("--hud", options.hud, "Show the frame, the body count and the total energy");
  command.add_flag("--figure", options.figure,
                   "The look of the book's printed figures (fading trails) instead of the "
                   "sketch's");
}

RenderStyle make_style(const Scene& scene, const StyleOptions& options) {
  RenderStyle style = book_style(scene, options.figure ? BookLook::figure : BookLook::sketch);
  if (options.trails) style.trails = true;
  if (options.no_trails) style.trails = false;
  if (options.forces) style.show_forces = true;
  if (options.velocity) style.show_velocity = true;
  if (options.hud) style.show_hud = true;
  try {
    style.validate();
  } catch (const Error& e) {
    rethrow_with_context(e, scene.name + ": ");
  }
  return style;
}

double parse_scale(const std::string& flag, const std::string& text) {
  const std::optional<double> value = to_double(text);
  if (!value || !(*value > 0.0 && *value <= max_scale)) {
    throw InputError(flag + ": expected a number > 0 and <= " + detail::format_number(max_scale) +
                     ", got " + quoted(text));
  }
  return *value;
}

CanvasSize canvas_size(const std::optional<std::string>& size,
                       const std::optional<std::string>& scale, const Scene& scene) {
  CanvasSize result;
  if (scale) result.scale = parse_scale("--scale", *scale);
  if (size) {
    const std::size_t x = size->find_first_of("xX");
    std::optional<int> w;
    std::optional<int> h;
    if (x != std::string::npos) {
      w = side(size->substr(0, x));
      h = side(size->substr(x + 1));
    }
    if (!w || !h) {
      throw InputError("--size: expected WIDTHxHEIGHT in canvas pixels, each 1 to " +
                       std::to_string(max_image_side) + " (e.g. 640x240), got " + quoted(*size));
    }
    result.width = *w;
    result.height = *h;
  } else {
    const double w = std::round(scene.world.width);
    const double h = std::round(scene.world.height);
    if (!(w >= 1.0 && w <= max_image_side && h >= 1.0 && h <= max_image_side)) {
      throw InputError(scene.name + ": the canvas, " + format_number(scene.world.width) + " x " +
                       format_number(scene.world.height) + ", is not 1 to " +
                       std::to_string(max_image_side) + " pixels a side; choose one with --size");
    }
    result.width = static_cast<int>(w);
    result.height = static_cast<int>(h);
  }
  const double pw = std::round(result.width * result.scale);
  const double ph = std::round(result.height * result.scale);
  if (!(pw >= 1.0 && pw <= max_image_side && ph >= 1.0 && ph <= max_image_side)) {
    throw InputError("--scale: " + format_number(result.scale) + " makes the image " +
                     format_number(pw) + "x" + format_number(ph) + " pixels (" +
                     std::to_string(result.width) + "x" + std::to_string(result.height) +
                     " canvas pixels); each side must be 1 to " + std::to_string(max_image_side));
  }
  return result;
}

void check_output_path(const std::string& flag, const std::string& path) {
  if (path.empty()) throw InputError(flag + ": the file name is empty");
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw InputError(path + ": is a directory, not a file");
  const fs::path target(path);
  const fs::path directory = target.has_parent_path() ? target.parent_path() : fs::path(".");
  if (!fs::is_directory(directory, ec)) {
    throw InputError(path + ": cannot create the file: directory '" + directory.string() +
                     "' does not exist");
  }
}

std::string file_name_part(const std::string& name) {
  std::string part;
  for (const char c : name) {
    const bool safe = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                      c == '.' || c == '-' || c == '_';
    part += safe ? c : '_';
  }
  while (!part.empty() && part.front() == '.') part.erase(part.begin());
  return part.empty() ? std::string("scene") : part;
}

CLI::App* add_render_command(CLI::App& app, RenderOptions& options) {
  CLI::App* render = app.add_subcommand(
      "render", "Draw a scene headless to PNG frames (--png DIR) and/or an animated GIF (--gif)");
  add_input_options(*render, options.input);
  render->get_option("--frames")->description("Frames to run, 0 to 100000 (default: the scene's)");
  render
      ->add_option("--every", options.every,
                   "Draw every K-th frame: frames 0, K, 2K, ... up to --frames (default 1)")
      ->type_name("K");
  render
      ->add_option("--png", options.png,
                   "Write the frames as DIR/frame-000000.png, frame-000001.png, ... in the order "
                   "drawn (DIR is created if missing)")
      ->type_name("DIR");
  render
      ->add_option("--gif", options.gif,
                   "Write an endlessly looping animated GIF (written to a temporary file renamed "
                   "on success)")
      ->type_name("FILE");
  render
      ->add_option("--size", options.size,
                   "Canvas size in canvas pixels (default: the scene's width x height)")
      ->type_name("WxH");
  render
      ->add_option("--scale", options.scale,
                   "Pixel density in (0, " + detail::format_number(max_scale) +
                       "] (default 1; 2 gives the book's 1280x480 figures)")
      ->type_name("S");
  render->add_option("--fps", options.fps, "GIF frames per second, 0.01 to 100 (default 30)")
      ->type_name("F");
  add_style_options(*render, options.style);
  render->add_flag("--quiet,-q", options.quiet,
                   "No progress bar and no report of what was written");
  render->footer(
      "Frame 0 is the state after setup. --frames is at most 100000, and at most 10000 frames are "
      "written (frames / every + 1). Each side of the image, after --scale, is 1 to " +
      std::to_string(max_image_side) +
      " pixels.\n"
      "A progress bar is shown on standard error when it is a terminal.\n"
      "Exit status: 0 success, 1 the run or a write failed (the files it wrote are removed), 2 bad "
      "usage, bad input or an output path that can't be written.\n");
  return render;
}

namespace {

// Throws InputError when the run draws more frames, or writes more images,
// than render's limits.
void check_render_frames(const PreparedInput& input, const RenderOptions& options,
                         std::int64_t every) {
  const std::int64_t frames = input.scene.frames;
  if (frames > max_render_frames) {
    if (options.input.frames) {
      throw InputError("--frames: render draws at most " + std::to_string(max_render_frames) +
                       " frames, got " + quoted(*options.input.frames));
    }
    throw InputError(input.source + ": the scene runs " + std::to_string(frames) +
                     " frames, more than render draws (" + std::to_string(max_render_frames) +
                     "); choose fewer with --frames");
  }
  const std::int64_t outputs = frames / every + 1;
  if (outputs > max_output_frames) {
    throw InputError("--every: " + std::to_string(frames) + " frames every " +
                     std::to_string(every) + " would write " + std::to_string(outputs) +
                     " images, more than " + std::to_string(max_output_frames) +
                     " (use a larger --every or fewer --frames)");
  }
}

// What render wrote, one line per output (null: not chosen).
void report_written(std::ostream& out, const Canvas& canvas, std::int64_t frames,
                    const PngFolder* png, const GifWriter* gif, double fps) {
  const std::string what = std::to_string(frames) + (frames == 1 ? " frame" : " frames") + " of " +
                           size_text(canvas) + " pixels";
  if (png != nullptr) {
    out << "wrote " << png->name(0);
    if (png->count() > 1) out << " to " << png->name(png->count() - 1);
    out << " in " << png->dir() << " (" << what << ")\n";
  }
  if (gif != nullptr) {
    out << "wrote " << gif->path() << " (" << what << " at " << format_number(fps) << " fps)\n";
  }
}

}  // namespace

void render_command(const RenderOptions& options, std::ostream& out, std::ostream& err) {
  if (!options.png && !options.gif) {
    throw InputError("render: no output chosen: give --png DIR and/or --gif FILE");
  }
  const std::int64_t every = options.every ? parse_every(*options.every) : 1;
  const double fps = options.fps ? parse_fps(*options.fps) : 30.0;
  if (options.scale) (void)parse_scale("--scale", *options.scale);
  if (options.gif) check_output_path("--gif", *options.gif);

  const PreparedInput input = prepare_input(options.input);
  const std::int64_t frames = input.scene.frames;
  check_render_frames(input, options, every);
  const CanvasSize size = canvas_size(options.size, options.scale, input.scene);
  const RenderStyle style = make_style(input.scene, options.style);
  Simulation simulation = start_simulation(input);

  std::optional<Canvas> canvas;
  try {
    canvas.emplace(size.width, size.height, size.scale);
  } catch (const Error& e) {
    rethrow_with_context(e, "--size/--scale: ");
  }
  // From here on a terminating signal only sets a flag: the run stops at the
  // next frame and the destructors remove the GIF's temporary and the staged frames.
  const InterruptGuard interrupt;
  std::optional<GifWriter> gif;
  if (options.gif) {
    gif.emplace(*options.gif, canvas->pixel_width(), canvas->pixel_height(), fps);
  }
  std::optional<PngFolder> png;
  if (options.png) png.emplace(*options.png);

  Progress progress(err, "render " + detail::printable(input.scene.name), frames,
                    !options.quiet && stderr_is_terminal());
  std::int64_t index = 0;
  const auto emit = [&]() {
    if (png) png->write(*canvas, index);
    if (gif) {
      try {
        gif->add_frame(*canvas);
      } catch (const Error& e) {
        throw RunError(e.what());
      }
    }
    ++index;
  };

  draw(*canvas, simulation, style, input.source);
  emit();
  run_frames(simulation, frames, input.source, [&](std::int64_t frame) {
    interrupt.check();
    const bool output = frame % every == 0;
    // With trails every frame leaves its mark, as in the sketch.
    if (output || style.trails) draw(*canvas, simulation, style, input.source);
    if (output) emit();
    progress.update(frame);
  });
  interrupt.check();
  if (gif) {
    try {
      gif->finish();
    } catch (const Error& e) {
      throw RunError(e.what());
    }
  }
  if (png) png->commit();
  progress.finish();

  if (!options.quiet)
    report_written(out, *canvas, index, png ? &*png : nullptr, gif ? &*gif : nullptr, fps);
}

}  // namespace calder::app
