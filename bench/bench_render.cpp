// SPDX-License-Identifier: MIT
// Benchmarks of the renderer (calder/render.hpp): frames per second drawing
// example 2.7 and exercise 2.16 at 640 x 240 (scale 1) in the book's look.
//
//   Draw       Canvas::draw only
//   DrawPng    draw, then Canvas::encode_png (in memory, no disk)
//   DrawGif    draw, then GifWriter::add_frame (a file in the temp folder)
//   CairoFloor plain Cairo, no calder: the same background, the same number
//              of circles with the same style (and the attractor), same sizes
//
// The frames are the scene's first 600, simulated once beforehand: each
// iteration only moves the bodies to the next frame's positions, so the
// physics is not measured. items_per_second is frames per second.
#include <benchmark/benchmark.h>
#include <cairo.h>

#include <calder/calder.hpp>
#include <calder/render.hpp>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <variant>
#include <vector>

namespace {

constexpr int kFrames = 600;

// A scene's first kFrames frames, and a world to draw them with.
struct Recording {
  explicit Recording(const std::string& name) : sim(calder::builtin_scene(name), 1u) {
    style = calder::book_style(sim.scene());
    const std::size_t n = sim.world().body_count();
    for (int frame = 0; frame < kFrames; ++frame) {
      sim.step();
      for (std::size_t i = 0; i < n; ++i) {
        positions.push_back(sim.world().position(sim.world().body(i)));
      }
    }
  }
  // Moves the bodies to the positions of frame k (mod kFrames).
  void show(std::int64_t k) {
    const std::size_t n = sim.world().body_count();
    const std::size_t base = static_cast<std::size_t>(k % kFrames) * n;
    for (std::size_t i = 0; i < n; ++i) {
      sim.world().set_position(sim.world().body(i), positions[base + i]);
    }
  }

  calder::Simulation sim;
  calder::RenderStyle style;
  std::vector<calder::Vec2> positions;  // frame-major
};

Recording& recording(const std::string& name) {
  static Recording example_2_7("example-2.7");
  static Recording exercise_2_16("exercise-2.16");
  return name == "example-2.7" ? example_2_7 : exercise_2_16;
}

enum class Output { none, png, gif };

void run(benchmark::State& state, const std::string& scene, Output output) {
  Recording& r = recording(scene);
  calder::Canvas canvas(640, 240);
  std::unique_ptr<calder::GifWriter> gif;
  if (output == Output::gif) {
    // Never finished: the destructor removes the temporary file.
    gif = std::make_unique<calder::GifWriter>("/tmp/calder_bench_render.gif", 640, 240, 30.0);
  }
  std::int64_t frame = 0;
  std::size_t png_bytes = 0;
  for (auto _ : state) {
    r.show(frame);
    canvas.draw(r.sim.world(), r.sim.scene(), r.style, ++frame);
    if (output == Output::png) {
      const std::vector<unsigned char> png = canvas.encode_png();
      png_bytes += png.size();
      benchmark::DoNotOptimize(png.data());
    } else if (output == Output::gif) {
      gif->add_frame(canvas);
    }
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations());
  if (output == Output::png && state.iterations() > 0) {
    state.counters["png_kB"] =
        static_cast<double>(png_bytes) / static_cast<double>(state.iterations()) / 1000.0;
  }
  state.counters["bodies"] = static_cast<double>(r.sim.world().body_count());
}

// The floor: what Cairo alone takes to draw as many circles in the same style.
void cairo_floor(benchmark::State& state, const std::string& scene) {
  Recording& r = recording(scene);
  const calder::RenderStyle& s = r.style;
  const std::size_t n = r.sim.world().body_count();
  std::vector<double> radius(n);
  for (std::size_t i = 0; i < n; ++i) radius[i] = r.sim.world().radius(r.sim.world().body(i));
  std::vector<calder::Attractor> attractors;
  for (const calder::Field& f : r.sim.world().fields()) {
    if (const auto* a = std::get_if<calder::Attractor>(&f)) attractors.push_back(*a);
  }
  const calder::Vec2 origin = r.sim.scene().origin;
  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, 640, 240);
  cairo_t* cr = cairo_create(surface);
  const double pi = 3.14159265358979323846;
  std::int64_t frame = 0;
  for (auto _ : state) {
    const std::size_t base = static_cast<std::size_t>(frame % kFrames) * n;
    cairo_identity_matrix(cr);
    cairo_set_source_rgba(cr, 1, 1, 1, s.trails && frame > 0 ? s.trail_alpha : 1.0);
    cairo_paint(cr);
    cairo_translate(cr, origin.x, origin.y);
    for (const calder::Attractor& a : attractors) {
      cairo_arc(cr, a.position.x, a.position.y, a.mass, 0, 2 * pi);
      cairo_set_source_rgba(cr, s.attractor_fill.r, s.attractor_fill.g, s.attractor_fill.b,
                            s.attractor_fill.a);
      cairo_fill_preserve(cr);
      cairo_set_source_rgba(cr, 0, 0, 0, 1);
      cairo_set_line_width(cr, s.attractor_stroke_weight);
      cairo_stroke(cr);
    }
    cairo_set_line_width(cr, s.body_stroke_weight);
    for (std::size_t i = 0; i < n; ++i) {
      const calder::Vec2 p = r.positions[base + i];
      cairo_arc(cr, p.x, p.y, radius[i], 0, 2 * pi);
      cairo_set_source_rgba(cr, s.body_fill.r, s.body_fill.g, s.body_fill.b, s.body_fill.a);
      cairo_fill_preserve(cr);
      cairo_set_source_rgba(cr, 0, 0, 0, 1);
      cairo_stroke(cr);
    }
    cairo_surface_flush(surface);
    benchmark::DoNotOptimize(cairo_image_surface_get_data(surface));
    ++frame;
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["bodies"] = static_cast<double>(n);
  cairo_destroy(cr);
  cairo_surface_destroy(surface);
}

void register_all() {
  for (const char* scene : {"example-2.7", "exercise-2.16"}) {
    const std::string name = scene;
    benchmark::RegisterBenchmark(("Draw/" + name).c_str(), [name](benchmark::State& state) {
      run(state, name, Output::none);
    });
    benchmark::RegisterBenchmark(("DrawPng/" + name).c_str(), [name](benchmark::State& state) {
      run(state, name, Output::png);
    });
    benchmark::RegisterBenchmark(("DrawGif/" + name).c_str(), [name](benchmark::State& state) {
      run(state, name, Output::gif);
    });
    benchmark::RegisterBenchmark(("CairoFloor/" + name).c_str(),
                                 [name](benchmark::State& state) { cairo_floor(state, name); });
  }
}

}  // namespace

int main(int argc, char** argv) {
  register_all();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
