// SPDX-License-Identifier: MIT
#include "render_command.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "calder/diagnostics.hpp"
#include "calder/error.hpp"
#include "calder/trajectory.hpp"
#include "errors.hpp"
#include "output_policy.hpp"
#include "parse.hpp"
#include "progress.hpp"
#include "run_command.hpp"

namespace calder::app {

namespace {

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
  command.add_flag(
      "--hud", options.hud,
      "Show the frame, the body count, the total energy and its relative error since the start");
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

void start_hud(RenderStyle& style, const Simulation& simulation) {
  if (style.show_hud) style.hud_start_energy = start_energy(simulation);
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
  check_outputs({}, {{flag, path}});
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

// What render wrote, one line per output (null: not chosen); paths shown
// escaped, as in every message.
void report_written(std::ostream& out, const Canvas& canvas, std::int64_t frames,
                    const output::AtomicFolder* png, const GifWriter* gif, double fps) {
  const std::string what = std::to_string(frames) + (frames == 1 ? " frame" : " frames") + " of " +
                           size_text(canvas) + " pixels";
  if (png != nullptr) {
    out << "wrote " << png->name(0);
    if (png->count() > 1) out << " to " << png->name(png->count() - 1);
    out << " in " << shown_path(png->dir()) << " (" << what << ")\n";
  }
  if (gif != nullptr) {
    out << "wrote " << shown_path(gif->path()) << " (" << what << " at " << format_number(fps)
        << " fps)\n";
  }
}

// The work of the drawings: each image's HUD energy (bounded pairs) and
// force overlay (each field on each body), on top of the frames'.
WorkExtras render_work(const Simulation& simulation, const RenderStyle& style, std::int64_t frames,
                       std::int64_t every) {
  const World& world = simulation.world();
  const auto n = static_cast<double>(world.body_count());
  WorkExtras extras;
  extras.images = static_cast<double>(style.trails ? frames + 1 : frames / every + 1);
  extras.per_image = n;  // each body drawn
  if (style.show_hud) {
    extras.per_image += static_cast<double>(potential_energy_cost(world, kHudEnergyPairs));
  }
  if (style.show_forces) {
    extras.per_image += n * static_cast<double>(world.fields().size());
  }
  return extras;
}

// The inputs and outputs of a render, checked together (output_policy.hpp).
void check_render_outputs(const RenderOptions& options, const PreparedInput& input) {
  std::vector<NamedPath> inputs;
  struct stat info {};
  if (::stat(input.source.c_str(), &info) == 0) inputs.push_back({"the scene file", input.source});
  if (input.state_path) inputs.push_back({"--state", *input.state_path});
  std::vector<NamedPath> outputs;
  if (options.gif) outputs.push_back({"--gif", *options.gif});
  if (options.png) outputs.push_back({"--png", *options.png, output::Kind::folder});
  check_outputs(inputs, outputs);
}

}  // namespace

void render_command(const RenderOptions& options, std::ostream& out, std::ostream& err) {
  if (!options.png && !options.gif) {
    throw InputError("render: no output chosen: give --png DIR and/or --gif FILE");
  }
  const std::int64_t every = options.every ? parse_every(*options.every) : 1;
  const double fps = options.fps ? parse_fps(*options.fps) : 30.0;
  if (options.scale) (void)parse_scale("--scale", *options.scale);

  const PreparedInput input = prepare_input(options.input);
  const std::int64_t frames = input.scene.frames;
  check_render_frames(input, options, every);
  check_render_outputs(options, input);
  const CanvasSize size = canvas_size(options.size, options.scale, input.scene);
  RenderStyle style = make_style(input.scene, options.style);
  Simulation simulation = start_simulation(input);
  start_hud(style, simulation);
  check_world_work(input, simulation, render_work(simulation, style, frames, every));

  std::optional<Canvas> canvas;
  try {
    canvas.emplace(size.width, size.height, size.scale);
  } catch (const Error& e) {
    rethrow_with_context(e, "--size/--scale: ");
  }
  // From here on a terminating signal only sets a flag: the run stops at the
  // next frame and the destructors remove the GIF's temporary and the staged frames
  // (both registered with the output module's signal handler as they are made).
  const InterruptGuard interrupt;
  std::optional<GifWriter> gif;
  if (options.gif) gif.emplace(*options.gif, canvas->pixel_width(), canvas->pixel_height(), fps);
  std::optional<output::AtomicFolder> png;
  if (options.png)
    png.emplace("--png", *options.png, is_frame_png_name, "a PNG file of an earlier render");

  Progress progress(err, "render " + detail::printable(input.scene.name), frames,
                    !options.quiet && stderr_is_terminal());
  std::int64_t index = 0;
  const auto emit = [&]() {
    if (png) {
      std::vector<std::uint8_t> bytes;
      try {
        bytes = canvas->encode_png();
      } catch (const Error& e) {
        throw RunError("--png: " + std::string(e.what()));
      }
      png->write(frame_png_name(index), bytes);
    }
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
