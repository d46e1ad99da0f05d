// SPDX-License-Identifier: MIT
// The extension module calder._calder: the engine's public API for Python.
// python/calder/__init__.py re-exports it with a few helpers.
#include <calder/bulk.hpp>
#include <calder/error.hpp>
#include <calder/nbody.hpp>
#include <calder/render.hpp>
#include <calder/scene_file.hpp>
#include <string>
#include <unordered_map>

#include "bindings.hpp"

namespace calder::python {

namespace {
py::handle error_type_object;
}

WorldState& state_of(const World& world) {
  // Entries are never erased: a handle or view keeps its world alive, and a
  // new world at a reused address finds counts of zero and a generation that
  // only handles made after it will read.
  static std::unordered_map<const World*, WorldState> states;
  return states[&world];
}

void require_resizable(const World& world, const char* where, bool grows) {
  const WorldState& state = state_of(world);
  if (state.stepping) {
    throw Error(std::string(where) + ": the world is stepping in another thread");
  }
  if (grows && state.live_views > 0) {
    throw Error(std::string(where) + ": " + std::to_string(state.live_views) +
                " numpy view(s) of the world's arrays are alive, and adding bodies may move "
                "the arrays; delete the views (del x) and take new ones after adding");
  }
}

namespace {
struct ViewToken {
  const World* world;
  py::object owner;
};
}  // namespace

py::array body_view(const py::object& owner, const World& world, std::span<const double> data) {
  if (data.empty()) {
    py::array_t<double> empty(0);
    empty.attr("flags").attr("writeable") = false;
    return empty;
  }
  ++state_of(world).live_views;
  auto* token = new ViewToken{&world, owner};
  py::capsule base(token, [](void* pointer) {
    auto* t = static_cast<ViewToken*>(pointer);
    --state_of(*t->world).live_views;
    delete t;
  });
  py::array_t<double> view({static_cast<py::ssize_t>(data.size())}, {sizeof(double)}, data.data(),
                           base);
  // The base is a capsule, which offers no writable buffer: numpy refuses
  // to make the view writeable again.
  py::detail::array_proxy(view.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return view;
}

py::handle error_type() { return error_type_object; }

}  // namespace calder::python

PYBIND11_MODULE(_calder, m) {
  namespace py = pybind11;
  using namespace calder::python;
  m.doc() =
      "calder: the physics of chapter 2 (Forces) of The Nature of Code, for Python.\n\n"
      "Bodies with mass moving under forces by Newton's laws, in the book's vocabulary\n"
      "(Mover, apply_force, Attractor, Liquid), p5.js-compatible to the last bit.";

  static py::exception<calder::Error> error(m, "Error", PyExc_ValueError);
  error.doc() = "A bad argument or a failed step; the message is calder's (a ValueError).";
  error_type_object = error;
  static py::exception<calder::SceneFileError> scene_file_error(m, "SceneFileError", error);
  scene_file_error.doc() =
      "A scene file that cannot be read; the message names file, line and field.";
  // Translators run newest first: the more specific type is registered last.
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const calder::Error& e) {
      error(e.what());
    }
  });
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const calder::SceneFileError& e) {
      scene_file_error(e.what());
    }
  });

  bind_vec2_random(m);
  bind_fields(m);
  bind_world(m);
  bind_scene_render(m);
  bind_snapshot(m);
  bind_devices(m);

  // Frees the renderer's caches at exit, as the calder command does, so a
  // leak checker sees a clean interpreter exit.
  py::module_::import("atexit").attr("register")(
      py::cpp_function([] { calder::release_render_caches(); }));
}
