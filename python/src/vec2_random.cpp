// SPDX-License-Identifier: MIT
// Vec2 (with Python's operators), the p5-compatible Random and Noise, the
// module-level random()/noise() and the force laws of forces.hpp.
#include <pybind11/functional.h>
#include <pybind11/operators.h>
#include <pybind11/stl.h>

#include <calder/forces.hpp>
#include <calder/random.hpp>
#include <calder/trajectory.hpp>
#include <calder/vec2.hpp>
#include <string>

#include "bindings.hpp"

namespace calder::python {

namespace {

std::string repr(Vec2 v) { return "Vec2(" + format_number(v.x) + ", " + format_number(v.y) + ")"; }

Vec2 from_sequence(const py::sequence& s) {
  if (py::len(s) != 2) {
    throw py::type_error("Vec2: expected 2 numbers (x, y), got a sequence of " +
                         std::to_string(py::len(s)));
  }
  return {s[0].cast<double>(), s[1].cast<double>()};
}

}  // namespace

void bind_vec2_random(py::module_& m) {
  py::class_<Vec2> vec2(
      m, "Vec2",
      "A 2D vector, p5.Vector's arithmetic in double (mag is sqrt(x*x + y*y)).\n\n"
      "A value: a (x, y) tuple is accepted wherever a Vec2 is. add/sub/mult/div/\n"
      "normalize/set_mag/limit/rotate/lerp/set change the vector and return it,\n"
      "as in p5; the operators + - * / return new vectors.");
  vec2.def(py::init<>())
      .def(py::init([](double x, double y) {
             return Vec2{x, y};
           }),
           py::arg("x"), py::arg("y"))
      .def(py::init(&from_sequence), py::arg("xy"))
      .def_readwrite("x", &Vec2::x)
      .def_readwrite("y", &Vec2::y)
      .def("add", &Vec2::add, py::arg("v"), "self += v; returns self")
      .def("sub", &Vec2::sub, py::arg("v"), "self -= v; returns self")
      .def("mult", &Vec2::mult, py::arg("n"), "self *= n; returns self")
      .def("div", &Vec2::div, py::arg("n"), "self /= n (calder.Error if n == 0); returns self")
      .def("normalize", &Vec2::normalize, "Length 1 (multiplies by 1/len; zero stays zero)")
      .def("set_mag", &Vec2::set_mag, py::arg("length"))
      .def("limit", &Vec2::limit, py::arg("max"))
      .def("rotate", &Vec2::rotate, py::arg("angle"))
      .def("lerp", &Vec2::lerp, py::arg("v"), py::arg("amount"))
      .def("set", &Vec2::set, py::arg("x"), py::arg("y"))
      .def("mag", &Vec2::mag)
      .def("mag_sq", &Vec2::mag_sq)
      .def("heading", &Vec2::heading)
      .def("dist", &Vec2::dist, py::arg("v"))
      .def("dot", &Vec2::dot, py::arg("v"))
      .def("cross", &Vec2::cross, py::arg("v"))
      .def("copy", &Vec2::copy)
      .def("is_finite", &Vec2::is_finite)
      .def_static("from_angle", &Vec2::from_angle, py::arg("angle"), py::arg("length") = 1.0)
      .def_static(
          "random2d", [](Random& rng) { return Vec2::random2d(rng); }, py::arg("rng"),
          "A random unit vector drawn from rng (p5's random2D, but seeded)")
      .def(py::self + py::self)
      .def(py::self - py::self)
      .def(-py::self)
      .def(py::self * double())
      .def(double() * py::self)
      .def(py::self / double())
      .def(py::self += py::self)
      .def(py::self -= py::self)
      .def(py::self *= double())
      .def(py::self /= double())
      .def(py::self == py::self)
      .def(py::self != py::self)
      .def("__repr__", &repr)
      .def("__len__", [](Vec2) { return 2; })
      .def("__iter__", [](Vec2 v) { return py::iter(py::make_tuple(v.x, v.y)); })
      .def("__getitem__",
           [](Vec2 v, int i) {
             if (i == 0 || i == -2) return v.x;
             if (i == 1 || i == -1) return v.y;
             throw py::index_error("Vec2 index out of range");
           })
      .def(py::pickle([](Vec2 v) { return py::make_tuple(v.x, v.y); },
                      [](const py::tuple& t) { return from_sequence(t); }));
  py::implicitly_convertible<py::tuple, Vec2>();
  py::implicitly_convertible<py::list, Vec2>();

  py::class_<Random>(
      m, "Random",
      "p5's random generator (an LCG, polar Box-Muller): the same seed draws the same\n"
      "numbers as randomSeed() in a p5.js sketch.")
      .def(py::init<std::uint32_t>(), py::arg("seed") = 0)
      .def("random_seed", py::overload_cast<double>(&Random::random_seed), py::arg("seed"))
      .def("random", py::overload_cast<>(&Random::random), "A number in [0, 1)")
      .def("random", py::overload_cast<double>(&Random::random), py::arg("max"),
           "A number in [0, max)")
      .def("random", py::overload_cast<double, double>(&Random::random), py::arg("min"),
           py::arg("max"), "A number in [min, max)")
      .def("random_gaussian", &Random::random_gaussian, py::arg("mean") = 0.0, py::arg("sd") = 1.0)
      .def("random2d", &Random::random2d, "A random unit vector")
      .def_property_readonly("state", &Random::state);

  py::class_<Noise>(m, "Noise", "p5's value noise (noise(), noiseSeed(), noiseDetail()).")
      .def(py::init<std::uint32_t>(), py::arg("seed") = 0)
      .def("noise_seed", py::overload_cast<double>(&Noise::noise_seed), py::arg("seed"))
      .def("noise_detail", &Noise::noise_detail, py::arg("octaves"), py::arg("falloff") = 0.5)
      .def("noise", &Noise::noise, py::arg("x"), py::arg("y") = 0.0, py::arg("z") = 0.0)
      .def("__call__", &Noise::noise, py::arg("x"), py::arg("y") = 0.0, py::arg("z") = 0.0);

  // p5's global generators.
  m.def("random_seed", py::overload_cast<double>(&random_seed), py::arg("seed"));
  m.def("random", py::overload_cast<>(&random), "A number in [0, 1) (the global generator)");
  m.def("random", py::overload_cast<double>(&random), py::arg("max"));
  m.def("random", py::overload_cast<double, double>(&random), py::arg("min"), py::arg("max"));
  m.def("random_gaussian", &random_gaussian, py::arg("mean") = 0.0, py::arg("sd") = 1.0);
  m.def("noise_seed", py::overload_cast<double>(&noise_seed), py::arg("seed"));
  m.def("noise_detail", &noise_detail, py::arg("octaves"), py::arg("falloff") = 0.5);
  m.def("noise", &noise, py::arg("x"), py::arg("y") = 0.0, py::arg("z") = 0.0);
  m.def("map_range", &map_range, py::arg("value"), py::arg("start1"), py::arg("stop1"),
        py::arg("start2"), py::arg("stop2"), "p5's map()");
  m.def("constrain", &constrain, py::arg("n"), py::arg("low"), py::arg("high"));

  // --- the force laws: each returns a force, to pass to apply_force ---
  py::enum_<DistanceClamp> laws(m, "DistanceClamp");
  for (const DistanceClampName& law : kDistanceClampNames) {
    laws.value(std::string(law.name).c_str(), law.value);
  }
  py::enum_<MassProduct>(m, "MassProduct")
      .value("left_to_right", MassProduct::left_to_right)
      .value("masses_first", MassProduct::masses_first);

  py::class_<AttractionLaw>(m, "AttractionLaw",
                            "An attraction law: the book's clamped G m M / d^2 by default.")
      .def(py::init([](double G, DistanceClamp clamp, double min, double max, double softening,
                       MassProduct product, double exponent, double repulsion,
                       double repulsion_exponent, ForceLaw custom) {
             AttractionLaw law{G,
                               clamp,
                               min,
                               max,
                               softening,
                               product,
                               exponent,
                               repulsion,
                               repulsion_exponent,
                               std::move(custom)};
             law.validate("AttractionLaw");
             return law;
           }),
           py::kw_only(), py::arg("G") = 1.0, py::arg("clamp") = DistanceClamp::distance,
           py::arg("min") = 5.0, py::arg("max") = 25.0, py::arg("softening") = 0.0,
           py::arg("product") = MassProduct::left_to_right, py::arg("exponent") = 2.0,
           py::arg("repulsion") = 0.0, py::arg("repulsion_exponent") = 3.0,
           py::arg("custom") = ForceLaw{})
      .def_static("book", &AttractionLaw::book, py::arg("G") = 1.0, py::arg("min_distance") = 5.0,
                  py::arg("max_distance") = 25.0, py::arg("product") = MassProduct::left_to_right)
      .def_static("newtonian", &AttractionLaw::newtonian, py::arg("G") = 1.0,
                  py::arg("softening") = 0.0)
      .def_static("from_function", &AttractionLaw::from, py::arg("law"),
                  "law(distance, source_mass, target_mass) -> strength")
      .def_readwrite("G", &AttractionLaw::G)
      .def_readwrite("clamp", &AttractionLaw::clamp)
      .def_readwrite("min", &AttractionLaw::min)
      .def_readwrite("max", &AttractionLaw::max)
      .def_readwrite("softening", &AttractionLaw::softening)
      .def_readwrite("product", &AttractionLaw::product)
      .def_readwrite("exponent", &AttractionLaw::exponent)
      .def_readwrite("repulsion", &AttractionLaw::repulsion)
      .def_readwrite("repulsion_exponent", &AttractionLaw::repulsion_exponent)
      .def_readwrite("custom", &AttractionLaw::custom)
      .def("validate", &AttractionLaw::validate, py::arg("where") = "AttractionLaw");

  m.def("gravity", &gravity, py::arg("g"), py::arg("mass"), py::arg("scale_by_mass"));
  m.def("helium", &helium, py::arg("lift"));
  m.def("noise_wind", &noise_wind, py::arg("noise"), py::arg("time"), py::arg("strength"),
        py::arg("rate") = 0.01, py::arg("offset") = 0.0);
  m.def("fan", &fan, py::arg("fan_position"), py::arg("body_position"), py::arg("strength"),
        py::arg("reach"));
  m.def("edge_force", &edge_force, py::arg("position"), py::arg("width"), py::arg("height"),
        py::arg("strength"), py::arg("margin"));
  m.def("friction", &friction, py::arg("velocity"), py::arg("mu"), py::arg("normal") = 1.0,
        "-mu * normal * v/|v|: the book's friction force");
  m.def("drag", &drag, py::arg("velocity"), py::arg("c"), py::arg("area") = 1.0,
        "-(c * speed) * speed * area * v/|v|: the book's drag force");
  m.def("limit_drag", &limit_drag, py::arg("drag_force"), py::arg("velocity"), py::arg("mass"),
        py::arg("dt"));
  m.def("lift", &lift, py::arg("velocity"), py::arg("coefficient"));
  m.def("attraction", &attraction, py::arg("source_position"), py::arg("source_mass"),
        py::arg("target_position"), py::arg("target_mass"), py::arg("law") = AttractionLaw{},
        "The force the source exerts on the target under law");
  m.def("attraction_potential", &attraction_potential, py::arg("distance"), py::arg("source_mass"),
        py::arg("target_mass"), py::arg("law") = AttractionLaw{});
}

}  // namespace calder::python
