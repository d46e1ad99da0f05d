// SPDX-License-Identifier: MIT
// quantize_compare: the GIF writer's quantiser (src/render/quantize.hpp)
// against libimagequant and giflib's GifQuantizeBuffer on the coloured
// gallery frames. Each frame is rendered true-colour with calder::render
// (the scene's book look, plus the overlays named), quantised to 256
// colours by each, and compared with the true-colour frame:
//
//   PSNR     10 log10(255^2 / MSE), the MSE over the R, G and B channels
//   mean dE  the mean Euclidean RGB distance per pixel (0..441)
//   ms       the fastest of `repeats` runs (quantise and map every pixel)
//
//   quantize_compare [repeats]   (default 5)
//
// libimagequant (GPL-3+) is a measurement peer only: calder::render does not
// link it. Prints a Markdown table.
#include <gif_lib.h>
#include <libimagequant.h>

#include <algorithm>
#include <calder/calder.hpp>
#include <calder/render.hpp>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "../src/render/quantize.hpp"

namespace {

struct Frame {
  std::string label;
  int width = 0;
  int height = 0;
  std::vector<std::uint32_t> rgb;  // 0x00RRGGBB, flattened onto white
};

struct Shot {
  std::string label;
  std::string scene;
  int frames;
  calder::BookLook look;
  bool forces;
  bool velocity;
};

// The scene's frame `shot.frames` at seed 1, drawn as `calder render` does.
Frame render(const Shot& shot) {
  calder::Simulation sim(calder::builtin_scene(shot.scene), 1u);
  calder::RenderStyle style = calder::book_style(sim.scene(), shot.look);
  style.show_forces = shot.forces;
  style.show_velocity = shot.velocity;
  calder::Canvas canvas(static_cast<int>(sim.scene().world.width),
                        static_cast<int>(sim.scene().world.height));
  for (int frame = 1; frame <= shot.frames; ++frame) {
    sim.step();
    canvas.draw(sim.world(), sim.scene(), style, frame);
  }
  Frame out{shot.label, canvas.pixel_width(), canvas.pixel_height(), {}};
  const std::vector<std::uint8_t> rgba = canvas.rgba();
  for (std::size_t i = 0; i + 3 < rgba.size(); i += 4) {
    // Over white, as the GIF writer flattens (not premultiplied here).
    const std::uint32_t a = rgba[i + 3];
    std::uint32_t c = 0;
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t v = (rgba[i + k] * a + 255 * (255 - a) + 127) / 255;
      c = (c << 8) | v;
    }
    out.rgb.push_back(c);
  }
  return out;
}

struct Quantized {
  std::vector<std::uint32_t> palette;
  std::vector<std::uint8_t> indices;
};

Quantized ours(const Frame& f) {
  Quantized q;
  q.indices.resize(f.rgb.size());
  q.palette =
      calder::detail::quantize(f.rgb.data(), f.width, f.height, f.width, 256, q.indices.data());
  return q;
}

Quantized imagequant(const Frame& f, int speed, float dither) {
  std::vector<unsigned char> rgba;
  for (std::uint32_t c : f.rgb) {
    rgba.insert(rgba.end(),
                {static_cast<unsigned char>(c >> 16), static_cast<unsigned char>((c >> 8) & 0xff),
                 static_cast<unsigned char>(c & 0xff), 255});
  }
  liq_attr* attr = liq_attr_create();
  liq_set_max_colors(attr, 256);
  liq_set_speed(attr, speed);
  liq_image* image = liq_image_create_rgba(attr, rgba.data(), f.width, f.height, 0.0);
  liq_result* result = nullptr;
  if (liq_image_quantize(image, attr, &result) != LIQ_OK) throw std::runtime_error("liq failed");
  liq_set_dithering_level(result, dither);
  Quantized q;
  q.indices.resize(f.rgb.size());
  liq_write_remapped_image(result, image, q.indices.data(), q.indices.size());
  const liq_palette* palette = liq_get_palette(result);
  for (unsigned int i = 0; i < palette->count; ++i) {
    const liq_color& c = palette->entries[i];
    q.palette.push_back((std::uint32_t{c.r} << 16) | (std::uint32_t{c.g} << 8) | c.b);
  }
  liq_result_destroy(result);
  liq_image_destroy(image);
  liq_attr_destroy(attr);
  return q;
}

// giflib's median cut (its GifQuantizeBuffer, from the Utah Raster Toolkit).
Quantized giflib(const Frame& f) {
  std::vector<GifByteType> r, g, b;
  for (std::uint32_t c : f.rgb) {
    r.push_back(static_cast<GifByteType>(c >> 16));
    g.push_back(static_cast<GifByteType>((c >> 8) & 0xff));
    b.push_back(static_cast<GifByteType>(c & 0xff));
  }
  int size = 256;
  std::vector<GifColorType> map(256);
  Quantized q;
  q.indices.resize(f.rgb.size());
  if (GifQuantizeBuffer(static_cast<unsigned>(f.width), static_cast<unsigned>(f.height), &size,
                        r.data(), g.data(), b.data(), q.indices.data(), map.data()) == GIF_ERROR) {
    throw std::runtime_error("GifQuantizeBuffer failed");
  }
  for (int i = 0; i < size; ++i) {
    const GifColorType& c = map[static_cast<std::size_t>(i)];
    q.palette.push_back((std::uint32_t{c.Red} << 16) | (std::uint32_t{c.Green} << 8) | c.Blue);
  }
  return q;
}

struct Score {
  double psnr = 0.0;
  double mean_error = 0.0;
  double ms = 0.0;
};

Score score(const Frame& f, const std::function<Quantized(const Frame&)>& method, int repeats) {
  Score s;
  s.ms = 1e300;
  Quantized q;
  for (int k = 0; k < repeats; ++k) {
    const auto start = std::chrono::steady_clock::now();
    q = method(f);
    const auto end = std::chrono::steady_clock::now();
    s.ms = std::min(s.ms, std::chrono::duration<double, std::milli>(end - start).count());
  }
  double squared = 0.0;
  double distance = 0.0;
  for (std::size_t i = 0; i < f.rgb.size(); ++i) {
    const std::uint32_t p = q.palette.at(q.indices[i]);
    double d2 = 0.0;
    for (int shift : {16, 8, 0}) {
      const double d = static_cast<double>((f.rgb[i] >> shift) & 0xffu) -
                       static_cast<double>((p >> shift) & 0xffu);
      d2 += d * d;
    }
    squared += d2;
    distance += std::sqrt(d2);
  }
  const auto n = static_cast<double>(f.rgb.size());
  s.psnr = squared == 0.0 ? INFINITY : 10.0 * std::log10(255.0 * 255.0 / (squared / (n * 3)));
  s.mean_error = distance / n;
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  const std::vector<Shot> shots = {
      {"exercise-2.9 f120 --forces", "exercise-2.9", 120, calder::BookLook::sketch, true, false},
      {"example-2.7 f400 --figure --forces --velocity", "example-2.7", 400,
       calder::BookLook::figure, true, true},
      {"example-2.5 f90 --figure --forces", "example-2.5", 90, calder::BookLook::figure, true,
       false},
      {"exercise-2.16 f200 --forces", "exercise-2.16", 200, calder::BookLook::sketch, true, false},
  };
  struct Method {
    std::string name;
    std::function<Quantized(const Frame&)> run;
  };
  const std::vector<Method> methods = {
      {"calder (Wu + k-means)", ours},
      {"libimagequant speed 8, dither 1", [](const Frame& f) { return imagequant(f, 8, 1.0f); }},
      {"libimagequant speed 4, no dither", [](const Frame& f) { return imagequant(f, 4, 0.0f); }},
      {"giflib GifQuantizeBuffer", giflib},
  };
  std::printf("| frame (seed 1) | colours | quantiser | PSNR (dB) | mean dE | ms |\n");
  std::printf("|---|---:|---|---:|---:|---:|\n");
  for (const Shot& shot : shots) {
    const Frame f = render(shot);
    const std::size_t colours = std::set<std::uint32_t>(f.rgb.begin(), f.rgb.end()).size();
    for (const Method& m : methods) {
      const Score s = score(f, m.run, repeats);
      std::printf("| %s (%dx%d) | %zu | %s | %.2f | %.3f | %.1f |\n", shot.label.c_str(), f.width,
                  f.height, colours, m.name.c_str(), s.psnr, s.mean_error, s.ms);
    }
  }
  // Cairo's and fontconfig's caches, freed as the calder command frees them
  // (LeakSanitizer reports them otherwise).
  calder::release_render_caches();
}
