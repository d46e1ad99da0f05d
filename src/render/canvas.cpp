// SPDX-License-Identifier: MIT
// calder render: drawing a world into a Cairo image, and PNG output.
#include <cairo.h>
#include <dlfcn.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <deque>
#include <initializer_list>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include "../output/output.hpp"
#include "calder/diagnostics.hpp"
#include "calder/error.hpp"
#include "calder/fields.hpp"
#include "calder/render.hpp"

namespace calder {

namespace {

constexpr double kPi = 3.14159265358979323846;

void set_color(cairo_t* cr, const Color& c) { cairo_set_source_rgba(cr, c.r, c.g, c.b, c.a); }

bool visible(const Color& c) { return c.a > 0.0; }

// The part of the canvas a drawing can reach, in the world's coordinates.
struct View {
  double left, top, right, bottom;
};

// A path for a circle far larger than the view (radius over kHugeRadius
// view diagonals): the work of cairo_arc grows with the radius (a radius of
// 1e25 took seconds, 1e300 never ended), while over the view such an edge is
// straight to a tenth of a pixel (sagitta diagonal^2 / (8 radius)). Returns
// false when nothing of the disk or its edge reaches the view.
constexpr double kHugeRadius = 1e4;

bool huge_circle_path(cairo_t* cr, double x, double y, double radius, double margin,
                      const View& view) {
  const double cx = (view.left + view.right) / 2.0;
  const double cy = (view.top + view.bottom) / 2.0;
  const double half_diagonal = std::hypot(view.right - view.left, view.bottom - view.top) / 2.0;
  const double d = std::hypot(cx - x, cy - y);  // no overflow for huge coordinates
  const double inside = d - radius;             // < 0: the view's centre is in the disk
  if (inside > half_diagonal + margin) return false;
  const double reach = 2.0 * half_diagonal + margin;
  if (inside < -reach || !(d > 0.0)) {
    // The view lies wholly inside the disk.
    cairo_rectangle(cr, view.left - margin, view.top - margin, view.right - view.left + 2 * margin,
                    view.bottom - view.top + 2 * margin);
    return true;
  }
  // The edge crosses the view: the half-plane behind its tangent at the
  // point nearest the view's centre, clipped to a square around the view.
  const double nx = (cx - x) / d;
  const double ny = (cy - y) / d;
  const double ex = cx - nx * inside;  // the edge's point nearest the view's centre
  const double ey = cy - ny * inside;
  cairo_move_to(cr, ex - ny * reach, ey + nx * reach);
  cairo_line_to(cr, ex + ny * reach, ey - nx * reach);
  cairo_line_to(cr, ex + ny * reach - nx * 2 * reach, ey - nx * reach - ny * 2 * reach);
  cairo_line_to(cr, ex - ny * reach - nx * 2 * reach, ey + nx * reach - ny * 2 * reach);
  cairo_close_path(cr);
  return true;
}

// p5's circle(x, y, diameter) (or, with square, rectMode(CENTER) square of
// side 2 * radius) with the current fill and stroke.
void paint_circle(cairo_t* cr, double x, double y, double radius, const Color& fill,
                  const Color& stroke, double stroke_weight, const View& view,
                  bool square = false) {
  cairo_new_path(cr);
  const double diagonal = std::hypot(view.right - view.left, view.bottom - view.top);
  const double margin = stroke_weight + 1.0;
  if (radius > 0.0) {
    if (square) {
      // Clipped to the view: the same pixels, and no coordinates past Cairo's range.
      const double x0 = std::max(x - radius, view.left - margin);
      const double x1 = std::min(x + radius, view.right + margin);
      const double y0 = std::max(y - radius, view.top - margin);
      const double y1 = std::min(y + radius, view.bottom + margin);
      if (!(x1 >= x0 && y1 >= y0)) return;
      // The clipped sides are outside the view: their stroke isn't seen.
      cairo_rectangle(cr, x0, y0, x1 - x0, y1 - y0);
    } else if (radius > kHugeRadius * diagonal) {
      if (!huge_circle_path(cr, x, y, radius, margin, view)) return;
    } else {
      cairo_arc(cr, x, y, radius, 0.0, 2.0 * kPi);
    }
    if (visible(fill)) {
      set_color(cr, fill);
      cairo_fill_preserve(cr);
    }
    if (visible(stroke) && stroke_weight > 0.0) {
      set_color(cr, stroke);
      cairo_set_line_width(cr, stroke_weight);
      cairo_stroke_preserve(cr);
    }
  } else if (visible(stroke) && stroke_weight > 0.0) {
    // A point body: p5's point(), a dot as wide as the stroke.
    if (stroke_weight / 2.0 > kHugeRadius * diagonal) {
      if (!huge_circle_path(cr, x, y, stroke_weight / 2.0, 1.0, view)) return;
    } else {
      cairo_arc(cr, x, y, stroke_weight / 2.0, 0.0, 2.0 * kPi);
    }
    set_color(cr, stroke);
    cairo_fill_preserve(cr);
  }
  cairo_new_path(cr);
}

// An arrow from (x, y) along (dx, dy), in the current colour.
void arrow(cairo_t* cr, double x, double y, double dx, double dy, double weight,
           double max_length) {
  double length = std::sqrt(dx * dx + dy * dy);
  if (!(length >= 0.5) || weight <= 0.0) return;  // too short to see (or not finite)
  if (length > max_length) {                      // keep Cairo's fixed-point coordinates in range
    dx *= max_length / length;
    dy *= max_length / length;
    length = max_length;
  }
  const double head = std::min(3.0 + 2.0 * weight, 0.4 * length);
  const double ux = dx / length;
  const double uy = dy / length;
  const double tip_x = x + dx;
  const double tip_y = y + dy;
  cairo_new_path(cr);
  cairo_set_line_width(cr, weight);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  cairo_move_to(cr, x, y);
  cairo_line_to(cr, tip_x - ux * head * 0.8, tip_y - uy * head * 0.8);
  cairo_stroke(cr);
  // Head: a triangle 2 * 0.45 * head wide at its base.
  cairo_move_to(cr, tip_x, tip_y);
  cairo_line_to(cr, tip_x - ux * head - uy * head * 0.45, tip_y - uy * head + ux * head * 0.45);
  cairo_line_to(cr, tip_x - ux * head + uy * head * 0.45, tip_y - uy * head - ux * head * 0.45);
  cairo_close_path(cr);
  cairo_fill(cr);
}

std::string format_short(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", v);
  return buffer;
}

// Labels for the legend: the field's name, numbered when it repeats.
std::vector<std::string> field_labels(const std::deque<Field>& fields) {
  std::vector<std::string> labels;
  for (const Field& f : fields) labels.emplace_back(field_name(f));
  for (std::size_t i = 0; i < labels.size(); ++i) {
    const std::string name = field_name(fields[i]);
    const auto same = std::count_if(fields.begin(), fields.end(),
                                    [&](const Field& f) { return name == field_name(f); });
    if (same > 1) {
      const auto nth =
          std::count_if(fields.begin(), fields.begin() + static_cast<std::ptrdiff_t>(i),
                        [&](const Field& f) { return name == field_name(f); });
      labels[i] += ' ';
      labels[i] += std::to_string(nth + 1);
    }
  }
  return labels;
}

struct LegendEntry {
  std::string label;
  Color color;
};

// A box of text lines at canvas (x, y) (top-left corner), or anchored at its
// bottom-left corner when `from_bottom`.
void text_box(cairo_t* cr, double x, double y, bool from_bottom,
              const std::vector<LegendEntry>& entries, bool swatches, const Color& text) {
  if (entries.empty()) return;
  constexpr double font = 10.0;
  constexpr double line = 13.0;
  constexpr double pad = 4.0;
  constexpr double swatch = 14.0;
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, font);
  double text_width = 0.0;
  for (const LegendEntry& e : entries) {
    cairo_text_extents_t extents;
    cairo_text_extents(cr, e.label.c_str(), &extents);
    text_width = std::max(text_width, extents.x_advance);
  }
  const double left = swatches ? swatch + 4.0 : 0.0;
  const double w = pad * 2.0 + left + text_width;
  const double h = pad * 2.0 + line * static_cast<double>(entries.size()) - (line - font) + 2.0;
  const double top = from_bottom ? y - h : y;
  cairo_new_path(cr);
  cairo_rectangle(cr, x, top, w, h);
  cairo_set_source_rgba(cr, 1.0, 1.0, 1.0, 0.85);
  cairo_fill_preserve(cr);
  cairo_set_source_rgba(cr, 0.0, 0.0, 0.0, 0.3);
  cairo_set_line_width(cr, 0.5);
  cairo_stroke(cr);
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const double baseline = top + pad + font + line * static_cast<double>(i) - 1.0;
    if (swatches) {
      set_color(cr, entries[i].color);
      cairo_set_line_width(cr, 2.0);
      cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);
      cairo_move_to(cr, x + pad, baseline - font * 0.35);
      cairo_line_to(cr, x + pad + swatch, baseline - font * 0.35);
      cairo_stroke(cr);
    }
    set_color(cr, text);
    cairo_move_to(cr, x + pad + left, baseline);
    cairo_show_text(cr, entries[i].label.c_str());
    cairo_new_path(cr);
  }
}

// Unpremultiplies one channel as Cairo's PNG writer does.
std::uint8_t unpremultiply(std::uint32_t c, std::uint32_t a) {
  return static_cast<std::uint8_t>((c * 255u + a / 2u) / a);
}

struct PngSink {
  output::AtomicFile* file = nullptr;
  std::vector<unsigned char>* bytes = nullptr;
  int error = 0;
};

cairo_status_t write_png_bytes(void* closure, const unsigned char* data, unsigned int length) {
  auto* sink = static_cast<PngSink*>(closure);
  if (sink->bytes != nullptr) {
    sink->bytes->insert(sink->bytes->end(), data, data + length);
    return CAIRO_STATUS_SUCCESS;
  }
  const int fd = sink->file->fd();
  std::size_t left = length;
  while (left > 0) {
    const ssize_t n = ::write(fd, data, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      sink->error = errno;
      return CAIRO_STATUS_WRITE_ERROR;
    }
    data += n;
    left -= static_cast<std::size_t>(n);
  }
  return CAIRO_STATUS_SUCCESS;
}

}  // namespace

struct Canvas::Impl {
  cairo_surface_t* surface = nullptr;
  cairo_t* cr = nullptr;
  int width = 0;
  int height = 0;
  double scale = 1.0;
  int pixel_width = 0;
  int pixel_height = 0;
  bool fresh = true;    // nothing drawn since construction or clear()
  Transform transform;  // the shapes' (set_transform)
  // Per-field forces, field-major: force_x[k * n + i].
  std::vector<double> force_x, force_y, ax, ay;

  ~Impl() {
    if (cr != nullptr) cairo_destroy(cr);
    if (surface != nullptr) cairo_surface_destroy(surface);
  }

  void draw(const World& world, const RenderStyle& style, std::int64_t frame, Vec2 origin,
            const Scene* scene);
  void draw_fields(const World& world, const Scene* scene, const RenderStyle& style, double left,
                   double top, double right, double bottom);
  void draw_bodies(const World& world, const RenderStyle& style, double left, double top,
                   double right, double bottom);
  void draw_vectors(const World& world, const RenderStyle& style);
  void draw_text(const World& world, const RenderStyle& style, std::int64_t frame);
  // Sets up Cairo for one shape call (scale, then the transform; round caps,
  // the given join) and returns the canvas's extent in the shape's
  // coordinates; end_shape() puts Cairo back.
  View begin_shape(cairo_line_join_t join);
  void end_shape();
};

Canvas::Canvas(int width, int height, double scale) : impl_(std::make_unique<Impl>()) {
  if (!(std::isfinite(scale) && scale > 0.0 && scale <= max_scale)) {
    throw Error("Canvas: scale must be in (0, " + detail::format_number(max_scale) + "] (got " +
                detail::format_number(scale) + ")");
  }
  const double pw = std::round(static_cast<double>(width) * scale);
  const double ph = std::round(static_cast<double>(height) * scale);
  if (width < 1 || height < 1 || pw < 1.0 || ph < 1.0 || pw > max_side || ph > max_side) {
    throw Error("Canvas: size must be 1.." + std::to_string(max_side) +
                " pixels a side once scaled (got " + std::to_string(width) + " x " +
                std::to_string(height) + " at scale " + detail::format_number(scale) + ")");
  }
  Impl& d = *impl_;
  d.width = width;
  d.height = height;
  d.scale = scale;
  d.pixel_width = static_cast<int>(pw);
  d.pixel_height = static_cast<int>(ph);
  d.surface = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, d.pixel_width, d.pixel_height);
  if (cairo_surface_status(d.surface) != CAIRO_STATUS_SUCCESS) {
    throw Error(std::string("Canvas: cannot create the image: ") +
                cairo_status_to_string(cairo_surface_status(d.surface)));
  }
  d.cr = cairo_create(d.surface);
  if (cairo_status(d.cr) != CAIRO_STATUS_SUCCESS) {
    throw Error(std::string("Canvas: cannot draw: ") + cairo_status_to_string(cairo_status(d.cr)));
  }
}

Canvas::~Canvas() = default;
Canvas::Canvas(Canvas&& other) noexcept = default;
Canvas& Canvas::operator=(Canvas&& other) noexcept = default;

int Canvas::width() const { return impl_->width; }
int Canvas::height() const { return impl_->height; }
double Canvas::scale() const { return impl_->scale; }
int Canvas::pixel_width() const { return impl_->pixel_width; }
int Canvas::pixel_height() const { return impl_->pixel_height; }
int Canvas::stride() const { return cairo_image_surface_get_stride(impl_->surface); }
const unsigned char* Canvas::argb32_data() const {
  return cairo_image_surface_get_data(impl_->surface);
}

void Canvas::clear() {
  cairo_t* cr = impl_->cr;
  cairo_save(cr);
  cairo_set_operator(cr, CAIRO_OPERATOR_CLEAR);
  cairo_paint(cr);
  cairo_restore(cr);
  cairo_surface_flush(impl_->surface);
  impl_->fresh = true;
}

void Canvas::draw(const World& world, const Scene& scene, const RenderStyle& style,
                  std::int64_t frame) {
  style.validate();
  detail::require_finite(scene.origin.x, "Canvas::draw", "origin.x");
  detail::require_finite(scene.origin.y, "Canvas::draw", "origin.y");
  impl_->draw(world, style, frame, scene.origin, &scene);
}

void Canvas::draw(const World& world, const RenderStyle& style, std::int64_t frame, Vec2 origin) {
  style.validate();
  detail::require_finite(origin.x, "Canvas::draw", "origin.x");
  detail::require_finite(origin.y, "Canvas::draw", "origin.y");
  impl_->draw(world, style, frame, origin, nullptr);
}

void Canvas::Impl::draw(const World& world, const RenderStyle& style, std::int64_t frame,
                        Vec2 origin, const Scene* scene) {
  // Restores Cairo's state even when a field (a custom force) throws midway.
  struct Restore {
    cairo_t* cr;
    cairo_surface_t* surface;
    ~Restore() {
      cairo_restore(cr);
      cairo_surface_flush(surface);
    }
  };
  cairo_save(cr);
  const Restore restore{cr, surface};
  cairo_identity_matrix(cr);
  // The background: p5's background(c), or background(c, alpha) for trails.
  const Color& bg = style.background;
  if (!style.trails || fresh) {
    cairo_set_operator(cr, CAIRO_OPERATOR_SOURCE);
    set_color(cr, bg);
  } else {
    cairo_set_operator(cr, CAIRO_OPERATOR_OVER);
    cairo_set_source_rgba(cr, bg.r, bg.g, bg.b, bg.a * style.trail_alpha);
  }
  cairo_paint(cr);
  cairo_set_operator(cr, CAIRO_OPERATOR_OVER);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);

  cairo_scale(cr, scale, scale);
  cairo_matrix_t canvas_matrix;
  cairo_get_matrix(cr, &canvas_matrix);
  cairo_translate(cr, origin.x, origin.y);
  // The canvas in physics coordinates, for culling what can't be seen.
  const double left = -origin.x;
  const double top = -origin.y;
  const double right = left + width;
  const double bottom = top + height;

  draw_fields(world, scene, style, left, top, right, bottom);
  draw_bodies(world, style, left, top, right, bottom);
  if (style.show_forces || style.show_velocity) draw_vectors(world, style);

  cairo_set_matrix(cr, &canvas_matrix);
  draw_text(world, style, frame);
  fresh = false;
}

void Canvas::Impl::draw_fields(const World& world, const Scene* scene, const RenderStyle& style,
                               double left, double top, double right, double bottom) {
  for (std::size_t k = 0; k < world.fields().size(); ++k) {
    // A scene may hide a field (exercise 2.12's invisible attractors).
    if (scene != nullptr && k < scene->fields.size() && !scene->fields[k].visible) continue;
    const Field& field = world.fields()[k];
    if (const auto* liquid = std::get_if<Liquid>(&field)) {
      if (!liquid->enabled) continue;
      // p5: noStroke(); fill(200); rect(x, y, w, h), clipped to the canvas
      // (with a margin) so that a huge region stays within Cairo's range.
      const Rect& r = liquid->region;
      const double margin = 10.0 + style.liquid_surface_weight;
      const double x0 = std::max(r.x, left - margin);
      const double x1 = std::min(r.x + r.w, right + margin);
      const double y0 = std::max(r.y, top - margin);
      const double y1 = std::min(r.y + r.h, bottom + margin);
      if (x1 <= x0 || y1 < y0) continue;
      if (visible(style.liquid_fill) && y1 > y0) {
        cairo_new_path(cr);
        cairo_rectangle(cr, x0, y0, x1 - x0, y1 - y0);
        set_color(cr, style.liquid_fill);
        cairo_fill(cr);
      }
      if (visible(style.liquid_surface) && style.liquid_surface_weight > 0.0 &&
          r.y >= top - margin && r.y <= bottom + margin) {
        cairo_new_path(cr);
        cairo_move_to(cr, x0, r.y);
        cairo_line_to(cr, x1, r.y);
        set_color(cr, style.liquid_surface);
        cairo_set_line_width(cr, style.liquid_surface_weight);
        cairo_stroke(cr);
      }
    } else if (const auto* attractor = std::get_if<Attractor>(&field)) {
      if (!attractor->enabled) continue;
      const double radius = attractor->mass * style.attractor_diameter_per_mass / 2.0;
      const double reach = radius + style.attractor_stroke_weight;
      const Vec2 p = attractor->position;
      if (p.x + reach < left || p.x - reach > right || p.y + reach < top || p.y - reach > bottom) {
        continue;
      }
      paint_circle(cr, p.x, p.y, radius, style.attractor_fill, style.attractor_stroke,
                   style.attractor_stroke_weight, {left, top, right, bottom});
    } else if (const auto* mutual = std::get_if<MutualAttraction>(&field)) {
      if (!mutual->enabled || !mutual->central || !style.show_central_body) continue;
      const Vec2 p = mutual->central->position;
      const double radius = std::sqrt(mutual->central->mass);
      const double reach = radius + style.body_stroke_weight;
      if (p.x + reach < left || p.x - reach > right || p.y + reach < top || p.y - reach > bottom) {
        continue;
      }
      paint_circle(cr, p.x, p.y, radius, style.body_fill, style.body_stroke,
                   style.body_stroke_weight, {left, top, right, bottom});
    }
  }
}

void Canvas::Impl::draw_bodies(const World& world, const RenderStyle& style, double left,
                               double top, double right, double bottom) {
  const BodyView bodies = world.bodies();
  const double stroke = style.body_stroke_weight;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const double x = bodies.x[i];
    const double y = bodies.y[i];
    const double r = bodies.radius[i];
    const double reach = r + stroke;
    if (x + reach < left || x - reach > right || y + reach < top || y - reach > bottom) continue;
    paint_circle(cr, x, y, r, style.body_fill, style.body_stroke, stroke,
                 {left, top, right, bottom}, style.squares);
  }
}

void Canvas::Impl::draw_vectors(const World& world, const RenderStyle& style) {
  const BodyView bodies = world.bodies();
  const std::size_t n = bodies.size();
  const double max_length = 4.0 * (width + height);
  if (style.show_forces) {
    const std::size_t k_count = world.fields().size();
    force_x.assign(k_count * n, 0.0);
    force_y.assign(k_count * n, 0.0);
    const FieldContext context{bodies,        world.time(),   world.dt(),
                               world.width(), world.height(), &world.noise()};
    for (std::size_t k = 0; k < k_count; ++k) {
      ax.assign(n, 0.0);
      ay.assign(n, 0.0);
      accumulate(world.fields()[k], context, 0, n, std::span<double>(ax), std::span<double>(ay));
      for (std::size_t i = 0; i < n; ++i) {
        force_x[k * n + i] = ax[i] * bodies.mass[i];
        force_y[k * n + i] = ay[i] * bodies.mass[i];
      }
    }
    // The net force first and wider, each field's on top of it: a body
    // under one field shows that field's colour edged with the net's.
    set_color(cr, style.net_force_color);
    for (std::size_t i = 0; i < n; ++i) {
      double fx = 0.0;
      double fy = 0.0;
      for (std::size_t k = 0; k < k_count; ++k) {
        fx += force_x[k * n + i];
        fy += force_y[k * n + i];
      }
      arrow(cr, bodies.x[i], bodies.y[i], fx * style.force_scale, fy * style.force_scale,
            style.vector_weight * 2.0, max_length);
    }
    for (std::size_t k = 0; k < k_count; ++k) {
      set_color(cr, style.field_colors[k % style.field_colors.size()]);
      for (std::size_t i = 0; i < n; ++i) {
        arrow(cr, bodies.x[i], bodies.y[i], force_x[k * n + i] * style.force_scale,
              force_y[k * n + i] * style.force_scale, style.vector_weight, max_length);
      }
    }
  }
  if (style.show_velocity) {
    set_color(cr, style.velocity_color);
    for (std::size_t i = 0; i < n; ++i) {
      arrow(cr, bodies.x[i], bodies.y[i], bodies.vx[i] * style.velocity_scale,
            bodies.vy[i] * style.velocity_scale, style.vector_weight, max_length);
    }
  }
}

void Canvas::Impl::draw_text(const World& world, const RenderStyle& style, std::int64_t frame) {
  if (style.show_forces || style.show_velocity) {
    std::vector<LegendEntry> legend;
    if (style.show_forces) {
      legend.push_back({"net force", style.net_force_color});
      const std::vector<std::string> labels = field_labels(world.fields());
      for (std::size_t k = 0; k < labels.size(); ++k) {
        legend.push_back({labels[k], style.field_colors[k % style.field_colors.size()]});
      }
    }
    if (style.show_velocity) legend.push_back({"velocity", style.velocity_color});
    text_box(cr, 6.0, 6.0, false, legend, true, style.text_color);
  }
  if (style.show_hud) {
    text_box(cr, 6.0, height - 6.0, true, {{hud_text(world, style, frame), style.text_color}},
             false, style.text_color);
  }
}

std::string hud_text(const World& world, const RenderStyle& style, std::int64_t frame) {
  // Bounded per frame: past kHudEnergyPairs pairs the potential is a
  // sampled estimate, shown with a leading '~' and no error (a sample can't
  // show one of 1e-6).
  const DisplayedEnergy e = displayed_energy(world);
  std::string line =
      "frame " + std::to_string(frame) + "   bodies " + std::to_string(world.body_count());
  if (!e.has_potential) return line + "   energy n/a";  // a custom attraction law
  line +=
      "   energy " + (e.exact() ? std::string() : std::string(1, '~')) + format_short(e.total());
  if (e.exact() && std::isfinite(style.hud_start_energy)) {
    line += "   error " + format_short(relative_energy_error(style.hud_start_energy, e.total()));
  }
  return line;
}

// --- shapes --------------------------------------------------------------------

namespace {

void require_finite_all(const char* who, std::initializer_list<double> values) {
  for (const double v : values) {
    if (!std::isfinite(v)) {
      throw Error(std::string("Canvas::") + who + ": coordinates and sizes must be finite (got " +
                  detail::format_number(v) + ")");
    }
  }
}

// Fills and strokes the current path with a shape style, then clears it.
void paint_path(cairo_t* cr, const ShapeStyle& style) {
  if (visible(style.fill)) {
    set_color(cr, style.fill);
    cairo_fill_preserve(cr);
  }
  if (visible(style.stroke) && style.stroke_weight > 0.0) {
    set_color(cr, style.stroke);
    cairo_set_line_width(cr, style.stroke_weight);
    cairo_stroke_preserve(cr);
  }
  cairo_new_path(cr);
}

}  // namespace

Transform Transform::translated(double dx, double dy) const {
  Transform t = *this;
  t.x0 += xx * dx + xy * dy;
  t.y0 += yx * dx + yy * dy;
  return t;
}

Transform Transform::rotated(double angle) const {
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  Transform t = *this;
  t.xx = xx * c + xy * s;
  t.yx = yx * c + yy * s;
  t.xy = xy * c - xx * s;
  t.yy = yy * c - yx * s;
  return t;
}

Transform Transform::scaled(double sx, double sy) const {
  Transform t = *this;
  t.xx *= sx;
  t.yx *= sx;
  t.xy *= sy;
  t.yy *= sy;
  return t;
}

View Canvas::Impl::begin_shape(cairo_line_join_t join) {
  cairo_save(cr);
  cairo_identity_matrix(cr);
  cairo_set_operator(cr, CAIRO_OPERATOR_OVER);
  cairo_set_line_join(cr, join);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  cairo_scale(cr, scale, scale);
  const Transform& t = transform;
  if (t != Transform{}) {
    cairo_matrix_t m;
    cairo_matrix_init(&m, t.xx, t.yx, t.xy, t.yy, t.x0, t.y0);
    cairo_transform(cr, &m);
  }
  View view{};
  cairo_clip_extents(cr, &view.left, &view.top, &view.right, &view.bottom);
  fresh = false;
  return view;
}

void Canvas::Impl::end_shape() {
  cairo_restore(cr);
  cairo_surface_flush(surface);
}

void Canvas::background(const Color& color) {
  Impl& d = *impl_;
  cairo_save(d.cr);
  cairo_identity_matrix(d.cr);
  // Opaque: replaces what is there, as draw() does; translucent: over it.
  cairo_set_operator(d.cr, color.a >= 1.0 ? CAIRO_OPERATOR_SOURCE : CAIRO_OPERATOR_OVER);
  set_color(d.cr, color);
  cairo_paint(d.cr);
  cairo_restore(d.cr);
  cairo_surface_flush(d.surface);
  d.fresh = false;
}

void Canvas::set_transform(const Transform& t) {
  require_finite_all("set_transform", {t.xx, t.yx, t.xy, t.yy, t.x0, t.y0});
  impl_->transform = t;
}

const Transform& Canvas::transform() const { return impl_->transform; }

void Canvas::circle(double x, double y, double diameter, const ShapeStyle& style) {
  require_finite_all("circle", {x, y, diameter, style.stroke_weight});
  const View view = impl_->begin_shape(CAIRO_LINE_JOIN_ROUND);
  // The bodies' own path and paint (draw_bodies), so the same pixels.
  paint_circle(impl_->cr, x, y, std::abs(diameter) / 2.0, style.fill, style.stroke,
               style.stroke_weight, view);
  impl_->end_shape();
}

void Canvas::ellipse(double x, double y, double w, double h, const ShapeStyle& style) {
  require_finite_all("ellipse", {x, y, w, h, style.stroke_weight});
  if (std::abs(w) == std::abs(h)) {
    circle(x, y, w, style);
    return;
  }
  cairo_t* cr = impl_->cr;
  impl_->begin_shape(CAIRO_LINE_JOIN_ROUND);
  if (w != 0.0 && h != 0.0) {
    cairo_save(cr);
    cairo_translate(cr, x, y);
    cairo_scale(cr, std::abs(w) / 2.0, std::abs(h) / 2.0);
    cairo_arc(cr, 0.0, 0.0, 1.0, 0.0, 2.0 * kPi);
    cairo_restore(cr);  // the path stays; the stroke is not scaled
    paint_path(cr, style);
  }
  impl_->end_shape();
}

void Canvas::rect(double x, double y, double w, double h, const ShapeStyle& style) {
  require_finite_all("rect", {x, y, w, h, style.stroke_weight});
  cairo_t* cr = impl_->cr;
  impl_->begin_shape(CAIRO_LINE_JOIN_MITER);
  cairo_rectangle(cr, x, y, w, h);
  paint_path(cr, style);
  impl_->end_shape();
}

void Canvas::triangle(double x1, double y1, double x2, double y2, double x3, double y3,
                      const ShapeStyle& style) {
  require_finite_all("triangle", {x1, y1, x2, y2, x3, y3, style.stroke_weight});
  cairo_t* cr = impl_->cr;
  impl_->begin_shape(CAIRO_LINE_JOIN_MITER);
  cairo_move_to(cr, x1, y1);
  cairo_line_to(cr, x2, y2);
  cairo_line_to(cr, x3, y3);
  cairo_close_path(cr);
  paint_path(cr, style);
  impl_->end_shape();
}

void Canvas::line(double x1, double y1, double x2, double y2, const ShapeStyle& style) {
  require_finite_all("line", {x1, y1, x2, y2, style.stroke_weight});
  cairo_t* cr = impl_->cr;
  impl_->begin_shape(CAIRO_LINE_JOIN_ROUND);
  cairo_move_to(cr, x1, y1);
  cairo_line_to(cr, x2, y2);
  paint_path(cr, ShapeStyle{Color::none(), style.stroke, style.stroke_weight});
  impl_->end_shape();
}

void Canvas::point(double x, double y, const ShapeStyle& style) {
  require_finite_all("point", {x, y, style.stroke_weight});
  const View view = impl_->begin_shape(CAIRO_LINE_JOIN_ROUND);
  // A radius-0 body's dot (draw_bodies), so the same pixels.
  paint_circle(impl_->cr, x, y, 0.0, Color::none(), style.stroke, style.stroke_weight, view);
  impl_->end_shape();
}

void Canvas::text(const std::string& words, double x, double y, double size,
                  const ShapeStyle& style) {
  require_finite_all("text", {x, y, size});
  if (!visible(style.fill) || !(size > 0.0)) return;
  cairo_t* cr = impl_->cr;
  impl_->begin_shape(CAIRO_LINE_JOIN_ROUND);
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size);
  set_color(cr, style.fill);
  cairo_move_to(cr, x, y);
  cairo_show_text(cr, words.c_str());
  cairo_new_path(cr);
  impl_->end_shape();
}

std::vector<std::uint8_t> Canvas::rgba() const {
  const int w = impl_->pixel_width;
  const int h = impl_->pixel_height;
  const int s = stride();
  const unsigned char* data = argb32_data();
  std::vector<std::uint8_t> out(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 4u);
  std::size_t o = 0;
  for (int y = 0; y < h; ++y) {
    const unsigned char* row = data + static_cast<std::ptrdiff_t>(y) * s;
    for (int x = 0; x < w; ++x) {
      std::uint32_t p;
      std::memcpy(&p, row + static_cast<std::ptrdiff_t>(x) * 4, sizeof p);
      const std::uint32_t a = p >> 24;
      std::uint32_t r = (p >> 16) & 0xffu;
      std::uint32_t g = (p >> 8) & 0xffu;
      std::uint32_t b = p & 0xffu;
      if (a == 0) {
        r = g = b = 0;
      } else if (a != 255) {
        r = unpremultiply(r, a);
        g = unpremultiply(g, a);
        b = unpremultiply(b, a);
      }
      out[o++] = static_cast<std::uint8_t>(r);
      out[o++] = static_cast<std::uint8_t>(g);
      out[o++] = static_cast<std::uint8_t>(b);
      out[o++] = static_cast<std::uint8_t>(a);
    }
  }
  return out;
}

std::vector<unsigned char> Canvas::encode_png() const {
  std::vector<unsigned char> bytes;
  PngSink sink{nullptr, &bytes, 0};
  const cairo_status_t status =
      cairo_surface_write_to_png_stream(impl_->surface, write_png_bytes, &sink);
  if (status != CAIRO_STATUS_SUCCESS) {
    throw Error(std::string("Canvas::encode_png: ") + cairo_status_to_string(status));
  }
  return bytes;
}

std::string frame_png_name(std::int64_t index) {
  char name[32];
  std::snprintf(name, sizeof name, "frame-%06lld.png", static_cast<long long>(index));
  return name;
}

bool is_frame_png_name(const std::string& name) {
  if (!name.starts_with("frame-") || !name.ends_with(".png")) return false;
  const std::string digits = name.substr(6, name.size() - 10);
  if (digits.size() < 6) return false;
  return std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; });
}

void Canvas::write_png(const std::string& path) const {
  output::AtomicFile file("Canvas::write_png", path);
  PngSink sink{&file, nullptr, 0};
  const cairo_status_t status =
      cairo_surface_write_to_png_stream(impl_->surface, write_png_bytes, &sink);
  if (status != CAIRO_STATUS_SUCCESS) {
    file.discard();
    if (sink.error != 0) file.fail("write", sink.error);
    throw Error("Canvas::write_png: cannot write '" + path +
                "': " + cairo_status_to_string(status));
  }
  file.commit();
}

void release_render_caches() {
  cairo_debug_reset_static_data();
  // fontconfig is Cairo's dependency, not ours: look FcFini up at run time.
  if (void* fini = ::dlsym(RTLD_DEFAULT, "FcFini")) reinterpret_cast<void (*)()>(fini)();
}

}  // namespace calder
