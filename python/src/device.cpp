// SPDX-License-Identifier: MIT
// World(device=...) and calder.devices(): calder::gpu from Python, where the
// build has it (CALDER_WITH_GPU); without it, devices() is empty and
// device="gpu" is an error.
#include <string>

#include "bindings.hpp"
#include "calder/error.hpp"

#if defined(CALDER_PYTHON_HAS_GPU)
#include "calder/gpu.hpp"
#endif

namespace calder::python {

void use_device(WorldDef& def, const std::string& device) {
  if (device == "cpu") return;
  const bool any = device == "gpu";
  const bool indexed = device.starts_with("gpu:") && device.size() > 4 && device.size() <= 8 &&
                       device.find_first_not_of("0123456789", 4) == std::string::npos;
  if (!any && !indexed) {
    throw InvalidArgument("World: device must be 'cpu', 'gpu' or 'gpu:N' (got '" + device + "')");
  }
#if defined(CALDER_PYTHON_HAS_GPU)
  if (def.arithmetic == Arithmetic::book) {
    throw InvalidArgument("World: device '" + device +
                          "' runs arithmetic float32 and float64 (book, p5.js's bits, needs the "
                          "CPU): pass arithmetic=Arithmetic.float32 or float64");
  }
  gpu::open(any ? -1 : std::stoi(device.substr(4)));  // this world's, not the process default
  def.backends.step_batch = gpu::step_batch;
  def.backends.mutual_attraction = gpu::mutual_attraction;
#else
  (void)def;
  throw InvalidArgument("World: device '" + device +
                        "': this calder was built without calder::gpu (CALDER_WITH_GPU=OFF)");
#endif
}

void bind_devices(py::module_& m) {
  m.def(
      "gpu_built",
      [] {
#if defined(CALDER_PYTHON_HAS_GPU)
        return true;
#else
        return false;
#endif
      },
      "Whether this calder has calder::gpu (World(device='gpu'); CALDER_WITH_GPU).");
  m.def(
      "devices",
      [] {
        py::list out;
#if defined(CALDER_PYTHON_HAS_GPU)
        for (const gpu::DeviceInfo& d : gpu::devices()) {
          py::dict row;
          row["index"] = d.index;
          row["name"] = d.name;
          row["type"] = d.type;
          row["api_version"] = d.api_version;
          row["float64"] = d.float64;
          row["compute"] = d.compute;
          row["memory_bytes"] = d.memory_bytes;
          out.append(row);
        }
#endif
        return out;
      },
      "The Vulkan devices World(device='gpu:N') can use, as dicts (index, name, type,\n"
      "api_version, float64, compute, memory_bytes); empty without Vulkan or calder::gpu.");
}

}  // namespace calder::python
