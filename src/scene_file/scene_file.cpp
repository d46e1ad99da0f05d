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

#include "calder/error.hpp"
#include "calder/fields.hpp"
#include "calder/scene.hpp"
#include "calder/scene_file.hpp"
#include "calder/trajectory.hpp"
#include "names.hpp"
#include "text_check.hpp"

namespace calder {

namespace {

using scene_file_detail::cat;
using scene_file_detail::Choice;
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

using Keys = std::vector<std::string_view>;

// --- words for messages ---------------------------------------------------------

// The candidate closest to word when it is close enough to be a likely typo
// (see calder::detail::closest).
std::optional<std::string_view> nearest(std::string_view word, const Keys& candidates) {
  return detail::closest(word, candidates);
}

std::string join(const Keys& words) {
  std::string out;
  for (const std::string_view w : words) {
    if (!out.empty()) out += ", ";
    out += w;
  }
  return out;
}

template <class E, std::size_t N>
Keys names(const std::array<Choice<E>, N>& choices) {
  Keys out;
  for (const Choice<E>& c : choices) out.push_back(c.name);
  return out;
}

// Input shown in a message: control characters escaped, cut to a readable length.
std::string quote(std::string_view s) { return cat("'", detail::printable(s), "'"); }
std::string shown(std::string_view path) { return detail::printable(path, 240); }

const char* type_name(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a float";
    case toml::node_type::boolean:
      return "a boolean";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::table:
      return "a table";
    case toml::node_type::date:
      return "a date";
    case toml::node_type::time:
      return "a time";
    case toml::node_type::date_time:
      return "a date-time";
    case toml::node_type::none:
      break;
  }
  return "nothing";
}

// Messages are one line, whatever a key or a file name holds.
std::string one_line(std::string s) {
  for (char& c : s) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  return s;
}

bool before(const toml::source_position& a, const toml::source_position& b) {
  return a.line < b.line || (a.line == b.line && a.column < b.column);
}

enum class Check { any, positive, non_negative };

// The field types a file may name, in the order docs/SCENES.md lists them.
const Keys kFieldTypes = {"gravity", "wind",       "noise_wind", "helium",
                          "fan",     "edge_force", "friction",   "liquid",
                          "drag",    "lift",       "attractor",  "mutual_attraction"};

// The keys of the top level, in the order docs/SCENES.md lists them.
const Keys kTopLevelKeys = {"name",     "description", "frames", "seed",     "origin",
                            "on_press", "canvas",      "world",  "boundary", "edges_first",
                            "bodies",   "fields",      "input",  "look"};

// --- the reader -------------------------------------------------------------------

class Reader;

// A table of the document, with what messages call it ("[[bodies]]") and the
// prefix of its keys' labels ("law." for the keys of an inline `law` table).
class Tbl {
 public:
  Tbl(const Reader& reader, const toml::table& table, std::string context, std::string prefix = "")
      : r_(&reader), t_(&table), context_(std::move(context)), prefix_(std::move(prefix)) {}

  [[nodiscard]] const toml::table& table() const { return *t_; }
  [[nodiscard]] const std::string& context() const { return context_; }
  [[nodiscard]] std::string label(std::string_view key) const { return prefix_ + std::string(key); }
  [[nodiscard]] const toml::node* find(std::string_view key) const { return t_->get(key); }
  // Where a key that is there is written (the key itself, not its value).
  [[nodiscard]] toml::source_position key_at(std::string_view key) const {
    const auto it = t_->find(key);
    return it != t_->end() ? it->first.source().begin : t_->source().begin;
  }

  // Fails at the first key (in the file's order) that is not one of these.
  void allow(const Keys& keys) const;
  // The value of a key that must be there.
  [[nodiscard]] const toml::node& require(std::string_view key) const;

  [[nodiscard]] double number(std::string_view key, double fallback,
                              Check check = Check::any) const;
  [[nodiscard]] bool boolean(std::string_view key, bool fallback) const;
  [[nodiscard]] std::string string(std::string_view key, std::string fallback) const;
  [[nodiscard]] Vec2 vec2(std::string_view key, Vec2 fallback) const;
  template <class E, std::size_t N>
  [[nodiscard]] E choice(std::string_view key, const std::array<Choice<E>, N>& choices,
                         E fallback) const;
  // An optional sub-table (a [table] or an inline { ... }).
  [[nodiscard]] const toml::table* table(std::string_view key) const;
  // An optional array.
  [[nodiscard]] const toml::array* array(std::string_view key) const;

 private:
  const Reader* r_;
  const toml::table* t_;
  std::string context_;
  std::string prefix_;
};

class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void fail(const toml::source_position& at, const std::string& problem) const {
    const toml::source_position where = at ? at : toml::source_position{1, 1};
    throw SceneFileError(one_line(cat(shown(source_), ":", std::to_string(where.line), ":",
                                      std::to_string(where.column), ": ", problem)));
  }
  [[noreturn]] void fail(const toml::node& n, const std::string& problem) const {
    fail(n.source().begin, problem);
  }

  // --- values ---
  double number(const toml::node& n, const std::string& label, Check check = Check::any) const {
    double v = 0.0;
    if (const auto* i = n.as_integer()) {
      v = static_cast<double>(i->get());
    } else if (const auto* f = n.as_floating_point()) {
      v = f->get();
    } else {
      fail(n, quote(label) + " must be a number, got " + type_name(n));
    }
    if (!std::isfinite(v)) {
      fail(n, cat(quote(label), " must be a finite number, got ", format_number(v)));
    }
    if (check == Check::positive && !(v > 0.0)) {
      fail(n, cat(quote(label), " must be > 0, got ", format_number(v)));
    }
    if (check == Check::non_negative && !(v >= 0.0)) {
      fail(n, cat(quote(label), " must be >= 0, got ", format_number(v)));
    }
    return v;
  }

  std::int64_t integer(const toml::node& n, const std::string& label, std::int64_t min,
                       std::int64_t max) const {
    const auto* i = n.as_integer();
    if (i == nullptr) fail(n, quote(label) + " must be an integer, got " + type_name(n));
    const std::int64_t v = i->get();
    if (v < min || v > max) {
      fail(n, cat(quote(label), " must be between ", std::to_string(min), " and ",
                  std::to_string(max), ", got ", std::to_string(v)));
    }
    return v;
  }

  bool boolean(const toml::node& n, const std::string& label) const {
    const auto* b = n.as_boolean();
    if (b == nullptr) fail(n, quote(label) + " must be true or false, got " + type_name(n));
    return b->get();
  }

  std::string string(const toml::node& n, const std::string& label) const {
    const auto* s = n.as_string();
    if (s == nullptr) fail(n, quote(label) + " must be a string, got " + type_name(n));
    return s->get();
  }

  const toml::array& array_of(const toml::node& n, const std::string& label,
                              const char* shape) const {
    const auto* a = n.as_array();
    if (a == nullptr) fail(n, quote(label) + " must be " + shape + ", got " + type_name(n));
    return *a;
  }

  const toml::table& table_of(const toml::node& n, const std::string& label,
                              const char* shape = "a table") const {
    const auto* t = n.as_table();
    if (t == nullptr) fail(n, quote(label) + " must be " + shape + ", got " + type_name(n));
    return *t;
  }

  // An array of exactly `size` numbers.
  std::vector<double> numbers(const toml::node& n, const std::string& label, std::size_t size,
                              const char* shape) const {
    const toml::array& a = array_of(n, label, shape);
    if (a.size() != size) {
      fail(n,
           cat(quote(label), " must be ", shape, ", got an array of ", std::to_string(a.size())));
    }
    std::vector<double> out;
    for (std::size_t i = 0; i < size; ++i) {
      out.push_back(number(a[i], cat(label, "[", std::to_string(i), "]")));
    }
    return out;
  }

  Vec2 vec2(const toml::node& n, const std::string& label) const {
    const std::vector<double> v = numbers(n, label, 2, "an array of 2 numbers [x, y]");
    return {v[0], v[1]};
  }

  template <class E, std::size_t N>
  E choice(const toml::node& n, const std::string& label,
           const std::array<Choice<E>, N>& choices) const {
    const std::string s = string(n, label);
    for (const Choice<E>& c : choices) {
      if (c.name == s) return c.value;
    }
    fail(n, unknown_choice(label, s, names(choices)));
  }

  static std::string unknown_choice(const std::string& label, const std::string& got,
                                    const Keys& valid) {
    std::string m = cat(quote(label), " must be one of ", join(valid), " (got ", quote(got));
    if (const auto near = nearest(got, valid)) m += cat("; did you mean ", quote(*near), "?");
    return m + ")";
  }

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
  SceneField field(const toml::table& t) const;
  AttractionLaw law(const toml::node& n, const char* owner) const;
  void input(const Tbl& top, Scene& s) const;
  void look(const Tbl& top, Scene& s) const;

  std::string source_;
  std::vector<toml::source_position> bodies_at_;
  std::vector<toml::source_position> fields_at_;
};

void Tbl::allow(const Keys& keys) const {
  const toml::key* first = nullptr;
  for (auto&& [key, value] : *t_) {
    (void)value;
    if (std::find(keys.begin(), keys.end(), key.str()) != keys.end()) continue;
    if (first == nullptr || before(key.source().begin, first->source().begin)) first = &key;
  }
  if (first == nullptr) return;
  std::string m = cat("unknown key ", quote(first->str()), " in ", context_);
  if (const auto near = nearest(first->str(), keys)) {
    m += cat(" (did you mean ", quote(*near), "?)");
  } else {
    m += cat(" (valid keys: ", join(keys), ")");
  }
  const bool top_level_key =
      std::find(kTopLevelKeys.begin(), kTopLevelKeys.end(), first->str()) != kTopLevelKeys.end();
  if (top_level_key && t_->source().begin.line < first->source().begin.line) {
    // TOML's rule that surprises: every key after a [table] or [[table]]
    // header belongs to that table, up to the next header.
    m += cat("; '", first->str(),
             "' is a top-level key, but keys after a table header belong to "
             "that table: write it above the first [table] or [[table]] header");
  }
  r_->fail(first->source().begin, m);
}

const toml::node& Tbl::require(std::string_view key) const {
  const toml::node* n = find(key);
  if (n == nullptr) r_->fail(*t_, cat("missing required key ", quote(key), " in ", context_));
  return *n;
}

double Tbl::number(std::string_view key, double fallback, Check check) const {
  const toml::node* n = find(key);
  return n != nullptr ? r_->number(*n, label(key), check) : fallback;
}

bool Tbl::boolean(std::string_view key, bool fallback) const {
  const toml::node* n = find(key);
  return n != nullptr ? r_->boolean(*n, label(key)) : fallback;
}

std::string Tbl::string(std::string_view key, std::string fallback) const {
  const toml::node* n = find(key);
  return n != nullptr ? r_->string(*n, label(key)) : fallback;
}

Vec2 Tbl::vec2(std::string_view key, Vec2 fallback) const {
  const toml::node* n = find(key);
  return n != nullptr ? r_->vec2(*n, label(key)) : fallback;
}

template <class E, std::size_t N>
E Tbl::choice(std::string_view key, const std::array<Choice<E>, N>& choices, E fallback) const {
  const toml::node* n = find(key);
  return n != nullptr ? r_->choice(*n, label(key), choices) : fallback;
}

const toml::table* Tbl::table(std::string_view key) const {
  const toml::node* n = find(key);
  return n != nullptr ? &r_->table_of(*n, label(key)) : nullptr;
}

const toml::array* Tbl::array(std::string_view key) const {
  const toml::node* n = find(key);
  return n != nullptr ? &r_->array_of(*n, label(key), "an array") : nullptr;
}

Scene Reader::scene(const toml::table& root) {
  const Tbl top(*this, root, "the top level");
  top.allow(kTopLevelKeys);
  Scene s;
  s.name = top.string("name", std::filesystem::path(source_).stem().string());
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
  w.allow({"dt", "integrator", "update_order", "arithmetic", "threads", "max_speed"});
  s.world.dt = w.number("dt", s.world.dt, Check::positive);
  s.world.max_speed = w.number("max_speed", s.world.max_speed, Check::non_negative);
  s.world.integrator = w.choice("integrator", kIntegrators, s.world.integrator);
  s.world.update_order = w.choice("update_order", kUpdateOrders, s.world.update_order);
  s.world.arithmetic = w.choice("arithmetic", kArithmetics, s.world.arithmetic);
  if (const toml::node* n = w.find("threads")) {
    s.world.threads = static_cast<int>(integer(*n, "world.threads", 0, 1024));
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
  const Keys grid_only = {"x", "y", "position", "vx", "vy", "velocity"};
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
  } else {
    // position = [x, y] or x and y; velocity = [vx, vy] or vx and vy.
    const auto pair = [&](std::string_view both, std::string_view first, std::string_view second,
                          Draw& a, Draw& c, bool required) {
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
        fail(t, cat("missing required key ", quote(both), " (or ", quote(first), " and ",
                    quote(second), ") in [[bodies]]"));
      }
      if (na != nullptr || required) a = draw(b.require(first), std::string(first), Check::any);
      if (nc != nullptr || required) c = draw(b.require(second), std::string(second), Check::any);
    };
    pair("position", "x", "y", g.x, g.y, true);
    pair("velocity", "vx", "vy", g.vx, g.vy, false);
  }

  if (const toml::node* n = b.find("radius")) {
    if (const auto* rt = n->as_table()) {
      const Tbl radius(*this, *rt, "'radius'", "radius.");
      radius.allow({"per_mass", "per_sqrt_mass"});
      if (rt->size() != 1) {
        fail(*n, "'radius' must be a number, { per_mass = k } or { per_sqrt_mass = k }");
      }
      const bool per_mass = rt->contains("per_mass");
      const char* key = per_mass ? "per_mass" : "per_sqrt_mass";
      g.radius.kind = per_mass ? RadiusRule::Kind::per_mass : RadiusRule::Kind::per_sqrt_mass;
      g.radius.k = number(radius.require(key), radius.label(key), Check::non_negative);
    } else if (n->is_integer() || n->is_floating_point()) {
      g.radius = {RadiusRule::Kind::fixed, number(*n, "radius", Check::non_negative)};
    } else {
      fail(*n, "'radius' must be a number, { per_mass = k } or { per_sqrt_mass = k }, got " +
                   std::string(type_name(*n)));
    }
  }
  if (const toml::node* n = b.find("friction")) {
    g.friction = number(*n, "friction", Check::non_negative);
  }
  g.drag_area = b.number("drag_area", g.drag_area, Check::non_negative);
  return g;
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

SceneField Reader::field(const toml::table& t) const {
  const toml::node& type_node = Tbl(*this, t, "[[fields]]").require("type");
  const std::string type = string(type_node, "type");
  if (type == "custom_force") {
    fail(type_node,
         "a custom_force can't be written in a scene file: its force is C++ code "
         "(add it to the world with World::add)");
  }
  if (std::find(kFieldTypes.begin(), kFieldTypes.end(), type) == kFieldTypes.end()) {
    fail(type_node, unknown_choice("type", type, kFieldTypes));
  }
  const Tbl f(*this, t, cat("[[fields]] of type ", quote(type)));
  const auto allow = [&](std::initializer_list<std::string_view> own) {
    Keys keys = {"type"};
    keys.insert(keys.end(), own.begin(), own.end());
    for (const std::string_view k :
         {"enabled", "visible", "while_pressed", "follow_mouse", "draggable"}) {
      keys.push_back(k);
    }
    f.allow(keys);
  };

  SceneField out;
  if (type == "gravity") {
    allow({"g", "scale_by_mass"});
    Gravity g;
    g.g = f.vec2("g", g.g);
    g.scale_by_mass = f.boolean("scale_by_mass", g.scale_by_mass);
    out.field = g;
  } else if (type == "wind") {
    allow({"force"});
    Wind w;
    w.force = f.vec2("force", w.force);
    out.field = w;
  } else if (type == "noise_wind") {
    allow({"strength", "rate", "offset", "accumulate"});
    NoiseWind w;
    w.strength = f.number("strength", w.strength);
    w.rate = f.number("rate", w.rate);
    w.offset = f.number("offset", w.offset);
    w.accumulate = f.boolean("accumulate", w.accumulate);
    out.field = w;
  } else if (type == "helium") {
    allow({"lift"});
    Helium h;
    h.lift = f.number("lift", h.lift);
    out.field = h;
  } else if (type == "fan") {
    allow({"position", "strength", "reach"});
    Fan fan;
    fan.position = f.vec2("position", fan.position);
    fan.strength = f.number("strength", fan.strength);
    fan.reach = f.number("reach", fan.reach, Check::positive);
    out.field = fan;
  } else if (type == "edge_force") {
    allow({"strength", "margin"});
    EdgeForce e;
    e.strength = f.number("strength", e.strength);
    e.margin = f.number("margin", e.margin, Check::positive);
    out.field = e;
  } else if (type == "friction") {
    allow({"mu", "normal", "surface", "tolerance", "never_reverse"});
    Friction fr;
    fr.mu = f.number("mu", fr.mu, Check::non_negative);
    fr.normal = f.number("normal", fr.normal, Check::non_negative);
    fr.surface = f.choice("surface", kEdges, fr.surface);
    fr.tolerance = f.number("tolerance", fr.tolerance, Check::non_negative);
    fr.never_reverse = f.boolean("never_reverse", fr.never_reverse);
    out.field = fr;
  } else if (type == "liquid") {
    allow({"region", "c", "never_reverse"});
    Liquid l;
    if (const toml::node* n = f.find("region")) {
      const std::vector<double> r = numbers(*n, "region", 4, "an array of 4 numbers [x, y, w, h]");
      const toml::array& a = *n->as_array();
      number(a[2], "region[2]", Check::non_negative);
      number(a[3], "region[3]", Check::non_negative);
      l.region = {r[0], r[1], r[2], r[3]};
    }
    l.c = f.number("c", l.c, Check::non_negative);
    l.never_reverse = f.boolean("never_reverse", l.never_reverse);
    out.field = l;
  } else if (type == "drag") {
    allow({"c", "never_reverse"});
    Drag d;
    d.c = f.number("c", d.c, Check::non_negative);
    d.never_reverse = f.boolean("never_reverse", d.never_reverse);
    out.field = d;
  } else if (type == "lift") {
    allow({"coefficient"});
    Lift l;
    l.coefficient = f.number("coefficient", l.coefficient);
    out.field = l;
  } else if (type == "attractor") {
    allow({"position", "mass", "law"});
    Attractor a;
    a.position = f.vec2("position", a.position);
    a.mass = f.number("mass", a.mass, Check::positive);
    if (const toml::node* n = f.find("law")) a.law = law(*n, "attractor");
    out.field = a;
  } else {  // mutual_attraction
    allow({"law", "order", "central", "method", "theta", "single_precision", "threads"});
    MutualAttraction m;
    if (const toml::node* n = f.find("law")) m.law = law(*n, "mutual_attraction");
    m.order = f.choice("order", kPairOrders, m.order);
    m.method = f.choice("method", kNBodyMethods, m.method);
    m.theta = f.number("theta", m.theta, Check::non_negative);
    m.single_precision = f.boolean("single_precision", m.single_precision);
    if (const toml::node* n = f.find("threads")) {
      m.threads = static_cast<int>(integer(*n, "threads", 0, 1024));
    }
    if (const toml::node* n = f.find("central")) {
      const Tbl c(*this, table_of(*n, "central", "an inline table { position = [x, y], mass = m }"),
                  "'central'", "central.");
      c.allow({"position", "mass"});
      CentralBody central;
      central.position = c.vec2("position", central.position);
      central.mass = c.number("mass", central.mass, Check::positive);
      m.central = central;
    }
    out.field = m;
  }

  const bool enabled = f.boolean("enabled", true);
  std::visit([&](auto& field) { field.enabled = enabled; }, out.field);
  out.visible = f.boolean("visible", out.visible);
  out.binding.while_pressed = f.boolean("while_pressed", false);
  out.binding.follow_mouse = f.boolean("follow_mouse", false);
  out.binding.draggable = f.boolean("draggable", false);
  if (out.binding.follow_mouse && type != "fan" && type != "attractor") {
    fail(f.require("follow_mouse"), "only a fan or an attractor can follow the mouse");
  }
  if (out.binding.draggable && type != "attractor") {
    fail(f.require("draggable"), "only an attractor can be dragged");
  }
  try {
    calder::validate(out.field);
  } catch (const Error& e) {
    fail(t, e.what());
  }
  return out;
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
