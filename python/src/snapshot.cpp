// SPDX-License-Identifier: MIT
// Python bindings: snapshots and archives (calder/snapshot.hpp): save, load,
// to_bytes and from_bytes on Simulation and World, pickle and copy, and the
// Archive and ArchiveWriter classes.
#include <pybind11/stl.h>

#include <calder/error.hpp>
#include <calder/scene.hpp>
#include <calder/snapshot.hpp>
#include <calder/world.hpp>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>

#include "bindings.hpp"

namespace calder::python {

namespace {

py::bytes to_py(const Bytes& bytes) {
  return {reinterpret_cast<const char*>(bytes.data()), bytes.size()};
}

// A bytes-like object's bytes (bytes, bytearray, memoryview), as a span.
template <class Use>
auto with_bytes(const py::buffer& data, Use use) {
  const py::buffer_info info = data.request();
  if (info.itemsize != 1 || info.ndim != 1) throw Error("expected bytes");
  return use(std::span<const std::uint8_t>(static_cast<const std::uint8_t*>(info.ptr),
                                           static_cast<std::size_t>(info.size)));
}

// save, load, to_bytes, from_bytes, pickling and copying for Simulation and World.
template <class T, class FromBytes, class Load>
void add_snapshot_methods(py::class_<T>& cls, const char* name, FromBytes from_bytes, Load load) {
  cls.def(
         "save", [](const T& self, const std::string& path) { save_snapshot(self, path); },
         py::arg("path"),
         "Writes a snapshot (docs/SNAPSHOTS.md) to path, whole or not at all; load(path) goes "
         "on from it bit for bit")
      .def_static("load", load, py::arg("path"), "Reads a snapshot file written by save()")
      .def(
          "to_bytes", [](const T& self) { return to_py(to_snapshot(self)); },
          "The snapshot as bytes (what save() writes)")
      .def_static(
          "from_bytes",
          [from_bytes](const py::buffer& data) {
            return with_bytes(
                data, [&](std::span<const std::uint8_t> b) { return from_bytes(b, "bytes"); });
          },
          py::arg("data"), "The snapshot's bytes back as an object")
      .def(py::pickle([](const T& self) { return to_py(to_snapshot(self)); },
                      [from_bytes](const py::bytes& state) {
                        const std::string text = state;
                        return from_bytes(
                            std::span<const std::uint8_t>(
                                reinterpret_cast<const std::uint8_t*>(text.data()), text.size()),
                            "pickle");
                      }))
      .def("__copy__",
           [from_bytes](const T& self) {
             const Bytes bytes = to_snapshot(self);
             return from_bytes(bytes, "copy");
           })
      .def(
          "__deepcopy__",
          [from_bytes](const T& self, const py::dict&) {
            const Bytes bytes = to_snapshot(self);
            return from_bytes(bytes, "copy");
          },
          py::arg("memo"));
  (void)name;
}

}  // namespace

void bind_snapshot(py::module_& m) {
  auto simulation = py::reinterpret_borrow<py::class_<Simulation>>(py::type::of<Simulation>());
  add_snapshot_methods(simulation, "Simulation", &simulation_from_snapshot, &load_simulation);
  auto world = py::reinterpret_borrow<py::class_<World>>(py::type::of<World>());
  add_snapshot_methods(world, "World", &world_from_snapshot, &load_world);

  py::class_<ArchiveReader>(m, "Archive",
                            "An archive of snapshots (calder run --archive): its frames, and any\n"
                            "snapshot read alone; a run that was killed reads up to its last\n"
                            "complete snapshot.")
      .def(py::init<const std::string&>(), py::arg("path"))
      .def("__len__", &ArchiveReader::size)
      .def_property_readonly("frames", &ArchiveReader::frames, "The frame of each snapshot")
      .def_property_readonly("complete", &ArchiveReader::complete,
                             "Whether the archive ends with its index (False: a killed run)")
      .def("find", &ArchiveReader::find, py::arg("frame"),
           "The position of the snapshot of this frame, or None")
      .def(
          "snapshot_bytes",
          [](const ArchiveReader& a, std::size_t i) { return to_py(a.snapshot(i)); }, py::arg("i"),
          "The i-th snapshot's bytes (calder.snapshot_reader reads them)")
      .def("simulation", &ArchiveReader::simulation, py::arg("i"),
           "The i-th snapshot as a Simulation (only that snapshot is read)")
      .def(
          "at_frame",
          [](const ArchiveReader& a, std::int64_t frame) {
            const std::optional<std::size_t> i = a.find(frame);
            if (!i) throw Error("Archive.at_frame: no snapshot of frame " + std::to_string(frame));
            return a.simulation(*i);
          },
          py::arg("frame"), "The snapshot of this frame as a Simulation");

  py::class_<ArchiveWriter>(m, "ArchiveWriter",
                            "Appends snapshots to an archive file, each flushed as written;\n"
                            "close() (or the end of a with block) adds the index.")
      .def(py::init<const std::string&>(), py::arg("path"))
      .def("append", &ArchiveWriter::append, py::arg("simulation"))
      .def("close", &ArchiveWriter::close)
      .def("__len__", &ArchiveWriter::size)
      .def(
          "__enter__", [](ArchiveWriter& w) -> ArchiveWriter& { return w; },
          py::return_value_policy::reference_internal)
      .def("__exit__", [](ArchiveWriter& w, const py::args&) { w.close(); });
}

}  // namespace calder::python
