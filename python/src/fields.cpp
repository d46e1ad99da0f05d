// SPDX-License-Identifier: MIT
// The fields of fields.hpp as Python classes. A field object is either free
// (made in Python, holding its own parameters) or a live handle to a field
// stored in a World (what World.add returns, as World::add returns a
// reference in C++): setting enabled on the handle changes the world's field.
// A handle checks on every access that its field still exists, so one kept
// after clear_fields() raises calder.Error instead of reading freed memory.
#include <pybind11/functional.h>
#include <pybind11/stl.h>

#include <calder/error.hpp>
#include <calder/fields.hpp>
#include <calder/random.hpp>
#include <cctype>
#include <memory>
#include <string>
#include <tuple>
#include <variant>

#include "bindings.hpp"

namespace calder::python {

namespace {

template <class F>
struct FieldRef {
  std::shared_ptr<F> own;  // the parameters of a free field
  py::object owner;        // a live handle: keeps its world alive
  World* world = nullptr;
  std::size_t index = 0;
  std::uint64_t generation = 0;

  static FieldRef detached(F parameters) {
    FieldRef r;
    r.own = std::make_shared<F>(std::move(parameters));
    return r;
  }
  static FieldRef attached_to(const py::object& owner, World& world, std::size_t index) {
    FieldRef r;
    r.owner = owner;
    r.world = &world;
    r.index = index;
    r.generation = state_of(world).field_generation;
    return r;
  }

  // Changing a world's field while it steps in another thread (or from a
  // custom force's function) would race with the step that reads it.
  void require_changeable() const {
    if (world != nullptr && state_of(*world).stepping) {
      throw Error(std::string(field_name(Field{F{}})) +
                  ": the world is stepping in another thread; change its fields between steps");
    }
  }

  F& get() const {
    if (world == nullptr) return *own;
    if (state_of(*world).field_generation != generation) {
      throw Error(std::string(field_name(Field{F{}})) +
                  ": this field was removed from its world by clear_fields()");
    }
    return std::get<F>(world->field(index));
  }
};

// The context a custom force's function receives, valid during that call only.
struct ForceContext {
  const FieldContext* context = nullptr;

  const FieldContext& get() const {
    if (context == nullptr) {
      throw Error(
          "ForceContext: used after the custom force returned (it is valid only during "
          "the call)");
    }
    return *context;
  }
  std::size_t checked(std::size_t i) const {
    const std::size_t n = get().bodies.size();
    if (i >= n) {
      throw Error("ForceContext: no body with index " + std::to_string(i) + " (the world has " +
                  std::to_string(n) + " bodies)");
    }
    return i;
  }
};

CustomForceFunction wrap_custom_force(const py::function& function) {
  // The function is called from World.step, which runs without the GIL:
  // copies of the std::function must not touch Python reference counts.
  std::shared_ptr<py::object> held(new py::object(function), [](py::object* o) {
    py::gil_scoped_acquire gil;
    delete o;
  });
  return [held](const FieldContext& context, std::size_t index) -> Vec2 {
    py::gil_scoped_acquire gil;
    auto ref = std::make_shared<ForceContext>(ForceContext{&context});
    struct Expire {
      ForceContext* c;
      ~Expire() { c->context = nullptr; }
    } expire{ref.get()};
    const py::object result = (*held)(ref, index);
    try {
      return result.cast<Vec2>();
    } catch (const py::cast_error&) {
      throw Error("CustomForce: the function must return a Vec2 or (x, y), got " +
                  std::string(py::str(py::type::of(result).attr("__name__"))));
    }
  };
}

template <class F>
using FieldClass = py::class_<FieldRef<F>>;

// A read-write property of the field's parameters; a new value is checked
// as World::add checks the field, and a bad one changes nothing.
template <class F, class T>
void parameter(FieldClass<F>& c, const char* name, T F::*member) {
  c.def_property(
      name, [member](const FieldRef<F>& r) { return r.get().*member; },
      [member](const FieldRef<F>& r, T value) {
        r.require_changeable();
        F& field = r.get();
        F changed = field;
        changed.*member = std::move(value);
        validate(Field{changed});
        field = std::move(changed);
      });
}

template <class F>
FieldClass<F> field_class(py::module_& m, const char* name, const char* doc) {
  FieldClass<F> c(m, name, doc);
  c.def(py::init([name](const py::kwargs& parameters) {
          FieldRef<F> ref = FieldRef<F>::detached(F{});
          const py::object self = py::cast(ref);
          for (const auto& [key, value] : parameters) {
            const std::string k = py::str(key);
            if (!py::hasattr(py::type::of(self), k.c_str()) || k.starts_with("_") ||
                k == "attached") {
              throw py::type_error(std::string(name) + "() got an unexpected keyword argument '" +
                                   k + "'");
            }
            py::setattr(self, key, value);
          }
          return ref;
        }),
        "Keyword arguments set the parameters (see the class's properties); the rest keep "
        "calder's defaults.");
  c.def_property_readonly(
      "attached", [](const FieldRef<F>& r) { return r.world != nullptr; },
      "True for a handle to a field stored in a world (World.add's result)");
  c.def(
      "copy", [](const FieldRef<F>& r) { return FieldRef<F>::detached(r.get()); },
      "A free copy of the parameters");
  c.def("__repr__", [name](const FieldRef<F>& r) {
    return std::string(name) + "(" + (r.world ? "in a world, enabled=" : "enabled=") +
           (r.get().enabled ? "True" : "False") + ")";
  });
  parameter(c, "enabled", &F::enabled);
  return c;
}

// "edge_force" -> "EdgeForce": a kind's class name from its FieldKind::name.
std::string class_name(const char* kind) {
  std::string out;
  bool upper = true;
  for (const char* c = kind; *c != '\0'; ++c) {
    if (*c == '_') {
      upper = true;
      continue;
    }
    out += upper ? static_cast<char>(std::toupper(static_cast<unsigned char>(*c))) : *c;
    upper = false;
  }
  return out;
}

// A kind's class from its description (FieldKind<F>): its name, its summary
// as the docstring, a property for each parameter.
template <class F>
FieldClass<F> kind_class(py::module_& m) {
  using Kind = FieldKind<F>;
  static const std::string name = class_name(Kind::name);  // the class keeps a pointer to it
  FieldClass<F> c = field_class<F>(m, name.c_str(), Kind::summary);
  std::apply([&c](const auto&... p) { (parameter(c, p.key, p.member), ...); }, Kind::parameters);
  return c;
}

template <class... Fs>
std::tuple<FieldClass<Fs>...> kind_classes(py::module_& m, const std::variant<Fs...>*) {
  return {kind_class<Fs>(m)...};
}

// The kinds' descriptions, for the stub's test: class, name, parameter keys,
// whether scene files hold it.
template <class... Fs>
py::list describe_kinds(const std::variant<Fs...>*) {
  py::list out;
  (
      [&] {
        py::list keys;
        std::apply([&keys](const auto&... p) { (keys.append(p.key), ...); },
                   FieldKind<Fs>::parameters);
        out.append(py::make_tuple(class_name(FieldKind<Fs>::name), FieldKind<Fs>::name, keys,
                                  in_scene_files<Fs>()));
      }(),
      ...);
  return out;
}

template <class F>
bool add_if(const py::object& owner, World& world, py::handle field, py::object& result) {
  if (!py::isinstance<FieldRef<F>>(field)) return false;
  const F parameters = field.cast<const FieldRef<F>&>().get();
  require_resizable(world, "World.add", false);
  world.add_field(Field{parameters});
  result = field_handle(owner, world, world.fields().size() - 1);
  return true;
}

template <class... Fs>
py::object add_any(const py::object& owner, World& world, py::handle field,
                   const std::variant<Fs...>*) {
  py::object result;
  if (!(add_if<Fs>(owner, world, field, result) || ...)) {
    throw py::type_error("World.add: expected a field (Gravity, Wind, Liquid, ...), got " +
                         std::string(py::str(py::type::of(field).attr("__name__"))));
  }
  return result;
}

}  // namespace

py::object field_handle(const py::object& owner, World& world, std::size_t index) {
  Field& field = world.field(index);
  return std::visit(
      [&](auto& f) -> py::object {
        using F = std::decay_t<decltype(f)>;
        return py::cast(FieldRef<F>::attached_to(owner, world, index));
      },
      field);
}

py::object add_field(const py::object& owner, World& world, py::handle field) {
  return add_any(owner, world, field, static_cast<const Field*>(nullptr));
}

void clear_fields(World& world) {
  require_resizable(world, "World.clear_fields", false);
  world.clear_fields();
  ++state_of(world).field_generation;
}

void bind_fields(py::module_& m) {
  py::enum_<Edge>(m, "Edge")
      .value("left", Edge::left)
      .value("right", Edge::right)
      .value("top", Edge::top)
      .value("bottom", Edge::bottom);
  py::enum_<PairOrder>(m, "PairOrder")
      .value("pairwise", PairOrder::pairwise)
      .value("by_source", PairOrder::by_source);
  py::enum_<NBodyMethod> methods(m, "NBodyMethod");
  for (const NBodyMethodName& method : kNBodyMethodNames) {
    methods.value(std::string(method.name).c_str(), method.value);
  }

  py::class_<Rect>(m, "Rect", "An axis-aligned rectangle (x, y: top left corner)")
      .def(py::init([](double x, double y, double w, double h) {
             return Rect{x, y, w, h};
           }),
           py::arg("x") = 0.0, py::arg("y") = 0.0, py::arg("w") = 0.0, py::arg("h") = 0.0)
      .def_readwrite("x", &Rect::x)
      .def_readwrite("y", &Rect::y)
      .def_readwrite("w", &Rect::w)
      .def_readwrite("h", &Rect::h)
      .def("contains", &Rect::contains, py::arg("point"))
      .def("__repr__", [](const Rect& r) {
        return "Rect(" + std::string(py::str(py::make_tuple(r.x, r.y, r.w, r.h))) + ")";
      });
  py::class_<CentralBody>(m, "CentralBody", "A fixed body attracting all others")
      .def(py::init([](Vec2 position, double mass) {
             return CentralBody{position, mass};
           }),
           py::arg("position") = Vec2{}, py::arg("mass") = 500.0)
      .def_readwrite("position", &CentralBody::position)
      .def_readwrite("mass", &CentralBody::mass);
  m.def("touches_edge", &touches_edge, py::arg("edge"), py::arg("position"), py::arg("radius"),
        py::arg("width"), py::arg("height"), py::arg("tolerance"));

  py::class_<ForceContext, std::shared_ptr<ForceContext>>(
      m, "ForceContext",
      "What a CustomForce's function sees: the bodies' state, time, dt and canvas. Valid only "
      "during the call.")
      .def_property_readonly("time", [](const ForceContext& c) { return c.get().time; })
      .def_property_readonly("dt", [](const ForceContext& c) { return c.get().dt; })
      .def_property_readonly("width", [](const ForceContext& c) { return c.get().width; })
      .def_property_readonly("height", [](const ForceContext& c) { return c.get().height; })
      .def_property_readonly("body_count",
                             [](const ForceContext& c) { return c.get().bodies.size(); })
      .def(
          "position",
          [](const ForceContext& c, std::size_t i) {
            return c.get().bodies.position(c.checked(i));
          },
          py::arg("index"))
      .def(
          "velocity",
          [](const ForceContext& c, std::size_t i) {
            return c.get().bodies.velocity(c.checked(i));
          },
          py::arg("index"))
      .def(
          "mass",
          [](const ForceContext& c, std::size_t i) { return c.get().bodies.mass[c.checked(i)]; },
          py::arg("index"))
      .def(
          "radius",
          [](const ForceContext& c, std::size_t i) { return c.get().bodies.radius[c.checked(i)]; },
          py::arg("index"))
      .def(
          "noise",
          [](const ForceContext& c, double x, double y, double z) {
            const FieldContext& context = c.get();
            return context.noise != nullptr ? context.noise->noise(x, y, z) : 0.0;
          },
          py::arg("x"), py::arg("y") = 0.0, py::arg("z") = 0.0, "The world's noise()");

  // Every kind, from its description; then what some kinds add.
  auto kinds = kind_classes(m, static_cast<const Field*>(nullptr));
  m.def(
      "_field_kinds", [] { return describe_kinds(static_cast<const Field*>(nullptr)); },
      "The field kinds' descriptions: (class, name, parameter keys, in scene files).");

  auto& liquid = std::get<FieldClass<Liquid>>(kinds);
  liquid.def(
      "contains", [](const FieldRef<Liquid>& r, Vec2 p) { return r.get().contains(p); },
      py::arg("position"));
  liquid.def(
      "calculate_drag",
      [](const FieldRef<Liquid>& r, Vec2 v, double area) {
        return r.get().calculate_drag(v, area);
      },
      py::arg("velocity"), py::arg("area") = 1.0);

  auto& attractor = std::get<FieldClass<Attractor>>(kinds);
  attractor.def(
      "attract",
      [](const FieldRef<Attractor>& r, Vec2 p, double mass) { return r.get().attract(p, mass); },
      py::arg("body_position"), py::arg("body_mass"));

  auto& custom = std::get<FieldClass<CustomForce>>(kinds);
  custom.def_property(
      "force", [](const FieldRef<CustomForce>& r) { return r.get().force; },
      [](const FieldRef<CustomForce>& r, const py::function& function) {
        r.require_changeable();
        r.get().force = wrap_custom_force(function);
      });
}

}  // namespace calder::python
