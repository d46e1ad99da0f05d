// SPDX-License-Identifier: MIT
// calder scene files: the reader (see calder/scene_file.hpp and docs/SCENES.md).
//
// toml++ parses the text and keeps the line and column of every key and
// value; this file walks the document, checks every key against the keys its
// table may hold, converts every value with its location at hand, and so
// reports each problem as "FILE:LINE:COLUMN: problem".
#include <fcntl.h>
#include <sys/stat.h>
#include <toml++/toml.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <initializer_list>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <variant>
#include <vector>

#include "../kepler_orbit.hpp"
#include "calder/error.hpp"
#include "calder/fields.hpp"
#include "calder/scene.hpp"
#include "calder/scene_file.hpp"
#include "calder/trajectory.hpp"
#include "names.hpp"
#include "text_check.hpp"
#include "toml_reading.hpp"

namespace calder {

namespace {

using scene_file_detail::cat;
using scene_file_detail::Choice;
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

using scene_file_detail::Check;
using scene_file_detail::Keys;
using scene_file_detail::one_line;
using scene_file_detail::quote;
using scene_file_detail::shown;
using scene_file_detail::Tbl;
using scene_file_detail::TomlReader;
using scene_file_detail::type_name;

// The most threads a file may ask for: the core's limit (one check for files
// and snapshots).
constexpr std::int64_t kMaxThreads = max_threads;

// The keys of the top level, in the order docs/SCENES.md lists them.
const Keys kTopLevelKeys = {"name",     "description", "frames", "seed",     "origin",
                            "on_press", "canvas",      "world",  "boundary", "edges_first",
                            "bodies",   "fields",      "input",  "look"};

// --- the reader -------------------------------------------------------------------

class Reader : public TomlReader {
 public:
  explicit Reader(std::string source) : TomlReader(std::move(source), kTopLevelKeys) {}

  // A number, { min = a, max = b } or { start = a, step = b }.
  Draw draw(const toml::node& n, const std::string& label, Check check) const {
    if (const auto* t = n.as_table()) {
      const Tbl range(*this, *t, quote(label), label + ".");
      const bool uniform = t->contains("min") || t->contains("max");
      const bool linear = t->contains("start") || t->contains("step");
      if (uniform && linear) {
        fail(n,
             quote(label) + " is either { min = a, max = b } or { start = a, step = b }, not both");
      }
      if (linear) {
        range.allow({"start", "step"});
        const double start = number(range.require("start"), label + ".start", check);
        const double step = number(range.require("step"), label + ".step");
        return Draw::linear(start, step);
      }
      range.allow(uniform ? Keys{"min", "max"} : Keys{"min", "max", "start", "step"});
      const double min = number(range.require("min"), label + ".min", check);
      const double max = number(range.require("max"), label + ".max", check);
      return Draw::uniform(min, max);
    }
    if (n.is_integer() || n.is_floating_point()) return Draw::fixed(number(n, label, check));
    fail(n, quote(label) +
                " must be a number, { min = a, max = b } or { start = a, step = b }, got " +
                type_name(n));
  }

  // --- the scene ---
  Scene scene(const toml::table& root);
  // Scene::validate, its message placed at the element it names.
  void validate(const Scene& scene) const;

 private:
  void canvas(const Tbl& top, Scene& s) const;
  void world(const Tbl& top, Scene& s) const;
  void boundary(const Tbl& top, const char* table, Boundary& boundary) const;
  BodyGroup body_group(const toml::table& t, std::size_t total_before) const;
  void coordinates(const Tbl& b, std::string_view both, std::string_view first,
                   std::string_view second, Draw& a, Draw& c, bool required) const;
  void kepler(const Tbl& b, BodyGroup& g) const;
  RadiusRule radius(const toml::node& n) const;
  SceneField field(const toml::table& t) const;
  std::string field_type(const toml::table& t) const;
  template <class F>
  Field field_parameters(const Tbl& f) const;
  void field_options(const Tbl& f, SceneField& out) const;
  // One parameter of a field kind (FieldKind::parameters), by its type.
  void parameter(const Tbl& f, const char* key, Range range, double& value, const char*) const;
  void parameter(const Tbl& f, const char* key, Range range, int& value, const char*) const;
  void parameter(const Tbl& f, const char* key, Range, bool& value, const char*) const;
  void parameter(const Tbl& f, const char* key, Range, Vec2& value, const char*) const;
  void parameter(const Tbl& f, const char* key, Range, Rect& value, const char*) const;
  void parameter(const Tbl& f, const char* key, Range, AttractionLaw& value,
                 const char* kind) const;
  void parameter(const Tbl& f, const char* key, Range, std::optional<CentralBody>& value,
                 const char*) const;
  template <class E>
  requires std::is_enum_v<E>
  void parameter(const Tbl& f, const char* key, Range, E& value, const char*) const {
    value = f.choice(key, choices(E{}), value);
  }
  AttractionLaw law(const toml::node& n, const char* owner) const;
  void input(const Tbl& top, Scene& s) const;
  void look(const Tbl& top, Scene& s) const;

  std::vector<toml::source_position> bodies_at_;
  std::vector<toml::source_position> fields_at_;
};

Scene Reader::scene(const toml::table& root) {
  const Tbl top(*this, root, "the top level");
  top.allow(kTopLevelKeys);
  Scene s;
  s.name = top.string("name", std::filesystem::path(source()).stem().string());
  s.description = top.string("description", "");
  if (const toml::node* n = top.find("frames")) s.frames = integer(*n, "frames", 0, max_frames);
  if (const toml::node* n = top.find("seed")) {
    s.world.seed = static_cast<std::uint32_t>(
        integer(*n, "seed", 0, std::numeric_limits<std::uint32_t>::max()));
  }
  s.origin = top.vec2("origin", s.origin);
  s.on_press = top.choice("on_press", kPressActions, s.on_press);
  canvas(top, s);
  world(top, s);
  boundary(top, "boundary", s.world.boundary);
  boundary(top, "edges_first", s.edges_first);

  if (const toml::node* n = top.find("bodies")) {
    const toml::array& groups = array_of(*n, "bodies", "an array of tables ([[bodies]])");
    std::size_t total = 0;
    for (const toml::node& g : groups) {
      const toml::table& t = table_of(g, "bodies", "an array of tables ([[bodies]])");
      bodies_at_.push_back(t.source().begin);
      s.bodies.push_back(body_group(t, total));
      total += s.bodies.back().count;
    }
  }
  if (const toml::node* n = top.find("fields")) {
    const toml::array& fields = array_of(*n, "fields", "an array of tables ([[fields]])");
    for (const toml::node& f : fields) {
      const toml::table& t = table_of(f, "fields", "an array of tables ([[fields]])");
      fields_at_.push_back(t.source().begin);
      s.fields.push_back(field(t));
    }
  }
  input(top, s);
  look(top, s);
  return s;
}

void Reader::look(const Tbl& top, Scene& s) const {
  const toml::table* t = top.table("look");
  if (t == nullptr) return;
  const Tbl l(*this, *t, "[look]", "look.");
  l.allow({"trails", "trail_alpha", "body_gray", "body_alpha", "squares"});
  SceneLook& look = s.look;
  look.trails = l.boolean("trails", look.trails);
  const auto byte = [&](std::string_view key, double fallback) {
    const double v = l.number(key, fallback);
    if (!(v >= 0.0 && v <= 255.0)) {
      fail(l.require(key),
           quote(l.label(key)) + " must be between 0 and 255, got " + format_number(v));
    }
    return v;
  };
  look.trail_alpha = byte("trail_alpha", look.trail_alpha);
  look.body_gray = byte("body_gray", look.body_gray);
  look.body_alpha = byte("body_alpha", look.body_alpha);
  look.squares = l.boolean("squares", look.squares);
}

void Reader::canvas(const Tbl& top, Scene& s) const {
  const toml::table* t = top.table("canvas");
  if (t == nullptr) return;
  const Tbl c(*this, *t, "[canvas]", "canvas.");
  c.allow({"width", "height"});
  s.world.width = c.number("width", s.world.width, Check::positive);
  s.world.height = c.number("height", s.world.height, Check::positive);
}

void Reader::world(const Tbl& top, Scene& s) const {
  const toml::table* t = top.table("world");
  if (t == nullptr) return;
  const Tbl w(*this, *t, "[world]", "world.");
  w.allow({"dt", "integrator", "tolerance", "update_order", "arithmetic", "threads", "max_speed"});
  s.world.dt = w.number("dt", s.world.dt, Check::positive);
  s.world.tolerance = w.number("tolerance", s.world.tolerance, Check::positive);
  s.world.max_speed = w.number("max_speed", s.world.max_speed, Check::non_negative);
  s.world.integrator = w.choice("integrator", kIntegrators, s.world.integrator);
  s.world.update_order = w.choice("update_order", kUpdateOrders, s.world.update_order);
  s.world.arithmetic = w.choice("arithmetic", kArithmetics, s.world.arithmetic);
  if (const toml::node* n = w.find("threads")) {
    s.world.threads = static_cast<int>(integer(*n, "world.threads", 0, kMaxThreads));
  }
  if (s.world.arithmetic != Arithmetic::book &&
      (s.world.integrator != Integrator::semi_implicit_euler ||
       s.world.update_order != UpdateOrder::simultaneous)) {
    fail(w.require("arithmetic"),
         "arithmetic other than \"book\" needs integrator = \"semi_implicit_euler\" and "
         "update_order = \"simultaneous\"");
  }
  if (s.world.update_order == UpdateOrder::sequential &&
      s.world.integrator != Integrator::semi_implicit_euler) {
    fail(w.require("update_order"),
         "update_order = \"sequential\" needs integrator = \"semi_implicit_euler\"");
  }
}

// [boundary], or [edges_first] (the same keys but timing).
void Reader::boundary(const Tbl& top, const char* table, Boundary& boundary) const {
  const toml::table* t = top.table(table);
  if (t == nullptr) return;
  const std::string name(table);
  const Tbl b(*this, *t, cat("[", name, "]"), cat(name, "."));
  if (name == "boundary") {
    b.allow({"kind", "restitution", "use_radius", "edges", "timing", "inset", "periodic"});
  } else {
    b.allow({"kind", "restitution", "use_radius", "edges", "inset", "periodic"});
  }
  boundary.kind = choice(b.require("kind"), cat(name, ".kind"), kBoundaryKinds);
  boundary.restitution = b.number("restitution", boundary.restitution, Check::non_negative);
  boundary.use_radius = b.boolean("use_radius", boundary.use_radius);
  boundary.inset = b.number("inset", boundary.inset, Check::non_negative);
  boundary.periodic = b.boolean("periodic", boundary.periodic);
  if (const toml::array* edges = b.array("edges")) {
    boundary.edges = {false, false, false, false};
    std::size_t i = 0;
    for (const toml::node& e : *edges) {
      const std::string label = cat(name, ".edges[", std::to_string(i++), "]");
      bool* flag = nullptr;
      switch (choice(e, label, kEdges)) {
        case Edge::left:
          flag = &boundary.edges.left;
          break;
        case Edge::right:
          flag = &boundary.edges.right;
          break;
        case Edge::top:
          flag = &boundary.edges.top;
          break;
        case Edge::bottom:
          flag = &boundary.edges.bottom;
          break;
      }
      if (*flag) fail(e, cat("edge ", quote(*e.value<std::string>()), " is listed twice"));
      *flag = true;
    }
  }
  boundary.timing = b.choice("timing", kBoundaryTimings, boundary.timing);
}

BodyGroup Reader::body_group(const toml::table& t, std::size_t total_before) const {
  const Tbl b(*this, t, "[[bodies]]");
  BodyGroup g;
  g.layout = b.choice("layout", kLayouts, g.layout);
  const Keys common = {"count", "layout", "mass", "radius", "friction", "drag_area"};
  const Keys grid_only = {"x", "y", "position", "vx", "vy", "velocity", "kepler"};
  const Keys orbit_only = {"center", "distance", "speed"};
  const bool orbit = g.layout == BodyGroup::Layout::orbit;
  // A key of the other layout gets its own message rather than "unknown key".
  for (const std::string_view key : orbit ? grid_only : orbit_only) {
    if (b.find(key) != nullptr) {
      fail(b.key_at(key),
           quote(key) + (orbit ? " is not used with layout = \"orbit\" (it places bodies with "
                                 "center, distance and speed)"
                               : " is used only with layout = \"orbit\""));
    }
  }
  Keys allowed = common;
  allowed.insert(allowed.end(), (orbit ? orbit_only : grid_only).begin(),
                 (orbit ? orbit_only : grid_only).end());
  b.allow(allowed);

  if (const toml::node* n = b.find("count")) {
    const auto count =
        static_cast<std::size_t>(integer(*n, "count", 0, static_cast<std::int64_t>(max_bodies)));
    if (total_before + count > max_bodies) {
      fail(*n, cat("more than ", std::to_string(max_bodies), " bodies in all (",
                   std::to_string(total_before), " before this group)"));
    }
    g.count = count;
  }
  const toml::node& mass = b.require("mass");
  g.mass = draw(mass, "mass", Check::positive);
  if (g.mass.kind == Draw::Kind::linear && g.count > 0) {
    // start + i * step is monotonic in i: its ends are its extremes.
    const double last = g.mass.value + static_cast<double>(g.count - 1) * g.mass.step;
    if (!(last > 0.0) || !std::isfinite(last)) {
      fail(mass, cat("'mass' of the last body (", std::to_string(g.count - 1), ") would be ",
                     format_number(last), "; masses must be > 0"));
    }
  }

  if (orbit) {
    g.center = b.vec2("center", g.center);
    g.distance = draw(b.require("distance"), "distance", Check::any);
    g.speed = draw(b.require("speed"), "speed", Check::any);
  } else if (b.find("kepler") != nullptr) {
    kepler(b, g);
  } else {
    // position = [x, y] or x and y; velocity = [vx, vy] or vx and vy.
    coordinates(b, "position", "x", "y", g.x, g.y, true);
    coordinates(b, "velocity", "vx", "vy", g.vx, g.vy, false);
  }
  if (const toml::node* n = b.find("radius")) g.radius = radius(*n);
  if (const toml::node* n = b.find("friction")) {
    g.friction = number(*n, "friction", Check::non_negative);
  }
  g.drag_area = b.number("drag_area", g.drag_area, Check::non_negative);
  return g;
}

// position = [x, y], or x and y each a number or a draw (the same for velocity).
void Reader::coordinates(const Tbl& b, std::string_view both, std::string_view first,
                         std::string_view second, Draw& a, Draw& c, bool required) const {
  const toml::node* n = b.find(both);
  const toml::node* na = b.find(first);
  const toml::node* nc = b.find(second);
  if (n != nullptr) {
    if (na != nullptr || nc != nullptr) {
      fail(*n, cat("give either ", quote(both), " or ", quote(first), " and ", quote(second),
                   ", not both"));
    }
    const Vec2 v = vec2(*n, std::string(both));
    a = Draw::fixed(v.x);
    c = Draw::fixed(v.y);
    return;
  }
  if (required && na == nullptr && nc == nullptr) {
    fail(b.table(), cat("missing required key ", quote(both), " (or ", quote(first), " and ",
                        quote(second), ") in [[bodies]]"));
  }
  if (na != nullptr || required) a = draw(b.require(first), std::string(first), Check::any);
  if (nc != nullptr || required) c = draw(b.require(second), std::string(second), Check::any);
}

// kepler = { GM = ..., semi_major_axis = a, eccentricity = e, focus = [x, y] }:
// one body at the orbit's pericentre, focus + (a (1 - e), 0), moving along
// +y at the vis-viva speed (clockwise on the y-down canvas). It stands for
// position and velocity, which the scene then holds.
void Reader::kepler(const Tbl& b, BodyGroup& g) const {
  for (const std::string_view key : {"x", "y", "position", "vx", "vy", "velocity"}) {
    if (b.find(key) != nullptr) {
      fail(b.key_at(key), cat(quote(key),
                              " can't be given with 'kepler' (it places the body at "
                              "the orbit's pericentre, moving)"));
    }
  }
  if (g.count > 1) {
    fail(b.key_at("count"), cat("'kepler' starts one body, but 'count' is ",
                                std::to_string(g.count), " (one [[bodies]] table per orbit)"));
  }
  const toml::node& n = *b.find("kepler");
  const Tbl k(*this, table_of(n, "kepler", "an inline table { GM = ..., semi_major_axis = ... }"),
              "'kepler'", "kepler.");
  k.allow({"GM", "semi_major_axis", "eccentricity", "focus"});
  const double gm = number(k.require("GM"), k.label("GM"), Check::positive);
  const double a =
      number(k.require("semi_major_axis"), k.label("semi_major_axis"), Check::positive);
  const double e = k.number("eccentricity", 0.0);
  if (!(e >= 0.0 && e < 1.0)) {
    fail(*k.find("eccentricity"),
         cat("'kepler.eccentricity' must be >= 0 and < 1 (an ellipse), got ", format_number(e)));
  }
  const Vec2 focus = k.vec2("focus", {0.0, 0.0});
  const detail::Pericentre p = detail::pericentre(gm, a, e);
  const Vec2 at{focus.x + p.distance, focus.y};
  if (!(p.distance > 0.0) || !std::isfinite(p.speed) || !std::isfinite(at.x)) {
    fail(n, cat("'kepler': the pericentre of GM ", format_number(gm), ", a ", format_number(a),
                ", e ", format_number(e), " is not a finite place and speed"));
  }
  g.x = Draw::fixed(at.x);
  g.y = Draw::fixed(at.y);
  g.vx = Draw::fixed(0.0);
  g.vy = Draw::fixed(p.speed);
}

// A number, { per_mass = k } or { per_sqrt_mass = k }.
RadiusRule Reader::radius(const toml::node& n) const {
  if (const auto* rt = n.as_table()) {
    const Tbl radius(*this, *rt, "'radius'", "radius.");
    radius.allow({"per_mass", "per_sqrt_mass"});
    if (rt->size() != 1) {
      fail(n, "'radius' must be a number, { per_mass = k } or { per_sqrt_mass = k }");
    }
    const bool per_mass = rt->contains("per_mass");
    const char* key = per_mass ? "per_mass" : "per_sqrt_mass";
    return {per_mass ? RadiusRule::Kind::per_mass : RadiusRule::Kind::per_sqrt_mass,
            number(radius.require(key), radius.label(key), Check::non_negative)};
  }
  if (n.is_integer() || n.is_floating_point()) {
    return {RadiusRule::Kind::fixed, number(n, "radius", Check::non_negative)};
  }
  fail(n, "'radius' must be a number, { per_mass = k } or { per_sqrt_mass = k }, got " +
              std::string(type_name(n)));
}

AttractionLaw Reader::law(const toml::node& n, const char* owner) const {
  const Tbl l(*this, table_of(n, "law", "an inline table { G = ..., clamp = ..., ... }"), "'law'",
              "law.");
  l.allow({"G", "clamp", "min", "max", "softening", "product", "exponent", "repulsion",
           "repulsion_exponent"});
  AttractionLaw law;
  law.G = l.number("G", law.G);
  law.clamp = l.choice("clamp", kClamps, law.clamp);
  law.min = l.number("min", law.min);
  law.max = l.number("max", law.max);
  law.softening = l.number("softening", law.softening, Check::non_negative);
  law.product = l.choice("product", kProducts, law.product);
  law.exponent = l.number("exponent", law.exponent);
  law.repulsion = l.number("repulsion", law.repulsion, Check::non_negative);
  law.repulsion_exponent = l.number("repulsion_exponent", law.repulsion_exponent);
  try {
    law.validate(owner);
  } catch (const Error& e) {
    fail(n, e.what());
  }
  return law;
}

// --- fields: read as their FieldKind (calder/fields.hpp) describes them ---

// The keys of every [[fields]] table besides "type" and its kind's parameters.
const Keys kFieldOptions = {"enabled", "visible", "while_pressed", "follow_mouse", "draggable"};

// Calls visit.template operator()<F>() for the field kind F named `type`; false when none is.
template <class Visit, std::size_t... I>
bool with_kind_named(std::string_view type, Visit&& visit, std::index_sequence<I...>) {
  const auto named = [&]<class F>() {
    if (type != FieldKind<F>::name) return false;
    visit.template operator()<F>();
    return true;
  };
  return (named.template operator()<std::variant_alternative_t<I, Field>>() || ...);
}

template <class Visit>
bool with_kind_named(std::string_view type, Visit&& visit) {
  return with_kind_named(type, visit, std::make_index_sequence<std::variant_size_v<Field>>());
}

// The field types a file may name, in the order docs/SCENES.md lists them.
template <std::size_t... I>
Keys scene_file_types(std::index_sequence<I...>) {
  Keys out;
  const auto add = [&]<class F>() {
    if (in_scene_files<F>()) out.push_back(FieldKind<F>::name);
  };
  (add.template operator()<std::variant_alternative_t<I, Field>>(), ...);
  return out;
}
const Keys kFieldTypes = scene_file_types(std::make_index_sequence<std::variant_size_v<Field>>());

Check check_of(Range range) {
  switch (range) {
    case Range::finite:
      break;
    case Range::positive:
      return Check::positive;
    case Range::non_negative:
    case Range::unit_interval:  // validate checks <= 1, at the [[fields]] table
      return Check::non_negative;
  }
  return Check::any;
}

SceneField Reader::field(const toml::table& t) const {
  const std::string type = field_type(t);
  const Tbl f(*this, t, cat("[[fields]] of type ", quote(type)));
  SceneField out;
  with_kind_named(type, [&]<class F>() { out.field = field_parameters<F>(f); });
  field_options(f, out);
  try {
    calder::validate(out.field);
  } catch (const Error& e) {
    fail(t, e.what());
  }
  return out;
}

// The value of "type", a kind a file may name.
std::string Reader::field_type(const toml::table& t) const {
  const toml::node& type_node = Tbl(*this, t, "[[fields]]").require("type");
  std::string type = string(type_node, "type");
  bool in_files = false;
  if (!with_kind_named(type, [&]<class F>() { in_files = in_scene_files<F>(); })) {
    fail(type_node, unknown_choice("type", type, kFieldTypes));
  }
  if (!in_files) {
    fail(type_node, cat("a ", type,
                        " can't be written in a scene file: its force is C++ code "
                        "(add it to the world with World::add)"));
  }
  return type;
}

// The keys a field of kind F may hold, then its parameters.
template <class F>
Field Reader::field_parameters(const Tbl& f) const {
  using Kind = FieldKind<F>;
  Keys keys = {"type"};
  std::apply([&](const auto&... p) { (keys.push_back(p.key), ...); }, Kind::parameters);
  keys.insert(keys.end(), kFieldOptions.begin(), kFieldOptions.end());
  f.allow(keys);
  F field;
  std::apply(
      [&](const auto&... p) { (parameter(f, p.key, p.range, field.*p.member, Kind::name), ...); },
      Kind::parameters);
  return field;
}

// enabled, visible and how the field follows the mouse.
void Reader::field_options(const Tbl& f, SceneField& out) const {
  const bool enabled = f.boolean("enabled", true);
  std::visit([&](auto& field) { field.enabled = enabled; }, out.field);
  out.visible = f.boolean("visible", out.visible);
  out.binding.while_pressed = f.boolean("while_pressed", false);
  out.binding.follow_mouse = f.boolean("follow_mouse", false);
  out.binding.draggable = f.boolean("draggable", false);
  if (out.binding.follow_mouse && !can_follow_mouse(out.field)) {
    fail(f.require("follow_mouse"), cat("only ", kinds_following_mouse(), " can follow the mouse"));
  }
  if (out.binding.draggable && !can_be_dragged(out.field)) {
    fail(f.require("draggable"), "only an attractor can be dragged");
  }
}

void Reader::parameter(const Tbl& f, const char* key, Range range, double& value,
                       const char*) const {
  value = f.number(key, value, check_of(range));
}

// Integers of a field are thread counts.
void Reader::parameter(const Tbl& f, const char* key, Range range, int& value, const char*) const {
  if (const toml::node* n = f.find(key)) {
    const std::int64_t min = range == Range::positive ? 1 : 0;
    value = static_cast<int>(integer(*n, f.label(key), min, kMaxThreads));
  }
}

void Reader::parameter(const Tbl& f, const char* key, Range, bool& value, const char*) const {
  value = f.boolean(key, value);
}

void Reader::parameter(const Tbl& f, const char* key, Range, Vec2& value, const char*) const {
  value = f.vec2(key, value);
}

// [x, y, w, h], w and h >= 0.
void Reader::parameter(const Tbl& f, const char* key, Range, Rect& value, const char*) const {
  const toml::node* n = f.find(key);
  if (n == nullptr) return;
  const std::string label = f.label(key);
  const std::vector<double> r = numbers(*n, label, 4, "an array of 4 numbers [x, y, w, h]");
  const toml::array& a = *n->as_array();
  number(a[2], label + "[2]", Check::non_negative);
  number(a[3], label + "[3]", Check::non_negative);
  value = {r[0], r[1], r[2], r[3]};
}

void Reader::parameter(const Tbl& f, const char* key, Range, AttractionLaw& value,
                       const char* kind) const {
  if (const toml::node* n = f.find(key)) value = law(*n, kind);
}

// { position = [x, y], mass = m }.
void Reader::parameter(const Tbl& f, const char* key, Range, std::optional<CentralBody>& value,
                       const char*) const {
  const toml::node* n = f.find(key);
  if (n == nullptr) return;
  const std::string label = f.label(key);
  const Tbl c(*this, table_of(*n, label, "an inline table { position = [x, y], mass = m }"),
              quote(label), label + ".");
  c.allow({"position", "mass"});
  CentralBody central;
  central.position = c.vec2("position", central.position);
  central.mass = c.number("mass", central.mass, Check::positive);
  value = central;
}

void Reader::input(const Tbl& top, Scene& s) const {
  const toml::table* t = top.table("input");
  if (t == nullptr) return;
  const Tbl in(*this, *t, "[input]", "input.");
  in.allow({"mouse_pressed", "mouse", "moves"});
  constexpr std::int64_t kLast = std::numeric_limits<std::int64_t>::max();
  if (const toml::array* ranges = in.array("mouse_pressed")) {
    std::size_t i = 0;
    for (const toml::node& r : *ranges) {
      const std::string label = cat("input.mouse_pressed[", std::to_string(i++), "]");
      const toml::array& a = array_of(r, label, "a frame range [first, last]");
      if (a.size() != 2) {
        fail(r, quote(label) + " must be a frame range [first, last], got an array of " +
                    std::to_string(a.size()));
      }
      FrameRange range;
      range.first = integer(a[0], label + "[0]", 1, kLast);
      range.last = integer(a[1], label + "[1]", range.first, kLast);
      s.input.mouse_pressed.push_back(range);
    }
  }
  s.input.mouse = in.vec2("mouse", s.input.mouse);
  if (const toml::array* moves = in.array("moves")) {
    std::size_t i = 0;
    std::int64_t previous = 0;
    for (const toml::node& m : *moves) {
      const std::string label = cat("input.moves[", std::to_string(i++), "]");
      const Tbl move(*this, table_of(m, label, "a table { frame = f, position = [x, y] }"),
                     quote(label), label + ".");
      move.allow({"frame", "position"});
      MouseMove mm;
      const toml::node& frame = move.require("frame");
      mm.frame = integer(frame, label + ".frame", 0, kLast);
      if (mm.frame < previous) {
        fail(frame, cat("mouse moves must be sorted by frame (frame ", std::to_string(mm.frame),
                        " comes after frame ", std::to_string(previous), ")"));
      }
      previous = mm.frame;
      mm.position = vec2(move.require("position"), label + ".position");
      s.input.moves.push_back(mm);
    }
  }
}

void Reader::validate(const Scene& scene) const {
  try {
    scene.validate();
  } catch (const Error& e) {
    std::string m = e.what();
    const std::string prefix =
        cat("scene ", scene.name.empty() ? std::string_view("(unnamed)") : scene.name, ": ");
    if (m.rfind(prefix, 0) == 0) m.erase(0, prefix.size());
    // "bodies[3]: ..." and "fields[1] ...": at that element.
    toml::source_position at{1, 1};
    for (const auto& [name, places] :
         {std::pair<std::string_view, const std::vector<toml::source_position>*>{"bodies[",
                                                                                 &bodies_at_},
          {"fields[", &fields_at_}}) {
      if (m.rfind(name, 0) != 0) continue;
      const std::size_t index = std::strtoul(m.c_str() + name.size(), nullptr, 10);
      if (index < places->size()) at = (*places)[index];
    }
    fail(at, m);
  }
}

std::string read_file(const std::string& path) {
  const auto cannot_read = [&](int error) {
    return SceneFileError(one_line(shown(path) + ": cannot read: " +
                                   std::error_code(error, std::generic_category()).message()));
  };
  // O_NONBLOCK: opening a FIFO must not wait for a writer (it is refused below).
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throw cannot_read(errno);
  struct FdCloser {
    int fd;
    ~FdCloser() { ::close(fd); }
  } closer{fd};
  struct stat info {};
  if (::fstat(fd, &info) != 0) throw cannot_read(errno);
  if (S_ISDIR(info.st_mode)) throw cannot_read(EISDIR);
  if (!S_ISREG(info.st_mode)) {
    throw SceneFileError(shown(path) +
                         ": not a regular file (scene files are read whole; "
                         "a device, FIFO or socket is refused)");
  }
  const auto too_big = [&] {
    return SceneFileError(cat(shown(path), ": larger than ",
                              std::to_string(scene_file_detail::kMaxFileBytes >> 20),
                              " MiB, the limit of scene files"));
  };
  if (static_cast<std::uint64_t>(info.st_size) > scene_file_detail::kMaxFileBytes) throw too_big();
  std::string text;
  std::array<char, 65536> buffer{};
  while (true) {
    const ssize_t n = ::read(fd, buffer.data(), buffer.size());
    if (n < 0) {
      if (errno == EINTR) continue;
      throw cannot_read(errno);
    }
    if (n == 0) break;
    text.append(buffer.data(), static_cast<std::size_t>(n));
    if (text.size() > scene_file_detail::kMaxFileBytes) throw too_big();  // it grew meanwhile
  }
  return text;
}

}  // namespace

Scene parse_scene(std::string_view text, const std::string& source_name) {
  Reader reader(source_name);
  if (text.size() > scene_file_detail::kMaxFileBytes) {
    reader.fail(toml::source_position{1, 1},
                cat("larger than ", std::to_string(scene_file_detail::kMaxFileBytes >> 20),
                    " MiB, the limit of scene files"));
  }
  if (const auto problem = scene_file_detail::check_text(text)) {
    reader.fail(toml::source_position{static_cast<toml::source_index>(problem->line),
                                      static_cast<toml::source_index>(problem->column)},
                problem->what);
  }
  toml::table root;
  try {
    root = toml::parse(text, std::string_view(source_name));
  } catch (const toml::parse_error& e) {
    reader.fail(e.source().begin, std::string(e.description()));
  }
  Scene scene = reader.scene(root);
  reader.validate(scene);
  return scene;
}

Scene load_scene_file(const std::string& path) { return parse_scene(read_file(path), path); }

}  // namespace calder
