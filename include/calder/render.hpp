// SPDX-License-Identifier: MIT
// calder: drawing a world the way the book's p5.js sketches do, and saving
// it as PNG images or an animated GIF.
//
//   calder::Simulation sim(calder::builtin_scene("example-2.7"), 1u);
//   calder::Canvas canvas(640, 240, 2.0);   // 1280 x 480 pixels, like the book's figures
//   const calder::RenderStyle style = calder::book_style(sim.scene());
//   calder::GifWriter gif("orbit.gif", canvas.pixel_width(), canvas.pixel_height(), 30);
//   for (int frame = 1; frame <= 300; ++frame) {
//     sim.step();
//     canvas.draw(sim.world(), sim.scene(), style, sim.frame());
//     gif.add_frame(canvas);
//   }
//   gif.finish();
//   canvas.write_png("last.png");
//
// One frame is drawn like a sketch's draw(): the background (or, with trails,
// the background at a low alpha over the previous frame, p5's
// background(255, 50)), the liquids, the attractors, then the bodies, each a
// circle of diameter radius * 2 with a 2 px black stroke and a translucent
// gray fill (p5's fill(127, 127)). Coordinates are canvas pixels; the
// canvas's scale multiplies everything (pixel density 2 draws a 640 x 240
// canvas into 1280 x 480 pixels, strokes included).
//
// Files are written atomically (a temporary file in the same folder, then a
// rename) with mode 0644; failures throw calder::Error naming the path and
// leave no file behind. Needs Cairo and giflib (the
// calder::render CMake target); the core library does not.
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "calder/diagnostics.hpp"  // displayed_energy, kHudEnergyPairs
#include "calder/scene.hpp"
#include "calder/vec2.hpp"
#include "calder/world.hpp"

namespace calder {

// A colour; components in [0, 1], not premultiplied by alpha.
struct Color {
  double r = 0.0;
  double g = 0.0;
  double b = 0.0;
  double a = 1.0;

  // p5's fill(v, alpha): 0..255.
  static constexpr Color gray(double v, double alpha = 255.0) {
    return {v / 255.0, v / 255.0, v / 255.0, alpha / 255.0};
  }
  // p5's fill(r, g, b, alpha): 0..255.
  static constexpr Color rgb(double r, double g, double b, double alpha = 255.0) {
    return {r / 255.0, g / 255.0, b / 255.0, alpha / 255.0};
  }
  // p5's noFill() / noStroke(): nothing is drawn.
  static constexpr Color none() { return {0.0, 0.0, 0.0, 0.0}; }

  friend constexpr bool operator==(const Color&, const Color&) = default;
};

// How a world is drawn. The defaults are the book's sketches (examples
// 2.1-2.9): background(255); bodies stroke(0), strokeWeight(2),
// fill(127, 127); the liquid noStroke(), fill(200); attractors
// strokeWeight(4), stroke(0), fill(175, 200), diameter mass * 2.
struct RenderStyle {
  Color background = Color::gray(255.0);
  // Instead of clearing, each frame paints the background with this alpha
  // over the last frame (p5's background(255, 50)), so old frames fade. The
  // first frame (and the first after Canvas::clear) paints it opaque. As in
  // the browser's 8-bit canvas, the fade stops short of the background: at
  // 253 for alpha 50/255, at 243 for 10/255, which leaves faint ghosts.
  bool trails = false;
  double trail_alpha = 50.0 / 255.0;  // in (0, 1]

  // Bodies: a circle of diameter radius * 2 (a radius-0 body: a dot as
  // wide as the stroke, in the stroke's colour).
  Color body_fill = Color::gray(127.0, 127.0);
  Color body_stroke = Color::gray(0.0);
  double body_stroke_weight = 2.0;
  // Bodies as squares of side radius * 2 (exercise 2.9's boxes).
  bool squares = false;

  // Liquid fields: their rectangle, and a line along its top (the book's
  // printed figure of example 2.5 draws only the line).
  Color liquid_fill = Color::gray(200.0);
  Color liquid_surface = Color::none();
  double liquid_surface_weight = 2.0;

  // Attractor fields: a circle of diameter mass * attractor_diameter_per_mass.
  Color attractor_fill = Color::gray(175.0, 200.0);
  Color attractor_stroke = Color::gray(0.0);
  double attractor_stroke_weight = 4.0;
  double attractor_diameter_per_mass = 2.0;
  // Mutual attraction's fixed central body (the galaxy's sun, which the
  // sketch does not draw): when shown, a body of radius sqrt(mass).
  bool show_central_body = false;

  // --- overlays, off by default ---
  // Each field's force on each body (force = accumulated acceleration * mass,
  // at the world's current state, so the forces of its next step; forces
  // applied by hand with apply_force are not included), the net force (their
  // sum) and a legend naming the fields by colour.
  bool show_forces = false;
  bool show_velocity = false;
  // One line of text (hud_text): frame, body count, total energy (with more
  // than kHudEnergyPairs pairs of mutual attraction, "~" and a sampled
  // estimate: calder::displayed_energy) and, when hud_start_energy is
  // finite and the energy exact, the relative energy error since then.
  bool show_hud = false;
  // The energy the HUD's error is measured from: calder::start_energy of
  // the run (calder render and window set it); NaN shows no error.
  double hud_start_energy = std::numeric_limits<double>::quiet_NaN();
  double force_scale = 100.0;   // canvas pixels per unit of force (the book's gravity 0.1: 10 px)
  double velocity_scale = 5.0;  // canvas pixels per pixel-per-frame of velocity
  double vector_weight = 1.5;
  Color net_force_color = Color::rgb(225.0, 87.0, 89.0);
  Color velocity_color = Color::rgb(89.0, 161.0, 79.0);
  // Field k's colour is field_colors[k % size()].
  std::vector<Color> field_colors = {
      Color::rgb(78.0, 121.0, 167.0),  Color::rgb(242.0, 142.0, 43.0),
      Color::rgb(176.0, 122.0, 161.0), Color::rgb(118.0, 183.0, 178.0),
      Color::rgb(237.0, 201.0, 72.0),  Color::rgb(156.0, 117.0, 95.0),
      Color::rgb(255.0, 157.0, 167.0), Color::rgb(186.0, 176.0, 172.0)};
  Color text_color = Color::gray(40.0);

  // Throws calder::Error naming the member for a colour component outside
  // [0, 1], a negative or non-finite weight or scale, trail_alpha outside
  // (0, 1], or an empty field_colors while show_forces is on.
  void validate() const;
};

// Which look of a built-in scene book_style gives.
enum class BookLook {
  // The p5.js sketch as it runs: a fresh background every frame, except the
  // galaxy (exercise 2.16), which fades with background(255, 50) (and whose
  // forces, should they be shown, are drawn at force_scale 2, velocity_scale 2).
  sketch,
  // The book's printed figures (chapter 2's printed figures): trails that
  // fade with background(255, 10) (2.4, 2.7 and the other examples) or
  // background(255, 20) (2.5, whose liquid is drawn as a line, unfilled);
  // the galaxy as in its sketch.
  figure,
};

// The look of a scene: its SceneLook (trails, trail alpha, body gray and
// alpha, squares), plus, for BookLook::figure, the printed figures' trails
// (and example 2.5's liquid drawn as a line). Fields a scene marks invisible
// are not drawn (Canvas::draw with the scene). The origin of the drawing is
// the scene's, given to Canvas::draw.
RenderStyle book_style(const Scene& scene, BookLook look = BookLook::sketch);

// How a shape is painted (p5's fill, stroke and strokeWeight): a fill of
// alpha 0 is noFill(), a stroke of alpha 0 or weight 0 is noStroke().
struct ShapeStyle {
  Color fill = Color::gray(255.0);
  Color stroke = Color::gray(0.0);
  double stroke_weight = 1.0;
};

// An affine map of canvas pixels (p5's translate, rotate and scale, composed):
// (x, y) goes to (xx x + xy y + x0, yx x + yy y + y0).
struct Transform {
  double xx = 1.0, yx = 0.0, xy = 0.0, yy = 1.0, x0 = 0.0, y0 = 0.0;

  // This map after a translation, a rotation (radians, clockwise on screen
  // as in p5) or a scaling in the mapped coordinates.
  [[nodiscard]] Transform translated(double dx, double dy) const;
  [[nodiscard]] Transform rotated(double angle) const;
  [[nodiscard]] Transform scaled(double sx, double sy) const;
  friend constexpr bool operator==(const Transform&, const Transform&) = default;
};

// An image of (width * scale) x (height * scale) pixels that frames are
// drawn into; Cairo's ARGB32 underneath. Starts fully transparent. Movable
// (a moved-from canvas may only be destroyed or assigned to), not copyable.
class Canvas {
 public:
  static constexpr int max_side = 8192;     // pixels a side, once scaled
  static constexpr double max_scale = 8.0;  // scale in (0, max_scale]

  // width and height in canvas pixels (the sketch's createCanvas), scale in
  // (0, 8] (p5's pixelDensity). Throws calder::Error unless each side is
  // 1..8192 pixels once scaled.
  Canvas(int width, int height, double scale = 1.0);
  ~Canvas();
  Canvas(Canvas&& other) noexcept;
  Canvas& operator=(Canvas&& other) noexcept;
  Canvas(const Canvas&) = delete;
  Canvas& operator=(const Canvas&) = delete;

  // Draws one frame of the world, translated by the scene's origin. With
  // style.trails, frames accumulate across calls until clear(). `frame` is
  // shown by the HUD only. Throws calder::Error for an invalid style (and
  // draws nothing); what a custom force throws while the forces are shown
  // passes through (the frame is then partly drawn).
  void draw(const World& world, const Scene& scene, const RenderStyle& style, std::int64_t frame);
  // The same without a scene: the physics origin at `origin` on the canvas.
  void draw(const World& world, const RenderStyle& style, std::int64_t frame, Vec2 origin = {});
  // Back to fully transparent; the next draw starts without trails.
  void clear();

  // --- shapes: p5's drawing vocabulary (calder::sketch draws with these) ---
  // Coordinates are canvas pixels mapped by the transform (set_transform),
  // then by the scale. A body that draw() paints and a circle() with the
  // same centre, diameter and style are the same Cairo path and stroke, so
  // the same pixels. Strokes have round caps (p5's strokeCap(ROUND)); rect
  // and triangle corners are mitred (p5's strokeJoin(MITER)). Throws
  // calder::Error for a non-finite coordinate or size (drawing nothing).
  //
  // p5's background(c): paints the whole canvas, ignoring the transform; an
  // alpha below 1 is painted over what is there (background(255, 50)).
  void background(const Color& color);
  void set_transform(const Transform& transform);
  [[nodiscard]] const Transform& transform() const;
  // circle(x, y, d) and ellipse(x, y, w, h): centred on (x, y).
  void circle(double x, double y, double diameter, const ShapeStyle& style);
  void ellipse(double x, double y, double w, double h, const ShapeStyle& style);
  // rect(x, y, w, h): (x, y) its top-left corner (p5's rectMode(CORNER)).
  void rect(double x, double y, double w, double h, const ShapeStyle& style);
  void triangle(double x1, double y1, double x2, double y2, double x3, double y3,
                const ShapeStyle& style);
  // line and point: the stroke only (point: a dot as wide as the stroke).
  void line(double x1, double y1, double x2, double y2, const ShapeStyle& style);
  void point(double x, double y, const ShapeStyle& style);
  // text(s, x, y): the baseline's left end at (x, y), in the fill colour,
  // sans-serif, `size` canvas pixels high (p5's textSize, 12 by default).
  void text(const std::string& words, double x, double y, double size, const ShapeStyle& style);

  [[nodiscard]] int width() const;   // canvas pixels
  [[nodiscard]] int height() const;  // canvas pixels
  [[nodiscard]] double scale() const;
  [[nodiscard]] int pixel_width() const;  // image pixels: round(width * scale)
  [[nodiscard]] int pixel_height() const;

  // The image as RGBA, 8 bits each, not premultiplied, rows top to bottom,
  // pixel_width() * 4 bytes a row (as the PNG holds it).
  [[nodiscard]] std::vector<std::uint8_t> rgba() const;
  // Cairo's pixels: a 32-bit native-endian word per pixel, alpha in the top
  // byte, colour premultiplied by alpha; stride() bytes a row. Valid until
  // the next draw or clear (e.g. for an SDL ARGB8888 texture upload).
  [[nodiscard]] const unsigned char* argb32_data() const;
  [[nodiscard]] int stride() const;

  // The image as a PNG file's bytes (RGBA, 8 bits).
  [[nodiscard]] std::vector<unsigned char> encode_png() const;
  // Writes the PNG atomically, mode 0644. Throws calder::Error naming the
  // path on failure, leaving no file (and any old file at path untouched).
  void write_png(const std::string& path) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// An animated, endlessly looping GIF (like p5's saveGif), written to a
// temporary file next to `path` and renamed to it by finish().
//
// Each frame gets its own palette: the exact colours when the frame (the
// part that changed since the last frame) has at most 256, as every
// gray-only scene does, with no dithering or rounding; otherwise 256
// colours chosen by calder's quantiser (Wu's cuts refined by k-means, no
// dithering: src/render/quantize.hpp). Transparent pixels are flattened onto white.
class GifWriter {
 public:
  // width x height pixels (a canvas's pixel_width() x pixel_height()), fps
  // in [0.01, 100]. Frame delays are in hundredths of a second, rounded so
  // that the animation keeps time on average (30 fps: 3, 4, 3, 3, 4, 3, ...),
  // and at least 2, since browsers slow shorter delays down to 10: above
  // 50 fps the GIF plays at 50. Throws calder::Error naming the path if the
  // file cannot be created.
  GifWriter(const std::string& path, int width, int height, double fps);
  // Without finish(), removes the temporary file; never throws.
  ~GifWriter();
  GifWriter(GifWriter&& other) noexcept;
  GifWriter& operator=(GifWriter&& other) noexcept;
  GifWriter(const GifWriter&) = delete;
  GifWriter& operator=(const GifWriter&) = delete;

  // Appends the canvas's current image; its pixel size must be the GIF's.
  void add_frame(const Canvas& canvas);
  // Writes the trailer and renames the file into place (mode 0644). Throws
  // calder::Error naming the path on failure (removing the temporary file);
  // calling it twice, or with no frame, throws.
  void finish();

  [[nodiscard]] int frame_count() const;
  [[nodiscard]] const std::string& path() const;
  // The temporary file written until finish() ("" when written directly).
  [[nodiscard]] const std::string& temp_path() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Frees what Cairo and fontconfig keep for the process's lifetime (text is
// drawn with Cairo's toy font API). Call it once at exit, when no Canvas is
// left, so leak checkers see a clean exit; drawing text afterwards is not
// allowed.
void release_render_caches();

// The HUD's line for frame `frame` of the world: "frame 42   bodies 3
// energy -20506.7   error 5.02e-11" (the error only as show_hud says).
[[nodiscard]] std::string hud_text(const World& world, const RenderStyle& style,
                                   std::int64_t frame);

// A folder of PNG frames (`calder render --png`, a sketch's `--png`): frame
// `index` is frame-000001.png (six or more digits), and a new run replaces
// only files of that name.
[[nodiscard]] std::string frame_png_name(std::int64_t index);
[[nodiscard]] bool is_frame_png_name(const std::string& name);

}  // namespace calder
