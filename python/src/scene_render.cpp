// SPDX-License-Identifier: MIT
// Scenes (built-in or from a scene file), Simulation, and drawing with
// calder::render: a frame as a numpy image, PNG and GIF files.
#include <pybind11/operators.h>
#include <pybind11/stl.h>

#include <calder/fixed_step.hpp>
#include <calder/render.hpp>
#include <calder/scene.hpp>
#include <calder/scene_file.hpp>
#include <calder/trajectory.hpp>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <string>

#include "bindings.hpp"

namespace calder::python {

namespace {

// Whether rebuilding the scene's body groups (reset_bodies, or a press when
// the scene's on_press resets) makes more bodies than the world holds: its
// arrays may then move, which no live numpy view may see (after set_bodies
// with fewer bodies than the scene).
bool reset_may_grow(const Simulation& s) {
  std::size_t rebuilt = 0;
  for (const BodyGroup& group : s.scene().bodies) rebuilt += group.count;
  return rebuilt > s.world().body_count();
}

bool press_may_grow(const Simulation& s) {
  return s.scene().on_press == PressAction::reset && reset_may_grow(s);
}

// A built-in scene's name, or the path of a scene file, decided as the calder
// command decides (calder::load_scene).
Scene scene_from(const std::string& name_or_path) { return load_scene(name_or_path); }

py::array_t<std::uint8_t> image_of(const Canvas& canvas) {
  const std::vector<std::uint8_t> rgba = canvas.rgba();
  py::array_t<std::uint8_t> image({canvas.pixel_height(), canvas.pixel_width(), 4});
  std::memcpy(image.mutable_data(), rgba.data(), rgba.size());
  return image;
}

// calder::TrajectoryWriter into a Python text stream (anything with
// write(str)): each call's rows are formatted by the C++ writer into a
// buffer, then handed to the stream in one write.
class PyTrajectoryWriter {
 public:
  explicit PyTrajectoryWriter(py::object out)
      : out_(checked_stream(std::move(out))), writer_(buffer_) {
    flush();
  }
  void write(std::int64_t frame, const World& world) {
    writer_.write(frame, world);
    flush();
  }

 private:
  static py::object checked_stream(py::object out) {
    if (!py::hasattr(out, "write")) {
      throw py::type_error("TrajectoryWriter: out must have write(str), as a text file has");
    }
    return out;
  }
  void flush() {
    out_.attr("write")(buffer_.str());
    buffer_.str({});
  }
  py::object out_;
  std::ostringstream buffer_;
  TrajectoryWriter writer_;
};

}  // namespace

void bind_scene_render(py::module_& m) {
  py::enum_<PressAction>(m, "PressAction")
      .value("none", PressAction::none)
      .value("reset", PressAction::reset)
      .value("toss", PressAction::toss);

  py::class_<Scene>(m, "Scene",
                    "A world as data (canvas, bodies, fields, mouse script, look): a built-in\n"
                    "scene or a scene file (docs/SCENES.md). Simulation runs one.")
      .def(py::init(&scene_from), py::arg("name_or_path"),
           "A built-in scene by name (calder.builtin_scenes()) or a scene file's path")
      .def_static("builtin", &builtin_scene, py::arg("name"))
      .def_static("load", &load_scene_file, py::arg("path"), "Reads a scene file (TOML)")
      .def_static("parse", &parse_scene, py::arg("text"), py::arg("source_name") = "<string>",
                  "Reads a scene file's text")
      .def("to_toml", &to_toml, "The scene as a scene file's text")
      .def("validate", &Scene::validate)
      .def_readwrite("name", &Scene::name)
      .def_readwrite("description", &Scene::description)
      .def_readwrite("frames", &Scene::frames)
      .def_readwrite("origin", &Scene::origin)
      .def_property(
          "seed", [](const Scene& s) { return s.world.seed; },
          [](Scene& s, std::uint32_t seed) { s.world.seed = seed; })
      .def_property_readonly("width", [](const Scene& s) { return s.world.width; })
      .def_property_readonly("height", [](const Scene& s) { return s.world.height; })
      .def_property_readonly("on_press", [](const Scene& s) { return s.on_press; })
      .def("__repr__", [](const Scene& s) { return "Scene('" + s.name + "')"; });

  m.def(
      "builtin_scenes",
      [] {
        std::vector<std::pair<std::string, std::string>> scenes;
        for (const SceneInfo& info : builtin_scenes())
          scenes.emplace_back(info.name, info.description);
        return scenes;
      },
      "The built-in scenes: a list of (name, description)");

  py::class_<Simulation>(m, "Simulation",
                         "Runs a scene one frame at a time, with its scripted mouse (or yours):\n"
                         "the same frames, bits and state hash as `calder run`.")
      .def(py::init([](const py::object& scene, std::optional<std::uint32_t> seed) {
             if (py::isinstance<py::str>(scene)) {
               return std::make_unique<Simulation>(scene_from(scene.cast<std::string>()), seed);
             }
             return std::make_unique<Simulation>(scene.cast<Scene>(), seed);
           }),
           py::arg("scene"), py::arg("seed") = py::none(),
           "scene: a Scene, a built-in scene's name or a scene file's path; seed replaces "
           "the scene's")
      .def(
          "step",
          [](Simulation& s, std::optional<bool> mouse_pressed, std::optional<Vec2> mouse) {
            require_resizable(s.world(), "Simulation.step", press_may_grow(s));
            if (!mouse_pressed && !mouse) {
              s.step();
            } else {
              const std::int64_t next = s.frame() + 1;
              s.step(InputState{mouse_pressed.value_or(s.scene().input.pressed_at(next)),
                                mouse.value_or(s.scene().input.mouse_at(next))});
            }
          },
          py::kw_only(), py::arg("mouse_pressed") = py::none(), py::arg("mouse") = py::none(),
          "One frame; the mouse from the scene's script unless given")
      .def(
          "run",
          [](Simulation& s, std::int64_t frames) {
            if (frames < 0) {
              throw Error("Simulation.run: frames must be >= 0 (got " + std::to_string(frames) +
                          ")");
            }
            require_resizable(s.world(), "Simulation.run", press_may_grow(s));
            without_gil(s.world(), "Simulation.run", [&] {
              for (std::int64_t k = 0; k < frames; ++k) s.step();
            });
          },
          py::arg("frames"), "frames scripted frames (the GIL is released meanwhile)")
      .def("reset_bodies",
           [](Simulation& s) {
             require_resizable(s.world(), "Simulation.reset_bodies", reset_may_grow(s));
             s.reset_bodies();
           })
      .def(
          "set_bodies",
          [](Simulation& s, const py::handle& x, const py::handle& y, const py::handle& vx,
             const py::handle& vy, const py::handle& mass, const py::handle& radius,
             const py::object& friction, const py::handle& drag_area) {
            const char* where = "Simulation.set_bodies";
            const BodyArguments arguments(where, x, y, vx, vy, mass, radius, friction, drag_area);
            // The world's arrays are replaced (the old ones freed): no view may be alive.
            require_resizable(s.world(), where, true);
            s.set_bodies(arguments.body_defs(where));
          },
          py::arg("x"), py::arg("y"), py::arg("vx") = 0.0, py::arg("vy") = 0.0,
          py::arg("mass") = 1.0, py::arg("radius") = 0.0, py::arg("friction") = py::none(),
          py::arg("drag_area") = 1.0,
          "Replaces the bodies by these, in order (calder run --state), all or none.\n"
          "Arguments as World.add_bodies: arrays, or one number for all bodies.\n"
          "The fields, time and generator stay; the mouse lets go of a tossed body.")
      .def_property_readonly(
          "world", [](Simulation& s) -> World& { return s.world(); },
          py::return_value_policy::reference_internal)
      .def_property_readonly("scene", &Simulation::scene)
      .def_property_readonly("frame", &Simulation::frame);

  py::class_<FixedStep>(m, "FixedStep",
                        "A fixed time step for real-time use: collects elapsed real time and\n"
                        "runs as many whole steps as fit, carrying the remainder; alpha tells\n"
                        "how far the leftover is into the next step (for drawing in between).\n"
                        "At most max_steps per advance: time beyond that is dropped.")
      .def(py::init<double, int>(), py::arg("steps_per_second") = 60.0, py::arg("max_steps") = 8)
      .def(
          "advance",
          [](FixedStep& pacer, const py::object& target, double elapsed_seconds) {
            const char* where = "FixedStep.advance";
            int steps = 0;
            if (py::isinstance<World>(target)) {
              World& world = target.cast<World&>();
              without_gil(world, where, [&] { steps = pacer.advance(world, elapsed_seconds); });
            } else if (py::isinstance<Simulation>(target)) {
              Simulation& simulation = target.cast<Simulation&>();
              without_gil(simulation.world(), where, [&] {
                steps = pacer.advance(elapsed_seconds, [&] { simulation.step(); });
              });
            } else if (PyCallable_Check(target.ptr()) != 0) {
              steps = pacer.advance(elapsed_seconds, [&] { target(); });
            } else {
              throw py::type_error(std::string(where) +
                                   ": target must be a World, a Simulation or a callable");
            }
            return steps;
          },
          py::arg("target"), py::arg("elapsed_seconds"),
          "Adds elapsed_seconds (>= 0) of real time and steps target once per step\n"
          "due: a World (world.step()), a Simulation (its scripted frame) or a\n"
          "function of no arguments. Returns the number of steps taken.")
      .def_property_readonly("alpha", &FixedStep::alpha,
                             "Fraction of a step in the carried-over time, in [0, 1)")
      .def_property("steps_per_second", &FixedStep::steps_per_second,
                    &FixedStep::set_steps_per_second, "Steps per second of real time (> 0)")
      .def("reset", &FixedStep::reset, "Drops carried-over time (e.g. after a pause)");

  m.def("format_number", &format_number, py::arg("value"),
        "The shortest decimal form that reads back to the same float ('0.1'); 'nan', 'inf'");
  py::class_<PyTrajectoryWriter>(
      m, "TrajectoryWriter",
      "Writes a trajectory as CSV, `frame,body,x,y,vx,vy` (calder run --trajectory),\n"
      "into a text stream: the header at once, then one row per body per write().\n"
      "Numbers in their shortest exact form: the file reads back to the same bits.")
      .def(py::init<py::object>(), py::arg("out"),
           "out: anything with write(str), e.g. open(path, 'w')")
      .def("write", &PyTrajectoryWriter::write, py::arg("frame"), py::arg("world"),
           "One row per body of the world, all with this frame number");

  // --- drawing ---
  py::class_<Color>(m, "Color", "RGBA, each in [0, 1]")
      .def(py::init([](double r, double g, double b, double a) {
             return Color{r, g, b, a};
           }),
           py::arg("r") = 0.0, py::arg("g") = 0.0, py::arg("b") = 0.0, py::arg("a") = 1.0)
      .def_static("gray", &Color::gray, py::arg("v"), py::arg("alpha") = 255.0,
                  "p5's fill(v, alpha), 0..255")
      .def_static("rgb", &Color::rgb, py::arg("r"), py::arg("g"), py::arg("b"),
                  py::arg("alpha") = 255.0, "p5's fill(r, g, b, alpha), 0..255")
      .def_readwrite("r", &Color::r)
      .def_readwrite("g", &Color::g)
      .def_readwrite("b", &Color::b)
      .def_readwrite("a", &Color::a)
      .def(py::self == py::self);

  py::enum_<BookLook>(m, "BookLook")
      .value("sketch", BookLook::sketch)
      .value("figure", BookLook::figure);

  py::class_<RenderStyle>(m, "RenderStyle", "How a frame is drawn (colours, trails, overlays)")
      .def(py::init<>())
      .def_readwrite("background", &RenderStyle::background)
      .def_readwrite("trails", &RenderStyle::trails)
      .def_readwrite("trail_alpha", &RenderStyle::trail_alpha)
      .def_readwrite("body_fill", &RenderStyle::body_fill)
      .def_readwrite("body_stroke", &RenderStyle::body_stroke)
      .def_readwrite("body_stroke_weight", &RenderStyle::body_stroke_weight)
      .def_readwrite("squares", &RenderStyle::squares)
      .def_readwrite("liquid_fill", &RenderStyle::liquid_fill)
      .def_readwrite("attractor_fill", &RenderStyle::attractor_fill)
      .def_readwrite("show_forces", &RenderStyle::show_forces)
      .def_readwrite("show_velocity", &RenderStyle::show_velocity)
      .def_readwrite("show_hud", &RenderStyle::show_hud)
      .def_readwrite("hud_start_energy", &RenderStyle::hud_start_energy)
      .def_readwrite("force_scale", &RenderStyle::force_scale)
      .def_readwrite("velocity_scale", &RenderStyle::velocity_scale)
      .def("validate", &RenderStyle::validate);
  m.def("book_style", &book_style, py::arg("scene"), py::arg("look") = BookLook::sketch,
        "The scene's look as the book's sketch (or figure) draws it");

  py::class_<Canvas>(m, "Canvas", "An image to draw worlds on (Cairo): canvas pixels times scale.")
      .def(py::init<int, int, double>(), py::arg("width"), py::arg("height"),
           py::arg("scale") = 1.0)
      .def(
          "draw",
          [](Canvas& c, const Simulation& s, const std::optional<RenderStyle>& style) {
            c.draw(s.world(), s.scene(), style ? *style : book_style(s.scene()), s.frame());
          },
          py::arg("simulation"), py::arg("style") = py::none(),
          "Draws the simulation's world, fields and all, in the scene's look unless style")
      .def(
          "draw_world",
          [](Canvas& c, const World& w, const std::optional<RenderStyle>& style, std::int64_t frame,
             Vec2 origin) { c.draw(w, style ? *style : RenderStyle{}, frame, origin); },
          py::arg("world"), py::arg("style") = py::none(), py::arg("frame") = 0,
          py::arg("origin") = Vec2{})
      .def("clear", &Canvas::clear)
      .def_property_readonly("width", &Canvas::width)
      .def_property_readonly("height", &Canvas::height)
      .def_property_readonly("scale", &Canvas::scale)
      .def_property_readonly("pixel_width", &Canvas::pixel_width)
      .def_property_readonly("pixel_height", &Canvas::pixel_height)
      .def("image", &image_of,
           "The image as a new numpy array (pixel_height, pixel_width, 4) of uint8 RGBA")
      .def(
          "encode_png",
          [](const Canvas& c) {
            const std::vector<unsigned char> png = c.encode_png();
            return py::bytes(reinterpret_cast<const char*>(png.data()), png.size());
          },
          "The image as PNG bytes")
      .def("write_png", &Canvas::write_png, py::arg("path"));

  py::class_<GifWriter>(m, "GifWriter",
                        "An animated GIF written frame by frame (a context manager: finishes on "
                        "exit)")
      .def(py::init<const std::string&, int, int, double>(), py::arg("path"), py::arg("width"),
           py::arg("height"), py::arg("fps") = 30.0)
      .def("add_frame", &GifWriter::add_frame, py::arg("canvas"))
      .def("finish", &GifWriter::finish)
      .def_property_readonly("frame_count", &GifWriter::frame_count)
      .def_property_readonly("path", &GifWriter::path)
      .def("__enter__", [](py::object self) { return self; })
      .def("__exit__",
           [](GifWriter& g, const py::object& type, const py::object&, const py::object&) {
             if (type.is_none()) g.finish();
           });
}

}  // namespace calder::python
