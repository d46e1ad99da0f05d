// SPDX-License-Identifier: MIT
// calder render: styles, and the look of the book's examples.
#include <cmath>
#include <string>

#include "calder/error.hpp"
#include "calder/render.hpp"

namespace calder {

namespace {

void require_color(const Color& c, const char* what) {
  const double parts[] = {c.r, c.g, c.b, c.a};
  for (double v : parts) {
    if (!(v >= 0.0 && v <= 1.0)) {  // NaN fails too
      throw Error(std::string("RenderStyle: ") + what + " must have components in [0, 1] (got " +
                  detail::format_number(c.r) + ", " + detail::format_number(c.g) + ", " +
                  detail::format_number(c.b) + ", " + detail::format_number(c.a) + ")");
    }
  }
}

void require_non_negative(double v, const char* what) {
  detail::require_non_negative(v, "RenderStyle", what);
}

}  // namespace

void RenderStyle::validate() const {
  require_color(background, "background");
  require_color(body_fill, "body_fill");
  require_color(body_stroke, "body_stroke");
  require_color(liquid_fill, "liquid_fill");
  require_color(liquid_surface, "liquid_surface");
  require_color(attractor_fill, "attractor_fill");
  require_color(attractor_stroke, "attractor_stroke");
  require_color(net_force_color, "net_force_color");
  require_color(velocity_color, "velocity_color");
  require_color(text_color, "text_color");
  for (const Color& c : field_colors) require_color(c, "field_colors");
  if (!(trail_alpha > 0.0 && trail_alpha <= 1.0)) {
    throw Error("RenderStyle: trail_alpha must be in (0, 1] (got " +
                detail::format_number(trail_alpha) + ")");
  }
  require_non_negative(body_stroke_weight, "body_stroke_weight");
  require_non_negative(liquid_surface_weight, "liquid_surface_weight");
  require_non_negative(attractor_stroke_weight, "attractor_stroke_weight");
  require_non_negative(attractor_diameter_per_mass, "attractor_diameter_per_mass");
  require_non_negative(vector_weight, "vector_weight");
  detail::require_finite(force_scale, "RenderStyle", "force_scale");
  detail::require_finite(velocity_scale, "RenderStyle", "velocity_scale");
  if (show_forces && field_colors.empty()) {
    throw Error("RenderStyle: field_colors must not be empty when show_forces is on");
  }
}

RenderStyle book_style(const Scene& scene, BookLook look) {
  RenderStyle style;
  const SceneLook& l = scene.look;
  style.trails = l.trails;
  style.trail_alpha = l.trail_alpha / 255.0;
  style.body_fill = Color::gray(l.body_gray, l.body_alpha);
  style.squares = l.squares;
  const std::string& name = scene.name;
  if (name == "exercise-2.16") {
    // The sun pulls with up to 500 * 15 / 100 = 75: shorter vectors.
    style.force_scale = 2.0;
    style.velocity_scale = 2.0;
    return style;  // its sketch is its figure: background(255, 50), fill(0, 100)
  }
  if (look == BookLook::figure && !l.trails) {
    // Measured on the figures: the fade stops at 243 (2.4, 2.7) and 249
    // (2.5), which 8-bit blending of background(255, a) gives for a = 10 and
    // a = 20; the bodies settle at 131 and 136, fill(127, 127) under those.
    style.trails = true;
    style.trail_alpha = 10.0 / 255.0;
    if (name == "example-2.5") {
      style.trail_alpha = 20.0 / 255.0;
      style.liquid_fill = Color::none();
      style.liquid_surface = Color::gray(0.0);
      style.liquid_surface_weight = 2.0;
    }
  }
  return style;
}

}  // namespace calder
