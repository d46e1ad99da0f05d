// SPDX-License-Identifier: MIT
// What the binding's files share: the per-world bookkeeping that keeps
// numpy views and field handles from ever reaching freed memory, and the
// functions that add each part of the API to the module.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <calder/world.hpp>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace calder::python {

namespace py = pybind11;

// Bookkeeping of one World, looked up by its address (a World owned by a
// Simulation has no Python object of its own). Touched only with the GIL held.
struct WorldState {
  // numpy views of this world's arrays still alive: while any is, the world
  // may not gain bodies (that could move the arrays and free the old ones).
  int live_views = 0;
  // World.step running with the GIL released: nothing may add bodies or
  // clear them, fields included, until it returns.
  bool stepping = false;
  // Bumped by clear_fields(): handles to the removed fields see the change.
  std::uint64_t field_generation = 0;
};
WorldState& state_of(const World& world);

// Throws calder::Error (naming `where`) if the world's bodies may not change
// now: views alive (when `grows`) or a step running in another thread.
void require_resizable(const World& world, const char* where, bool grows);

// Runs f with the GIL released and the world marked as stepping, so that
// other threads can neither resize the world nor step it meanwhile.
template <class Function>
void without_gil(World& world, const char* where, Function&& f) {
  WorldState& state = state_of(world);
  require_resizable(world, where, false);  // not already stepping
  state.stepping = true;
  struct Done {
    WorldState& s;
    ~Done() { s.stepping = false; }
  } done{state};
  py::gil_scoped_release release;
  f();
}

// A read-only numpy view of one of the world's arrays. Its base keeps `owner`
// (the Python object that keeps the World alive) and counts as a live view.
py::array body_view(const py::object& owner, const World& world, std::span<const double> data);

// One column of bodies' values from Python: a 1-D array, or one number for
// all bodies; viewed without a copy when it is already a contiguous float64
// array. Anything else raises TypeError naming `where` and `name`.
struct Column {
  py::array_t<double, py::array::c_style | py::array::forcecast> values;
  double scalar = 0.0;
  bool is_array = false;

  Column(const py::handle& given, const char* where, const char* name);
  [[nodiscard]] std::span<const double> span() const;
};

// The arguments of World.add_bodies and Simulation.set_bodies (x, y, vx, vy,
// mass, radius, friction or None, drag_area), as World::add_bodies' columns.
class BodyArguments {
 public:
  BodyArguments(const char* where, const py::handle& x, const py::handle& y, const py::handle& vx,
                const py::handle& vy, const py::handle& mass, const py::handle& radius,
                const py::object& friction, const py::handle& drag_area);
  // True when an argument is an empty array: no bodies (World::add_bodies
  // would read an empty column as "not given" and add one body).
  [[nodiscard]] bool empty() const { return empty_; }
  [[nodiscard]] BodyColumns columns() const;
  // One BodyDef per body, checked as World::add_bodies checks them (its
  // message, with `where` in place of "World::add_bodies").
  [[nodiscard]] std::vector<BodyDef> body_defs(const char* where) const;

 private:
  Column x_, y_, vx_, vy_, mass_, radius_, drag_area_;
  std::optional<Column> friction_;
  bool empty_ = false;
};

// The Python exception type calder.Error (a ValueError).
py::handle error_type();

void bind_vec2_random(py::module_& m);
void bind_fields(py::module_& m);
void bind_world(py::module_& m);
void bind_scene_render(py::module_& m);
void bind_snapshot(py::module_& m);
// device.cpp: World(device=...) and calder.devices() (calder::gpu).
void use_device(WorldDef& def, const std::string& device);
void bind_devices(py::module_& m);

}  // namespace calder::python

namespace calder::python {
// A live handle (a Python field object) to the world's index-th field.
py::object field_handle(const py::object& owner, World& world, std::size_t index);
// World.add: stores a copy of a field object's parameters; returns the handle.
py::object add_field(const py::object& owner, World& world, py::handle field);
// World.clear_fields: handles to the removed fields raise from then on.
void clear_fields(World& world);
}  // namespace calder::python
