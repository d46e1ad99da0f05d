// SPDX-License-Identifier: MIT
// calder: snapshots in memory, the format of docs/SNAPSHOTS.md (see
// calder/snapshot.hpp). Files and archives are in snapshot_files.cpp.
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "calder/error.hpp"
#include "calder/fields.hpp"
#include "calder/scene.hpp"
#include "calder/snapshot.hpp"
#include "calder/world.hpp"
#include "snapshot_bytes.hpp"

namespace calder {

namespace {

using snapshot_detail::In;
using snapshot_detail::Out;

// --- enumerations: their declaration order is their code (docs/SNAPSHOTS.md) ---

template <class E>
inline constexpr E kLast{};
template <>
inline constexpr Integrator kLast<Integrator> = Integrator::yoshida6;
template <>
inline constexpr UpdateOrder kLast<UpdateOrder> = UpdateOrder::sequential;
template <>
inline constexpr BoundaryKind kLast<BoundaryKind> = BoundaryKind::wrap;
template <>
inline constexpr BoundaryTiming kLast<BoundaryTiming> = BoundaryTiming::before_update;
template <>
inline constexpr Arithmetic kLast<Arithmetic> = Arithmetic::float32;
template <>
inline constexpr DistanceClamp kLast<DistanceClamp> = DistanceClamp::none;
template <>
inline constexpr MassProduct kLast<MassProduct> = MassProduct::masses_first;
template <>
inline constexpr Edge kLast<Edge> = Edge::bottom;
template <>
inline constexpr PairOrder kLast<PairOrder> = PairOrder::by_source;
template <>
inline constexpr NBodyMethod kLast<NBodyMethod> = NBodyMethod::barnes_hut;
template <>
inline constexpr PressAction kLast<PressAction> = PressAction::toss;
template <>
inline constexpr Draw::Kind kLast<Draw::Kind> = Draw::Kind::linear;
template <>
inline constexpr RadiusRule::Kind kLast<RadiusRule::Kind> = RadiusRule::Kind::per_sqrt_mass;
template <>
inline constexpr BodyGroup::Layout kLast<BodyGroup::Layout> = BodyGroup::Layout::orbit;

// The codes are part of the format: an enumerator moved or inserted shows here.
static_assert(static_cast<int>(Integrator::rk4) == 2 && static_cast<int>(Integrator::ias15) == 3 &&
              static_cast<int>(Integrator::yoshida6) == 5 &&
              static_cast<int>(BoundaryKind::wrap) == 2);
static_assert(static_cast<int>(Arithmetic::float32) == 2 &&
              static_cast<int>(DistanceClamp::none) == 2);
static_assert(static_cast<int>(Edge::bottom) == 3 &&
              static_cast<int>(NBodyMethod::barnes_hut) == 2);
static_assert(static_cast<int>(PressAction::toss) == 2 &&
              static_cast<int>(Draw::Kind::linear) == 2);
static_assert(static_cast<int>(RadiusRule::Kind::per_sqrt_mass) == 2 &&
              static_cast<int>(BodyGroup::Layout::orbit) == 1);

template <class E>
requires std::is_enum_v<E>
void put(Out& out, E value) { out.u32(static_cast<std::uint32_t>(value)); }
template <class E>
requires std::is_enum_v<E>
void get(In& in, E& value) {
  const std::uint32_t code = in.u32();
  if (code > static_cast<std::uint32_t>(kLast<E>)) {
    in.fail("an enumeration has the unknown code " + std::to_string(code));
  }
  value = static_cast<E>(code);
}

// --- values ---

void put(Out& out, double v) { out.f64(v); }
void get(In& in, double& v) { v = in.f64(); }
void put(Out& out, bool v) { out.u8(v ? 1 : 0); }
void get(In& in, bool& v) { v = in.boolean(); }
void put(Out& out, int v) { out.u32(static_cast<std::uint32_t>(v)); }
void get(In& in, int& v) { v = static_cast<int>(static_cast<std::int32_t>(in.u32())); }
void put(Out& out, Vec2 v) {
  out.f64(v.x);
  out.f64(v.y);
}
void get(In& in, Vec2& v) {
  v.x = in.f64();
  v.y = in.f64();
}
void put(Out& out, const Rect& r) {
  for (const double v : {r.x, r.y, r.w, r.h}) out.f64(v);
}
void get(In& in, Rect& r) {
  for (double* v : {&r.x, &r.y, &r.w, &r.h}) *v = in.f64();
}

void put(Out& out, const AttractionLaw& law) {
  if (law.custom) throw Error("a law with a custom function (C++ code) can't be saved");
  out.f64(law.G);
  put(out, law.clamp);
  out.f64(law.min);
  out.f64(law.max);
  out.f64(law.softening);
  put(out, law.product);
  out.f64(law.exponent);
  out.f64(law.repulsion);
  out.f64(law.repulsion_exponent);
}
void get(In& in, AttractionLaw& law) {
  law.G = in.f64();
  get(in, law.clamp);
  law.min = in.f64();
  law.max = in.f64();
  law.softening = in.f64();
  get(in, law.product);
  law.exponent = in.f64();
  law.repulsion = in.f64();
  law.repulsion_exponent = in.f64();
}

void put(Out& out, const std::optional<CentralBody>& c) {
  put(out, c.has_value());
  if (c) {
    put(out, c->position);
    out.f64(c->mass);
  }
}
void get(In& in, std::optional<CentralBody>& c) {
  c.reset();
  if (!in.boolean()) return;
  CentralBody body;
  get(in, body.position);
  body.mass = in.f64();
  c = body;
}

void put(Out& out, const Boundary& b) {
  put(out, b.kind);
  out.f64(b.restitution);
  put(out, b.use_radius);
  for (const bool e : {b.edges.left, b.edges.right, b.edges.top, b.edges.bottom}) put(out, e);
  put(out, b.timing);
  out.f64(b.inset);
  put(out, b.periodic);
}
void get(In& in, Boundary& b) {
  get(in, b.kind);
  b.restitution = in.f64();
  b.use_radius = in.boolean();
  for (bool* e : {&b.edges.left, &b.edges.right, &b.edges.top, &b.edges.bottom}) *e = in.boolean();
  get(in, b.timing);
  b.inset = in.f64();
  b.periodic = in.boolean();
}

// --- fields: the kind's name, enabled, then each parameter of its FieldKind
// as key and value, so that a field written by another kind list is refused
// by name, never misread ---

void put_field(Out& out, const Field& field) {
  std::visit(
      [&out](const auto& f) {
        using F = std::decay_t<decltype(f)>;
        if constexpr (!in_scene_files<F>()) {
          throw Error(std::string("a ") + FieldKind<F>::name +
                      " field holds C++ code: a snapshot can't hold it");
        } else {
          out.str(FieldKind<F>::name);
          put(out, f.enabled);
          std::apply([&](const auto&... p) { ((out.str(p.key), put(out, f.*(p.member))), ...); },
                     FieldKind<F>::parameters);
        }
      },
      field);
}

template <class F>
void get_kind(In& in, const std::string& name, std::optional<Field>& field) {
  if constexpr (in_scene_files<F>()) {
    if (field || name != FieldKind<F>::name) return;
    F f{};
    f.enabled = in.boolean();
    std::apply(
        [&](const auto&... p) {
          const auto one = [&](const auto& parameter) {
            const std::string key = in.str();
            if (key != parameter.key) {
              in.fail("field " + name + ": expected the parameter '" + parameter.key +
                      "', found '" + detail::printable(key) + "'");
            }
            get(in, f.*(parameter.member));
          };
          (one(p), ...);
        },
        FieldKind<F>::parameters);
    field = Field{std::move(f)};
  }
}

Field get_field(In& in) {
  const std::string name = in.str();
  std::optional<Field> field;
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    (get_kind<std::variant_alternative_t<I, Field>>(in, name, field), ...);
  }
  (std::make_index_sequence<std::variant_size_v<Field>>());
  if (!field) in.fail("unknown field kind '" + detail::printable(name) + "'");
  return std::move(*field);
}

// --- the scene ---

void put(Out& out, const Draw& d) {
  put(out, d.kind);
  for (const double v : {d.value, d.min, d.max, d.step}) out.f64(v);
}
void get(In& in, Draw& d) {
  get(in, d.kind);
  for (double* v : {&d.value, &d.min, &d.max, &d.step}) *v = in.f64();
}

void put_world_def(Out& out, const WorldDef& w) {
  for (const double v : {w.width, w.height, w.dt}) out.f64(v);
  put(out, w.integrator);
  put(out, w.update_order);
  put(out, w.boundary);
  out.u32(w.seed);
  put(out, w.arithmetic);
  put(out, w.threads);
  out.f64(w.max_speed);
}
void get_world_def(In& in, WorldDef& w) {
  for (double* v : {&w.width, &w.height, &w.dt}) *v = in.f64();
  get(in, w.integrator);
  get(in, w.update_order);
  get(in, w.boundary);
  w.seed = in.u32();
  get(in, w.arithmetic);
  get(in, w.threads);
  w.max_speed = in.f64();
}

void put(Out& out, const BodyGroup& g) {
  put(out, g.layout);
  out.u64(g.count);
  for (const Draw* d : {&g.x, &g.y, &g.mass, &g.vx, &g.vy}) put(out, *d);
  put(out, g.center);
  put(out, g.distance);
  put(out, g.speed);
  put(out, g.radius.kind);
  out.f64(g.radius.k);
  put(out, g.friction.has_value());
  out.f64(g.friction.value_or(0.0));
  out.f64(g.drag_area);
}
void get(In& in, BodyGroup& g) {
  get(in, g.layout);
  const std::uint64_t count = in.u64();
  if (count > max_bodies) in.fail("a body group of " + std::to_string(count) + " bodies");
  g.count = static_cast<std::size_t>(count);
  for (Draw* d : {&g.x, &g.y, &g.mass, &g.vx, &g.vy}) get(in, *d);
  get(in, g.center);
  get(in, g.distance);
  get(in, g.speed);
  get(in, g.radius.kind);
  g.radius.k = in.f64();
  const bool has_friction = in.boolean();
  const double friction = in.f64();
  g.friction = has_friction ? std::optional<double>(friction) : std::nullopt;
  g.drag_area = in.f64();
}

void put(Out& out, const SceneField& f) {
  put_field(out, f.field);
  for (const bool b :
       {f.binding.while_pressed, f.binding.follow_mouse, f.binding.draggable, f.visible}) {
    put(out, b);
  }
}
void get(In& in, SceneField& f) {
  f.field = get_field(in);
  for (bool* b :
       {&f.binding.while_pressed, &f.binding.follow_mouse, &f.binding.draggable, &f.visible}) {
    *b = in.boolean();
  }
}

void put(Out& out, const InputScript& input) {
  out.u32(static_cast<std::uint32_t>(input.mouse_pressed.size()));
  for (const FrameRange& r : input.mouse_pressed) {
    out.i64(r.first);
    out.i64(r.last);
  }
  put(out, input.mouse);
  out.u32(static_cast<std::uint32_t>(input.moves.size()));
  for (const MouseMove& m : input.moves) {
    out.i64(m.frame);
    put(out, m.position);
  }
}
void get(In& in, InputScript& input) {
  input.mouse_pressed.resize(in.count(16));
  for (FrameRange& r : input.mouse_pressed) {
    r.first = in.i64();
    r.last = in.i64();
  }
  get(in, input.mouse);
  input.moves.resize(in.count(24));
  for (MouseMove& m : input.moves) {
    m.frame = in.i64();
    get(in, m.position);
  }
}

void put(Out& out, const SceneLook& look) {
  put(out, look.trails);
  for (const double v : {look.trail_alpha, look.body_gray, look.body_alpha}) out.f64(v);
  put(out, look.squares);
}
void get(In& in, SceneLook& look) {
  look.trails = in.boolean();
  for (double* v : {&look.trail_alpha, &look.body_gray, &look.body_alpha}) *v = in.f64();
  look.squares = in.boolean();
}

// Counted lists of a scene: a count, then the items.
template <class T>
void put_list(Out& out, const std::vector<T>& items) {
  out.u32(static_cast<std::uint32_t>(items.size()));
  for (const T& item : items) put(out, item);
}
template <class T>
void get_list(In& in, std::vector<T>& items, std::size_t min_item_bytes) {
  items.resize(in.count(min_item_bytes));
  for (T& item : items) get(in, item);
}

Bytes scene_section(const Scene& s) {
  Out out;
  out.str(s.name);
  out.str(s.description);
  put_world_def(out, s.world);
  put_list(out, s.bodies);
  put_list(out, s.fields);
  out.i64(s.frames);
  put(out, s.on_press);
  put(out, s.input);
  put(out, s.origin);
  put(out, s.look);
  put(out, s.edges_first);
  return std::move(out.bytes);
}

Scene read_scene(In& in) {
  Scene s;
  s.name = in.str();
  s.description = in.str();
  get_world_def(in, s.world);
  get_list(in, s.bodies, 8);
  get_list(in, s.fields, 8);
  s.frames = in.i64();
  get(in, s.on_press);
  get(in, s.input);
  get(in, s.origin);
  get(in, s.look);
  get(in, s.edges_first);
  in.finish();
  return s;
}

// --- the simulation's progress ---

Bytes progress_section(const SimulationProgress& p) {
  Out out;
  out.i64(p.frame);
  put(out, p.was_pressed);
  put(out, p.last_mouse);
  out.i64(p.tossed ? static_cast<std::int64_t>(*p.tossed) : -1);
  put(out, p.toss_offset);
  out.u32(static_cast<std::uint32_t>(p.grabs.size()));
  for (const SimulationProgress::Grab& g : p.grabs) {
    out.u64(g.field);
    put(out, g.offset);
  }
  return std::move(out.bytes);
}

SimulationProgress read_progress(In& in) {
  SimulationProgress p;
  p.frame = in.i64();
  p.was_pressed = in.boolean();
  get(in, p.last_mouse);
  const std::int64_t tossed = in.i64();
  if (tossed < -1) in.fail("a tossed body of index " + std::to_string(tossed));
  if (tossed >= 0) p.tossed = static_cast<std::size_t>(tossed);
  get(in, p.toss_offset);
  p.grabs.resize(in.count(24));
  for (SimulationProgress::Grab& g : p.grabs) {
    g.field = static_cast<std::size_t>(in.u64());
    get(in, g.offset);
  }
  in.finish();
  return p;
}

// --- the world: settings and clock, generators, fields, bodies ---

Bytes world_section(const World& world) {
  Out out;
  put_world_def(out, world.def());
  out.f64(world.time());
  out.i64(world.step_count());
  return std::move(out.bytes);
}

Bytes random_section(const World& world) {
  Out out;
  const Random& random = world.random();
  out.u32(random.state());
  put(out, random.spare_gaussian().has_value());
  out.f64(random.spare_gaussian().value_or(0.0));
  const Noise& noise = world.noise();
  out.u32(noise.seed());
  put(out, noise.octaves());
  out.f64(noise.falloff());
  return std::move(out.bytes);
}

Bytes fields_section(const World& world) {
  Out out;
  out.u32(static_cast<std::uint32_t>(world.fields().size()));
  for (std::size_t k = 0; k < world.fields().size(); ++k) {
    try {
      put_field(out, world.fields()[k]);
    } catch (const Error& e) {
      rethrow_with_context(e, "snapshot: field " + std::to_string(k) + ": ");
    }
  }
  return std::move(out.bytes);
}

// u64 count, u32 columns, u32 0, a 16-byte name per column, then each
// column's count doubles: every column 8-byte aligned (numpy maps them).
Bytes bodies_section(const World& world) {
  const BodyView b = world.bodies();
  Out out;
  out.u64(b.size());
  std::uint32_t columns = 0;
  for_each_column([&columns](const char*, std::span<const double>) { ++columns; }, b);
  out.u32(columns);
  out.u32(0);
  for_each_column([&out](const char* name, std::span<const double>) { out.name16(name); }, b);
  for_each_column([&out](const char*, std::span<const double> column) { out.f64s(column); }, b);
  return std::move(out.bytes);
}

// Everything but the scene and the progress: the world's sections.
void put_world_sections(snapshot_detail::SectionWriter& w, const World& world) {
  w.add("WRLD", world_section(world));
  w.add("RAND", random_section(world));
  w.add("FLDS", fields_section(world));
  w.add("BODY", bodies_section(world));
}

WorldDef read_world_def(In& in, double& time, std::int64_t& steps) {
  WorldDef def;
  get_world_def(in, def);
  time = in.f64();
  steps = in.i64();
  in.finish();
  return def;
}

void read_random(In& in, World& world) {
  const std::uint32_t state = in.u32();
  const bool has_spare = in.boolean();
  const double spare = in.f64();
  world.random().restore(state, has_spare ? std::optional<double>(spare) : std::nullopt);
  const std::uint32_t seed = in.u32();
  int octaves = 0;
  get(in, octaves);
  const double falloff = in.f64();
  in.finish();
  world.noise().noise_seed(seed);
  world.noise().noise_detail(octaves, falloff);
}

void read_fields(In& in, World& world) {
  const std::size_t count = in.count(8);
  for (std::size_t k = 0; k < count; ++k) world.add_field(get_field(in));
  in.finish();
}

// The columns as numpy would see them: checked names, then spans.
void read_bodies(In& in, World& world, double time, std::int64_t steps) {
  const std::uint64_t n = in.u64();
  const std::uint32_t columns = in.u32();
  (void)in.u32();
  std::vector<std::string> expected;
  for_each_column([&expected](const char* name, const auto&) { expected.emplace_back(name); },
                  BodyColumnsOf<char>{});
  if (columns != expected.size()) {
    in.fail(std::to_string(columns) + " body columns, expected " + std::to_string(expected.size()));
  }
  for (const std::string& name : expected) {
    const std::string found = in.name16();
    if (found != name) {
      in.fail("body column '" + detail::printable(found) + "' where '" + name + "' belongs");
    }
  }
  if (n > max_bodies || in.left() != n * 8 * columns) {
    in.fail(std::to_string(n) + " bodies need " + std::to_string(n * 8 * columns) +
            " bytes of columns, the section has " + std::to_string(in.left()));
  }
  BodyColumnsOf<std::vector<double>> data;
  for_each_column(
      [&in, n](const char*, std::vector<double>& column) {
        column.resize(static_cast<std::size_t>(n));
        in.f64s(column);
      },
      data);
  BodyColumns spans;
  for_each_property(
      [](const char*, std::span<const double>& to, const std::vector<double>& from) { to = from; },
      spans, data);
  spans.x = data.x;
  spans.y = data.y;
  spans.vx = data.vx;
  spans.vy = data.vy;
  world.add_bodies(spans);
  world.restore(time, steps, data.ax, data.ay);
}

// --- the adaptive integrator (section ADPT, format version 2) ---

bool has_adaptive_settings(const WorldDef& w) {
  return w.integrator == Integrator::ias15 || w.tolerance != kDefaultTolerance;
}

// f64 the scene's tolerance, f64 the world's, the carried state, the counts,
// then four arrays, each u64 length and its f64s.
Bytes adaptive_section(const World& world, double scene_tolerance) {
  Out out;
  const AdaptiveState& s = world.adaptive_state();
  for (const double v :
       {scene_tolerance, world.tolerance(), s.next_step, s.last_step, s.clock_compensation}) {
    out.f64(v);
  }
  const AdaptiveStats& stats = s.stats;
  for (const std::int64_t v :
       {stats.steps, stats.rejected, stats.force_evaluations, stats.iterations}) {
    out.i64(v);
  }
  for (const double v :
       {stats.smallest_step, stats.closest_approach, stats.closest_approach_time}) {
    out.f64(v);
  }
  for (const std::vector<double>* v :
       {&s.position_compensation, &s.velocity_compensation, &s.coefficients, &s.correction}) {
    out.u64(v->size());
    out.f64s(*v);
  }
  return std::move(out.bytes);
}

// Adds ADPT when the world or the scene needs it; the snapshot is then version 2.
void put_adaptive(snapshot_detail::SectionWriter& w, const World& world, const WorldDef& scene) {
  if (!has_adaptive_settings(world.def()) && !has_adaptive_settings(scene)) return;
  w.add("ADPT", adaptive_section(world, scene.tolerance));
  w.require_version(2);
}

struct AdaptiveSection {
  double scene_tolerance = kDefaultTolerance;
  double world_tolerance = kDefaultTolerance;
  AdaptiveState state;
};

AdaptiveSection read_adaptive(In& in) {
  AdaptiveSection a;
  AdaptiveState& s = a.state;
  for (double* v : {&a.scene_tolerance, &a.world_tolerance, &s.next_step, &s.last_step,
                    &s.clock_compensation}) {
    *v = in.f64();
  }
  AdaptiveStats& stats = s.stats;
  for (std::int64_t* v :
       {&stats.steps, &stats.rejected, &stats.force_evaluations, &stats.iterations}) {
    *v = in.i64();
  }
  for (double* v : {&stats.smallest_step, &stats.closest_approach, &stats.closest_approach_time}) {
    *v = in.f64();
  }
  for (std::vector<double>* v :
       {&s.position_compensation, &s.velocity_compensation, &s.coefficients, &s.correction}) {
    const std::uint64_t n = in.u64();
    if (n > in.left() / 8)
      in.fail("an array of " + std::to_string(n) + " runs past the section's end");
    v->resize(static_cast<std::size_t>(n));
    in.f64s(*v);
  }
  in.finish();
  return a;
}

World read_world(const snapshot_detail::Sections& sections, const Backends& backends) {
  double time = 0.0;
  std::int64_t steps = 0;
  In wrld = sections.open("WRLD");
  WorldDef def = read_world_def(wrld, time, steps);
  def.backends = backends;
  World world(def);
  In rand = sections.open("RAND");
  read_random(rand, world);
  In fields = sections.open("FLDS");
  read_fields(fields, world);
  In bodies = sections.open("BODY");
  read_bodies(bodies, world, time, steps);
  if (sections.has("ADPT")) {
    In adaptive = sections.open("ADPT");
    const AdaptiveSection a = read_adaptive(adaptive);
    world.set_tolerance(a.world_tolerance);
    world.restore_adaptive(a.state);
  }
  return world;
}

// Runs read, turning the errors of values that passed the checksums but not
// calder's checks (a crafted file) into InputError naming the file.
template <class Read>
auto reading(const std::string& source, Read read) {
  try {
    return read();
  } catch (const InputError&) {
    throw;
  } catch (const Error& e) {
    throw InputError(detail::printable(source, 240) + ": " + e.what());
  }
}

}  // namespace

Bytes to_snapshot(const Simulation& simulation) {
  snapshot_detail::SectionWriter w;
  w.add("SCEN", scene_section(simulation.scene()));
  w.add("SIMU", progress_section(simulation.progress()));
  put_world_sections(w, simulation.world());
  put_adaptive(w, simulation.world(), simulation.scene().world);
  return w.finish();
}

Bytes to_snapshot(const World& world) {
  snapshot_detail::SectionWriter w;
  put_world_sections(w, world);
  put_adaptive(w, world, world.def());
  return w.finish();
}

Simulation simulation_from_snapshot(std::span<const std::uint8_t> bytes,
                                    const std::string& source) {
  return reading(source, [&] {
    const snapshot_detail::Sections sections(bytes, source);
    if (!sections.has("SCEN")) {
      throw InputError(detail::printable(source, 240) +
                       ": a world's snapshot (no scene): load it as a World");
    }
    In scene_in = sections.open("SCEN");
    Scene scene = read_scene(scene_in);
    if (sections.has("ADPT")) {
      In adaptive = sections.open("ADPT");
      scene.world.tolerance = read_adaptive(adaptive).scene_tolerance;
      detail::require_positive(scene.world.tolerance, "snapshot", "the scene's tolerance");
    }
    World world = read_world(sections, scene.world.backends);
    In progress = sections.open("SIMU");
    return Simulation(std::move(scene), std::move(world), read_progress(progress));
  });
}

World world_from_snapshot(std::span<const std::uint8_t> bytes, const std::string& source) {
  return reading(source, [&] {
    const snapshot_detail::Sections sections(bytes, source);
    return read_world(sections, Backends{});
  });
}

SnapshotInfo snapshot_info(std::span<const std::uint8_t> bytes, const std::string& source) {
  const snapshot_detail::Sections sections(bytes, source);
  SnapshotInfo info;
  double time = 0.0;
  In wrld = sections.open("WRLD");
  (void)read_world_def(wrld, time, info.steps);
  info.time = time;
  In body = sections.open("BODY");
  info.bodies = static_cast<std::size_t>(body.u64());
  if (sections.has("SCEN")) {
    info.has_scene = true;
    In scene = sections.open("SCEN");
    info.scene = scene.str();
    In progress = sections.open("SIMU");
    info.frame = progress.i64();
  }
  return info;
}

}  // namespace calder
