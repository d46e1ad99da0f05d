// SPDX-License-Identifier: MIT
// calder scene files: the writer, to_toml (see calder/scene_file.hpp).
//
// Writes the keys in the order docs/SCENES.md describes them, every number in
// the shortest form that reads back to the same double, so that
// parse_scene(to_toml(s)) is a scene equal to s and to_toml of that is the
// same text again.
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>

#include "calder/error.hpp"
#include "calder/fields.hpp"
#include "calder/scene.hpp"
#include "calder/scene_file.hpp"
#include "calder/trajectory.hpp"
#include "names.hpp"

namespace calder {

namespace {

using scene_file_detail::cat;
using scene_file_detail::choices;
using scene_file_detail::kArithmetics;
using scene_file_detail::kBoundaryKinds;
using scene_file_detail::kBoundaryTimings;
using scene_file_detail::kClamps;
using scene_file_detail::kEdges;
using scene_file_detail::kIntegrators;
using scene_file_detail::kLayouts;
using scene_file_detail::kNBodyMethods;
using scene_file_detail::kPairOrders;
using scene_file_detail::kPressActions;
using scene_file_detail::kProducts;
using scene_file_detail::kUpdateOrders;
using scene_file_detail::name_of;

// A double as a TOML number that reads back to the same double. The shortest
// round-trip form is a valid TOML float or integer, except that "-0" would
// read as the integer 0 (losing the sign) and an integer of more than 15
// digits might not fit TOML's 64-bit integers: those get a ".0".
std::string num(double value) {
  if (!std::isfinite(value)) {
    throw Error(cat("to_toml: a scene file can't hold the number ", format_number(value)));
  }
  std::string s = format_number(value);
  if (s.find_first_of(".eE") == std::string::npos) {
    const std::size_t digits = s.size() - (s[0] == '-' ? 1 : 0);
    if (value == 0.0 && std::signbit(value)) return "-0.0";
    if (digits > 15) s += ".0";
  }
  return s;
}

// A TOML basic string.
std::string str(std::string_view s) {
  std::string out = "\"";
  for (const char c : s) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\r':
        out += "\\r";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
          char escape[8];
          std::snprintf(escape, sizeof escape, "\\u%04X", static_cast<unsigned>(c));
          out += escape;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

std::string vec(Vec2 v) { return cat("[", num(v.x), ", ", num(v.y), "]"); }

std::string boolean(bool b) { return b ? "true" : "false"; }

std::string draw(const Draw& d) {
  switch (d.kind) {
    case Draw::Kind::fixed:
      break;
    case Draw::Kind::uniform:
      return cat("{ min = ", num(d.min), ", max = ", num(d.max), " }");
    case Draw::Kind::linear:
      return cat("{ start = ", num(d.value), ", step = ", num(d.step), " }");
  }
  return num(d.value);
}

// Exactly equal, down to the sign of zero.
bool same(double a, double b) { return a == b && std::signbit(a) == std::signbit(b); }

// G, clamp, min, max and product always; the rarer parameters when they are
// not the default.
std::string law(const AttractionLaw& l) {
  const AttractionLaw plain{};
  std::string out = cat("{ G = ", num(l.G), ", clamp = ", str(name_of(kClamps, l.clamp)),
                        ", min = ", num(l.min), ", max = ", num(l.max));
  if (!same(l.softening, plain.softening)) out += cat(", softening = ", num(l.softening));
  out += cat(", product = ", str(name_of(kProducts, l.product)));
  if (!same(l.exponent, plain.exponent)) out += cat(", exponent = ", num(l.exponent));
  if (!same(l.repulsion, plain.repulsion)) out += cat(", repulsion = ", num(l.repulsion));
  if (!same(l.repulsion_exponent, plain.repulsion_exponent)) {
    out += cat(", repulsion_exponent = ", num(l.repulsion_exponent));
  }
  return out + " }";
}

class Writer {
 public:
  void line(std::string_view key, const std::string& value) {
    out_ += key;
    out_ += " = ";
    out_ += value;
    out_ += '\n';
  }
  void header(std::string_view text) {
    out_ += '\n';
    out_ += text;
    out_ += '\n';
  }
  std::string take() { return std::move(out_); }

 private:
  std::string out_;
};

void write_body_group(Writer& w, const BodyGroup& g) {
  w.header("[[bodies]]");
  w.line("count", std::to_string(g.count));
  if (g.layout == BodyGroup::Layout::orbit) {
    w.line("layout", str(name_of(kLayouts, g.layout)));
    w.line("center", vec(g.center));
    w.line("distance", draw(g.distance));
    w.line("speed", draw(g.speed));
    w.line("mass", draw(g.mass));
  } else {
    const bool fixed_position = g.x.kind == Draw::Kind::fixed && g.y.kind == Draw::Kind::fixed;
    if (fixed_position) {
      w.line("position", vec({g.x.value, g.y.value}));
    } else {
      w.line("x", draw(g.x));
      w.line("y", draw(g.y));
    }
    w.line("mass", draw(g.mass));
    if (g.vx.kind == Draw::Kind::fixed && g.vy.kind == Draw::Kind::fixed) {
      w.line("velocity", vec({g.vx.value, g.vy.value}));
    } else {
      w.line("vx", draw(g.vx));
      w.line("vy", draw(g.vy));
    }
  }
  switch (g.radius.kind) {
    case RadiusRule::Kind::fixed:
      w.line("radius", num(g.radius.k));
      break;
    case RadiusRule::Kind::per_mass:
      w.line("radius", cat("{ per_mass = ", num(g.radius.k), " }"));
      break;
    case RadiusRule::Kind::per_sqrt_mass:
      w.line("radius", cat("{ per_sqrt_mass = ", num(g.radius.k), " }"));
      break;
  }
  if (g.friction) w.line("friction", num(*g.friction));
  w.line("drag_area", num(g.drag_area));
}

// [boundary] (with its timing) or [edges_first]; inset and periodic only
// when they are not the defaults.
void write_boundary(Writer& w, const char* header, const Boundary& b, bool timing) {
  w.header(header);
  w.line("kind", str(name_of(kBoundaryKinds, b.kind)));
  w.line("restitution", num(b.restitution));
  w.line("use_radius", boolean(b.use_radius));
  std::string edges;
  for (const auto& [edge, on] : {std::pair{Edge::left, b.edges.left},
                                 {Edge::right, b.edges.right},
                                 {Edge::top, b.edges.top},
                                 {Edge::bottom, b.edges.bottom}}) {
    if (!on) continue;
    if (!edges.empty()) edges += ", ";
    edges += str(name_of(kEdges, edge));
  }
  w.line("edges", "[" + edges + "]");
  if (timing) w.line("timing", str(name_of(kBoundaryTimings, b.timing)));
  if (b.inset != 0.0) w.line("inset", num(b.inset));
  if (!b.periodic) w.line("periodic", boolean(false));
}

// One parameter of a field kind (FieldKind::parameters), by its type.
void write_value(Writer& w, const char* key, double value) { w.line(key, num(value)); }
void write_value(Writer& w, const char* key, int value) { w.line(key, std::to_string(value)); }
void write_value(Writer& w, const char* key, bool value) { w.line(key, boolean(value)); }
void write_value(Writer& w, const char* key, Vec2 value) { w.line(key, vec(value)); }
void write_value(Writer& w, const char* key, const Rect& r) {
  w.line(key, cat("[", num(r.x), ", ", num(r.y), ", ", num(r.w), ", ", num(r.h), "]"));
}
void write_value(Writer& w, const char* key, const AttractionLaw& value) {
  w.line(key, law(value));
}
void write_value(Writer& w, const char* key, const std::optional<CentralBody>& central) {
  if (!central) return;
  w.line(key, cat("{ position = ", vec(central->position), ", mass = ", num(central->mass), " }"));
}
template <class E>
requires std::is_enum_v<E>
void write_value(Writer& w, const char* key, E value) {
  w.line(key, str(name_of(choices(E{}), value)));
}

void write_field(Writer& w, const SceneField& sf) {
  w.header("[[fields]]");
  w.line("type", str(field_name(sf.field)));
  std::visit(
      [&](const auto& f) {
        std::apply(
            [&](const auto&... p) {
              ((p.written == nullptr || p.written(f) ? write_value(w, p.key, f.*p.member) : void()),
               ...);
            },
            FieldKind<std::decay_t<decltype(f)>>::parameters);
      },
      sf.field);
  const bool enabled = std::visit([](const auto& f) { return f.enabled; }, sf.field);
  if (!enabled) w.line("enabled", "false");
  if (!sf.visible) w.line("visible", "false");
  if (sf.binding.while_pressed) w.line("while_pressed", "true");
  if (sf.binding.follow_mouse) w.line("follow_mouse", "true");
  if (sf.binding.draggable) w.line("draggable", "true");
}

// A custom attraction law is C++ code; other parameters are written as they are.
void require_writable_value(const AttractionLaw& law, const std::string& where) {
  if (law.custom) {
    throw Error(where + ": a custom attraction law is C++ code, which a scene file can't hold");
  }
}
template <class T>
void require_writable_value(const T&, const std::string&) {}

// Throws when a field is C++ code: a custom force, a custom attraction law.
void require_writable(const Field& field, const std::string& where) {
  std::visit(
      [&](const auto& f) {
        using F = std::decay_t<decltype(f)>;
        if (!in_scene_files<F>()) {
          throw Error(where + ": a custom force is C++ code, which a scene file can't hold");
        }
        std::apply([&](const auto&... p) { (require_writable_value(f.*p.member, where), ...); },
                   FieldKind<F>::parameters);
      },
      field);
}

// [input] and [look] list only what differs from the defaults.
void write_input(Writer& w, const InputScript& in) {
  const bool mouse_moved = !same(in.mouse.x, 0.0) || !same(in.mouse.y, 0.0);
  if (!in.mouse_pressed.empty() || mouse_moved || !in.moves.empty()) {
    w.header("[input]");
    if (!in.mouse_pressed.empty()) {
      std::string ranges;
      for (const FrameRange& r : in.mouse_pressed) {
        if (!ranges.empty()) ranges += ", ";
        ranges += cat("[", std::to_string(r.first), ", ", std::to_string(r.last), "]");
      }
      w.line("mouse_pressed", "[" + ranges + "]");
    }
    if (mouse_moved) w.line("mouse", vec(in.mouse));
    if (!in.moves.empty()) {
      std::string moves;
      for (const MouseMove& m : in.moves) {
        if (!moves.empty()) moves += ", ";
        moves += cat("{ frame = ", std::to_string(m.frame), ", position = ", vec(m.position), " }");
      }
      w.line("moves", "[" + moves + "]");
    }
  }
}

void write_look(Writer& w, const SceneLook& look) {
  const SceneLook plain{};
  const bool trails = look.trails != plain.trails;
  const bool trail_alpha = !same(look.trail_alpha, plain.trail_alpha);
  const bool body_gray = !same(look.body_gray, plain.body_gray);
  const bool body_alpha = !same(look.body_alpha, plain.body_alpha);
  const bool squares = look.squares != plain.squares;
  if (trails || trail_alpha || body_gray || body_alpha || squares) {
    w.header("[look]");
    if (trails) w.line("trails", boolean(look.trails));
    if (trail_alpha) w.line("trail_alpha", num(look.trail_alpha));
    if (body_gray) w.line("body_gray", num(look.body_gray));
    if (body_alpha) w.line("body_alpha", num(look.body_alpha));
    if (squares) w.line("squares", boolean(look.squares));
  }
}

}  // namespace

std::string to_toml(const Scene& scene) {
  const std::string where =
      cat("to_toml: scene ", scene.name.empty() ? std::string_view("(unnamed)") : scene.name);
  for (std::size_t k = 0; k < scene.fields.size(); ++k) {
    const Field& f = scene.fields[k].field;
    require_writable(f, cat(where, ": fields[", std::to_string(k), "] (", field_name(f), ")"));
  }
  scene.validate();

  Writer w;
  w.line("name", str(scene.name));
  w.line("description", str(scene.description));
  w.line("frames", std::to_string(scene.frames));
  w.line("seed", std::to_string(scene.world.seed));
  if (!same(scene.origin.x, 0.0) || !same(scene.origin.y, 0.0)) w.line("origin", vec(scene.origin));
  if (scene.on_press != PressAction::none) {
    w.line("on_press", str(name_of(kPressActions, scene.on_press)));
  }

  w.header("[canvas]");
  w.line("width", num(scene.world.width));
  w.line("height", num(scene.world.height));

  w.header("[world]");
  w.line("dt", num(scene.world.dt));
  w.line("integrator", str(name_of(kIntegrators, scene.world.integrator)));
  if (scene.world.tolerance != kDefaultTolerance) w.line("tolerance", num(scene.world.tolerance));
  w.line("update_order", str(name_of(kUpdateOrders, scene.world.update_order)));
  w.line("arithmetic", str(name_of(kArithmetics, scene.world.arithmetic)));
  w.line("threads", std::to_string(scene.world.threads));
  if (scene.world.max_speed > 0.0) w.line("max_speed", num(scene.world.max_speed));

  write_boundary(w, "[boundary]", scene.world.boundary, true);
  if (scene.edges_first.kind != BoundaryKind::none) {
    write_boundary(w, "[edges_first]", scene.edges_first, false);
  }

  for (const BodyGroup& g : scene.bodies) write_body_group(w, g);
  for (const SceneField& f : scene.fields) write_field(w, f);

  write_input(w, scene.input);
  write_look(w, scene.look);
  return w.take();
}

}  // namespace calder
