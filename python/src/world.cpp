// SPDX-License-Identifier: MIT
// World, Mover, their settings, the diagnostics, and numpy views of the
// body arrays.
//
// Views: world.x (and y, vx, vy, mass, radius, friction, drag_area) returns
// a new read-only numpy array over the world's own memory at each access. Its
// base holds the world and counts as a live view; while any view is alive,
// adding bodies (which may move the arrays and free the old ones) raises
// calder.Error. Stepping and setters change the values a view shows, never
// its memory. So no view can read freed memory: it is refused, not detected.
#include <pybind11/stl.h>

#include <algorithm>
#include <calder/diagnostics.hpp>
#include <calder/error.hpp>
#include <calder/scene.hpp>
#include <calder/trajectory.hpp>
#include <calder/world.hpp>
#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bindings.hpp"

namespace calder::python {

namespace {

// An id as C++'s BodyId; the world checks it (an index out of range raises
// with the C++ message). Numbers no BodyId can hold name no body either.
BodyId id_of(const World& world, std::int64_t index, const char* where) {
  if (index < 0 || index >= std::int64_t{UINT32_MAX}) {
    throw Error(std::string(where) + ": no body with id " + std::to_string(index) +
                " (the world has " + std::to_string(world.body_count()) + " bodies)");
  }
  return BodyId{static_cast<std::uint32_t>(index)};
}

py::object add_bodies(World& world, const py::handle& x, const py::handle& y, const py::handle& vx,
                      const py::handle& vy, const py::handle& mass, const py::handle& radius,
                      const py::object& friction, const py::handle& drag_area) {
  const char* where = "World.add_bodies";
  const BodyArguments arguments(where, x, y, vx, vy, mass, radius, friction, drag_area);
  require_resizable(world, where, true);
  const std::size_t first =
      arguments.empty() ? world.body_count() : world.add_bodies(arguments.columns()).index;
  return py::module_::import("builtins").attr("range")(first, world.body_count());
}

// Bulk setters: all values are checked first (by the per-body setter, on
// the first bad one), then all are set.
void set_pairs(World& world, const py::handle& a, const py::handle& b, const char* where,
               void (World::*setter)(BodyId, Vec2)) {
  const Column ca(a, where, "the first array"), cb(b, where, "the second array");
  const std::span<const double> sa = ca.span(), sb = cb.span();
  const std::size_t n = world.body_count();
  for (const std::size_t size : {sa.size(), sb.size()}) {
    if (size != n && size != 1) {
      throw py::value_error(std::string(where) + ": got " + std::to_string(size) +
                            " values for a world of " + std::to_string(n) + " bodies");
    }
  }
  const auto value = [&](std::size_t i) {
    return Vec2{sa[sa.size() == 1 ? 0 : i], sb[sb.size() == 1 ? 0 : i]};
  };
  for (std::size_t i = 0; i < n; ++i) {
    if (!value(i).is_finite())
      (world.*setter)(BodyId{static_cast<std::uint32_t>(i)}, value(i));  // throws
  }
  for (std::size_t i = 0; i < n; ++i)
    (world.*setter)(BodyId{static_cast<std::uint32_t>(i)}, value(i));
}

py::array view(const py::object& self, std::span<const double> BodyView::*column) {
  const World& world = self.cast<const World&>();
  return body_view(self, world, world.bodies().*column);
}

}  // namespace

Column::Column(const py::handle& given, const char* where, const char* name) {
  if (py::isinstance<py::float_>(given) || py::isinstance<py::int_>(given)) {
    scalar = given.cast<double>();
    return;
  }
  is_array = true;
  values = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(given);
  if (!values || values.ndim() != 1) {
    throw py::type_error(std::string(where) + ": " + name +
                         " must be a number or a 1-D array of numbers");
  }
}

std::span<const double> Column::span() const {
  if (!is_array) return {&scalar, 1};
  return {values.data(), static_cast<std::size_t>(values.shape(0))};
}

BodyArguments::BodyArguments(const char* where, const py::handle& x, const py::handle& y,
                             const py::handle& vx, const py::handle& vy, const py::handle& mass,
                             const py::handle& radius, const py::object& friction,
                             const py::handle& drag_area)
    : x_(x, where, "x"),
      y_(y, where, "y"),
      vx_(vx, where, "vx"),
      vy_(vy, where, "vy"),
      mass_(mass, where, "mass"),
      radius_(radius, where, "radius"),
      drag_area_(drag_area, where, "drag_area") {
  if (!friction.is_none()) friction_.emplace(friction, where, "friction");
  const std::pair<const char*, const Column*> named[] = {
      {"x", &x_},
      {"y", &y_},
      {"vx", &vx_},
      {"vy", &vy_},
      {"mass", &mass_},
      {"radius", &radius_},
      {"friction", friction_ ? &*friction_ : nullptr},
      {"drag_area", &drag_area_}};
  const char* empty_name = nullptr;
  const char* longest_name = nullptr;
  std::size_t longest = 0;
  for (const auto& [name, column] : named) {
    if (column == nullptr || !column->is_array) continue;
    const std::size_t size = column->span().size();
    if (size == 0 && empty_name == nullptr) empty_name = name;
    if (size > longest) {
      longest = size;
      longest_name = name;
    }
  }
  if (empty_name != nullptr && longest > 1) {
    throw Error(std::string(where) + ": " + empty_name + " is empty but " + longest_name + " has " +
                std::to_string(longest) + " values");
  }
  empty_ = empty_name != nullptr;
}

BodyColumns BodyArguments::columns() const {
  return {x_.span(),
          y_.span(),
          vx_.span(),
          vy_.span(),
          mass_.span(),
          radius_.span(),
          friction_ ? friction_->span() : std::span<const double>{},
          drag_area_.span()};
}

std::vector<BodyDef> BodyArguments::body_defs(const char* where) const {
  // World::add_bodies checks and spreads the columns (one value for all,
  // defaults) into a scratch world: one piece of code for what a column means.
  if (empty_) return {};
  World scratch;
  try {
    scratch.add_bodies(columns());
  } catch (const Error& e) {
    const std::string message = e.what();
    const std::string prefix = "World::add_bodies";
    throw Error(message.starts_with(prefix) ? where + message.substr(prefix.size()) : message);
  }
  const BodyView b = scratch.bodies();
  std::vector<BodyDef> defs(b.size());
  for (std::size_t i = 0; i < b.size(); ++i) {
    defs[i] = {b.position(i),
               b.velocity(i),
               b.mass[i],
               b.radius[i],
               std::isnan(b.friction[i]) ? std::nullopt : std::optional<double>(b.friction[i]),
               b.drag_area[i]};
  }
  return defs;
}

void bind_world(py::module_& m) {
  py::enum_<Integrator>(m, "Integrator")
      .value("semi_implicit_euler", Integrator::semi_implicit_euler,
             "the book's update: v += a dt; x += v dt")
      .value("velocity_verlet", Integrator::velocity_verlet)
      .value("rk4", Integrator::rk4)
      .value("ias15", Integrator::ias15,
             "adaptive 15th order (Rein & Spiegel 2015): steps of dt made of internal steps "
             "to the tolerance")
      .value("yoshida4", Integrator::yoshida4, "4th-order symplectic composition of leapfrog")
      .value("yoshida6", Integrator::yoshida6, "6th-order symplectic composition of leapfrog");
  py::enum_<UpdateOrder>(m, "UpdateOrder")
      .value("simultaneous", UpdateOrder::simultaneous)
      .value("sequential", UpdateOrder::sequential, "body by body, as example 2.9");
  py::enum_<BoundaryKind>(m, "BoundaryKind")
      .value("none", BoundaryKind::none)
      .value("bounce", BoundaryKind::bounce)
      .value("wrap", BoundaryKind::wrap);
  py::enum_<BoundaryTiming>(m, "BoundaryTiming")
      .value("after_update", BoundaryTiming::after_update)
      .value("before_update", BoundaryTiming::before_update);
  py::enum_<Arithmetic>(m, "Arithmetic")
      .value("book", Arithmetic::book, "IEEE double in the book's order: p5.js's bits")
      .value("float64", Arithmetic::float64, "double with fused multiply-adds, ~2x faster")
      .value("float32", Arithmetic::float32, "float32 within each batch of steps");

  py::class_<Edges>(m, "Edges", "Which canvas edges a bounce applies to")
      .def(py::init([](bool left, bool right, bool top, bool bottom) {
             return Edges{left, right, top, bottom};
           }),
           py::arg("left") = true, py::arg("right") = true, py::arg("top") = true,
           py::arg("bottom") = true)
      .def_readwrite("left", &Edges::left)
      .def_readwrite("right", &Edges::right)
      .def_readwrite("top", &Edges::top)
      .def_readwrite("bottom", &Edges::bottom);

  py::class_<Boundary>(m, "Boundary",
                       "What happens at the canvas edges: Boundary.none(), Boundary.bounce(...), "
                       "Boundary.wrap(...)")
      .def(py::init<>())
      .def_static("none", &Boundary::none)
      .def_static("bounce", &Boundary::bounce, py::arg("restitution") = 1.0,
                  py::arg("use_radius") = false, py::arg("edges") = Edges{})
      .def_static("wrap", &Boundary::wrap, py::arg("use_radius") = false)
      .def_readwrite("kind", &Boundary::kind)
      .def_readwrite("restitution", &Boundary::restitution)
      .def_readwrite("use_radius", &Boundary::use_radius)
      .def_readwrite("edges", &Boundary::edges)
      .def_readwrite("timing", &Boundary::timing)
      .def("__repr__", [](const Boundary& b) {
        const char* kinds[] = {"none", "bounce", "wrap"};
        return std::string("Boundary(kind=") + kinds[static_cast<int>(b.kind)] +
               ", restitution=" + format_number(b.restitution) +
               ", use_radius=" + (b.use_radius ? "True" : "False") + ")";
      });

  py::class_<Mover> mover(m, "Mover",
                          "A handle to one body with the book's vocabulary (apply_force, update,\n"
                          "check_edges, contact_edge). Keeps its world alive.");
  py::class_<World> world(
      m, "World",
      "Bodies with mass in contiguous arrays, the fields acting on them, and a step.\n\n"
      "Bodies are named by integer ids (0, 1, ...); world.mover(id) gives the book's\n"
      "Mover handle. world.x, world.y, world.vx, world.vy, world.masses, world.radii,\n"
      "world.frictions and world.drag_areas are read-only numpy views of the arrays\n"
      "(zero copy, live: they show the state after each step). While a view is\n"
      "alive the world cannot gain bodies (calder.Error): delete views before adding.\n"
      "Bad arguments raise calder.Error (a ValueError) with calder's message; a step\n"
      "that fails leaves the world as it was.");
  world
      .def(py::init([](double width, double height, double dt, Integrator integrator,
                       UpdateOrder update_order, const Boundary& boundary, std::uint32_t seed,
                       Arithmetic arithmetic, int threads, double tolerance,
                       const std::string& device) {
             WorldDef def{width,    height, dt,         integrator, update_order,
                          boundary, seed,   arithmetic, threads};
             def.tolerance = tolerance;
             use_device(def, device);  // device.cpp: "gpu" steps on calder::gpu
             return std::make_unique<World>(def);
           }),
           py::kw_only(), py::arg("width") = 640.0, py::arg("height") = 240.0, py::arg("dt") = 1.0,
           py::arg("integrator") = Integrator::semi_implicit_euler,
           py::arg("update_order") = UpdateOrder::simultaneous, py::arg("boundary") = Boundary{},
           py::arg("seed") = 0, py::arg("arithmetic") = Arithmetic::book, py::arg("threads") = 0,
           py::arg("tolerance") = kDefaultTolerance, py::arg("device") = "cpu")
      // --- bodies ---
      .def(
          "add_body",
          [](World& w, Vec2 position, Vec2 velocity, double mass, double radius,
             std::optional<double> friction, double drag_area) {
            require_resizable(w, "World.add_body", true);
            return w.add_body({position, velocity, mass, radius, friction, drag_area}).index;
          },
          py::kw_only(), py::arg("position") = Vec2{}, py::arg("velocity") = Vec2{},
          py::arg("mass") = 1.0, py::arg("radius") = 0.0, py::arg("friction") = py::none(),
          py::arg("drag_area") = 1.0, "Adds a body; returns its id")
      .def(
          "add_mover",
          [](World& w, Vec2 position, Vec2 velocity, double mass, double radius,
             std::optional<double> friction, double drag_area) {
            require_resizable(w, "World.add_mover", true);
            return w.add_mover({position, velocity, mass, radius, friction, drag_area});
          },
          py::kw_only(), py::arg("position") = Vec2{}, py::arg("velocity") = Vec2{},
          py::arg("mass") = 1.0, py::arg("radius") = 0.0, py::arg("friction") = py::none(),
          py::arg("drag_area") = 1.0, py::keep_alive<0, 1>(),
          "Adds a body; returns its Mover handle")
      .def("add_bodies", &add_bodies, py::arg("x"), py::arg("y"), py::arg("vx") = 0.0,
           py::arg("vy") = 0.0, py::arg("mass") = 1.0, py::arg("radius") = 0.0,
           py::arg("friction") = py::none(), py::arg("drag_area") = 1.0,
           "Adds len(x) bodies from arrays (or numbers, the same for all), all or none:\n"
           "every body is checked first. friction NaN: the Friction field's mu.\n"
           "Returns the range of their ids.")
      .def(
          "mover", [](World& w, std::int64_t id) { return w.mover(id_of(w, id, "World::mover")); },
          py::arg("id"), py::keep_alive<0, 1>())
      .def_property_readonly("body_count", &World::body_count)
      .def("__len__", &World::body_count)
      .def("clear_bodies",
           [](World& w) {
             require_resizable(w, "World.clear_bodies", false);
             w.clear_bodies();
           })
      .def(
          "position",
          [](const World& w, std::int64_t id) {
            return w.position(id_of(w, id, "World::position"));
          },
          py::arg("id"))
      .def(
          "velocity",
          [](const World& w, std::int64_t id) {
            return w.velocity(id_of(w, id, "World::velocity"));
          },
          py::arg("id"))
      .def(
          "acceleration",
          [](const World& w, std::int64_t id) {
            return w.acceleration(id_of(w, id, "World::acceleration"));
          },
          py::arg("id"), "The acceleration accumulated since the body's last update")
      .def(
          "mass",
          [](const World& w, std::int64_t id) { return w.mass(id_of(w, id, "World::mass")); },
          py::arg("id"))
      .def(
          "radius",
          [](const World& w, std::int64_t id) { return w.radius(id_of(w, id, "World::radius")); },
          py::arg("id"))
      .def(
          "friction",
          [](const World& w, std::int64_t id) {
            return w.friction(id_of(w, id, "World::friction"));
          },
          py::arg("id"), "The body's own friction coefficient, or None")
      .def(
          "drag_area",
          [](const World& w, std::int64_t id) {
            return w.drag_area(id_of(w, id, "World::drag_area"));
          },
          py::arg("id"))
      .def(
          "set_position",
          [](World& w, std::int64_t id, Vec2 p) {
            w.set_position(id_of(w, id, "World::set_position"), p);
          },
          py::arg("id"), py::arg("position"))
      .def(
          "set_velocity",
          [](World& w, std::int64_t id, Vec2 v) {
            w.set_velocity(id_of(w, id, "World::set_velocity"), v);
          },
          py::arg("id"), py::arg("velocity"))
      .def(
          "set_mass",
          [](World& w, std::int64_t id, double mass) {
            w.set_mass(id_of(w, id, "World::set_mass"), mass);
          },
          py::arg("id"), py::arg("mass"))
      .def(
          "set_radius",
          [](World& w, std::int64_t id, double r) {
            w.set_radius(id_of(w, id, "World::set_radius"), r);
          },
          py::arg("id"), py::arg("radius"))
      .def(
          "set_friction",
          [](World& w, std::int64_t id, std::optional<double> mu) {
            w.set_friction(id_of(w, id, "World::set_friction"), mu);
          },
          py::arg("id"), py::arg("mu"))
      .def(
          "set_drag_area",
          [](World& w, std::int64_t id, double a) {
            w.set_drag_area(id_of(w, id, "World::set_drag_area"), a);
          },
          py::arg("id"), py::arg("area"))
      .def(
          "set_positions",
          [](World& w, const py::handle& x, const py::handle& y) {
            set_pairs(w, x, y, "World.set_positions", &World::set_position);
          },
          py::arg("x"), py::arg("y"), "Sets every body's position from two arrays, all or none")
      .def(
          "set_velocities",
          [](World& w, const py::handle& vx, const py::handle& vy) {
            set_pairs(w, vx, vy, "World.set_velocities", &World::set_velocity);
          },
          py::arg("vx"), py::arg("vy"), "Sets every body's velocity from two arrays, all or none")
      .def(
          "apply_force",
          [](World& w, std::int64_t id, Vec2 f) {
            w.apply_force(id_of(w, id, "World::apply_force"), f);
          },
          py::arg("id"), py::arg("force"), "acceleration += force / mass, one force at a time")
      .def(
          "update", [](World& w, std::int64_t id) { w.update(id_of(w, id, "World::update")); },
          py::arg("id"), "The book's update() for one body")
      .def(
          "apply_boundary",
          [](World& w, std::int64_t id, const std::optional<Boundary>& b) {
            const BodyId body = id_of(w, id, "World::apply_boundary");
            if (b)
              w.apply_boundary(body, *b);
            else
              w.apply_boundary(body);
          },
          py::arg("id"), py::arg("boundary") = py::none())
      .def(
          "touching",
          [](const World& w, std::int64_t id, Edge edge, double tolerance) {
            return w.touching(id_of(w, id, "World::touching"), edge, tolerance);
          },
          py::arg("id"), py::arg("edge"), py::arg("tolerance") = 1.0)
      // --- fields ---
      .def(
          "add",
          [](py::object self, py::handle field) {
            return add_field(self, self.cast<World&>(), field);
          },
          py::arg("field"),
          "Stores a copy of the field; returns a live handle to the stored one (set\n"
          "handle.enabled = False to switch it off, as the book's mouse does)")
      .def_property_readonly("fields",
                             [](py::object self) {
                               World& w = self.cast<World&>();
                               py::list handles;
                               for (std::size_t i = 0; i < w.fields().size(); ++i) {
                                 handles.append(field_handle(self, w, i));
                               }
                               return handles;
                             })
      .def(
          "field",
          [](py::object self, std::size_t i) { return field_handle(self, self.cast<World&>(), i); },
          py::arg("index"))
      .def("clear_fields", [](World& w) { clear_fields(w); })
      // --- stepping ---
      .def(
          "step", [](World& w, int count) { without_gil(w, "World.step", [&] { w.step(count); }); },
          py::arg("count") = 1,
          "Advances every body count steps (the GIL is released meanwhile). A failed\n"
          "step raises calder.Error and leaves the world as it was.")
      .def_property_readonly("time", &World::time)
      .def_property_readonly("step_count", &World::step_count)
      .def_property("dt", &World::dt, &World::set_dt)
      .def_property("integrator", &World::integrator, &World::set_integrator)
      .def_property("tolerance", &World::tolerance, &World::set_tolerance,
                    "ias15's step criterion (default 1e-9; smaller is more accurate)")
      .def_property_readonly(
          "adaptive_stats",
          [](const World& w) {
            const AdaptiveStats& s = w.adaptive_stats();
            py::dict d;
            d["steps"] = s.steps;
            d["rejected"] = s.rejected;
            d["force_evaluations"] = s.force_evaluations;
            d["iterations"] = s.iterations;
            d["smallest_step"] = s.smallest_step;
            d["closest_approach"] = s.closest_approach;
            d["closest_approach_time"] = s.closest_approach_time;
            return d;
          },
          "What ias15 counted: steps, rejected, force_evaluations, iterations, smallest_step, "
          "closest_approach (inf when not measured) and closest_approach_time")
      .def_property("update_order", &World::update_order, &World::set_update_order)
      .def_property("boundary", &World::boundary, &World::set_boundary)
      .def_property("arithmetic", &World::arithmetic, &World::set_arithmetic)
      .def_property("threads", &World::threads, &World::set_threads)
      .def_property_readonly("width", &World::width)
      .def_property_readonly("height", &World::height)
      .def_property_readonly(
          "random", [](World& w) -> Random& { return w.random(); },
          py::return_value_policy::reference_internal, "The world's generator (seeded with seed)")
      .def_property_readonly(
          "noise", [](World& w) -> Noise& { return w.noise(); },
          py::return_value_policy::reference_internal)
      // --- numpy views ---
      .def_property_readonly("x", [](py::object s) { return view(s, &BodyView::x); })
      .def_property_readonly("y", [](py::object s) { return view(s, &BodyView::y); })
      .def_property_readonly("vx", [](py::object s) { return view(s, &BodyView::vx); })
      .def_property_readonly("vy", [](py::object s) { return view(s, &BodyView::vy); })
      .def_property_readonly("masses", [](py::object s) { return view(s, &BodyView::mass); })
      .def_property_readonly("radii", [](py::object s) { return view(s, &BodyView::radius); })
      .def_property_readonly(
          "frictions", [](py::object s) { return view(s, &BodyView::friction); },
          "NaN for a body without its own coefficient")
      .def_property_readonly("drag_areas",
                             [](py::object s) { return view(s, &BodyView::drag_area); })
      .def_property_readonly(
          "live_views", [](const World& w) { return state_of(w).live_views; },
          "How many numpy views of this world's arrays are alive");

  mover.def("apply_force", &Mover::apply_force, py::arg("force"))
      .def("update", &Mover::update)
      .def("check_edges", py::overload_cast<>(&Mover::check_edges))
      .def("check_edges", py::overload_cast<const Boundary&>(&Mover::check_edges),
           py::arg("boundary"))
      .def("contact_edge", &Mover::contact_edge, py::arg("tolerance") = 1.0)
      .def_property("position", &Mover::position, &Mover::set_position)
      .def_property("velocity", &Mover::velocity, &Mover::set_velocity)
      .def_property_readonly("acceleration", &Mover::acceleration)
      .def_property_readonly("mass", &Mover::mass)
      .def_property_readonly("radius", &Mover::radius)
      .def("attract", &Mover::attract, py::arg("other"), py::arg("law") = AttractionLaw{})
      .def_property_readonly("id", [](const Mover& mv) { return mv.id().index; })
      .def_property_readonly("world", &Mover::world, py::return_value_policy::reference,
                             py::keep_alive<0, 1>());

  // --- diagnostics ---
  m.def("kinetic_energy", &kinetic_energy, py::arg("world"));
  m.def("potential_energy",
        py::overload_cast<const World&, const AttractionLaw&>(&potential_energy), py::arg("world"),
        py::arg("law"));
  m.def("potential_energy", py::overload_cast<const World&>(&potential_energy), py::arg("world"),
        "Of the world's attractors and mutual attraction");
  m.def("total_energy", &total_energy, py::arg("world"));
  py::class_<DisplayedEnergy>(m, "DisplayedEnergy",
                              "The energy a display shows (the HUD, `calder run`'s summary, "
                              "the web page): the potential in bounded time")
      .def_readonly("kinetic", &DisplayedEnergy::kinetic)
      .def_property_readonly("potential",
                             [](const DisplayedEnergy& e) -> std::optional<double> {
                               if (!e.has_potential) return std::nullopt;
                               return e.potential.value;
                             })
      .def_property_readonly("total", &DisplayedEnergy::total)
      .def_property_readonly("exact", &DisplayedEnergy::exact,
                             "False where the potential is a sampled estimate")
      .def_readonly("why_not", &DisplayedEnergy::why_not, "Why there is no potential");
  m.def("displayed_energy", &displayed_energy, py::arg("world"),
        py::arg("max_pairs") = kHudEnergyPairs,
        "Kinetic and potential energy, at most max_pairs pairs of each mutual attraction "
        "summed (past them a sampled estimate)");
  m.def("conserves_energy", &conserves_energy, py::arg("world"),
        "Whether the world's fields and boundary keep its total energy constant");
  m.def("relative_energy_error", &relative_energy_error, py::arg("start"), py::arg("now"),
        "|now - start| / |start| (|now - start| when start is 0)");
  m.def("start_energy", &start_energy, py::arg("simulation"),
        "The total energy of the simulation's scene at its first frame (what its relative "
        "error is measured from; built again for a resumed run); NaN when not measured");
  py::class_<EnergyWatch>(m, "EnergyWatch",
                          "The relative energy error of a run since its start: observe(world, "
                          "frame) after each frame returns True the first time it passes the "
                          "threshold")
      .def(py::init<const World&, double>(), py::arg("world"),
           py::arg("threshold") = kDefaultEnergyThreshold)
      .def("observe", &EnergyWatch::observe, py::arg("world"), py::arg("frame"))
      .def_property_readonly("active", &EnergyWatch::active)
      .def_property_readonly("start_energy", &EnergyWatch::start_energy)
      .def_property_readonly("last_error", &EnergyWatch::last_error)
      .def_property_readonly("worst_error", &EnergyWatch::worst_error)
      .def_property_readonly("threshold", &EnergyWatch::threshold)
      .def_property_readonly("first_frame_over", &EnergyWatch::first_frame_over);
  m.def("linear_momentum", &linear_momentum, py::arg("world"));
  m.def("angular_momentum", &angular_momentum, py::arg("world"), py::arg("origin") = Vec2{});
  m.def("center_of_mass", &center_of_mass, py::arg("world"));
  m.def("state_hash", &state_hash, py::arg("world"),
        "A 64-bit hash of every body's state bits (as `calder run` prints)");
}

}  // namespace calder::python
