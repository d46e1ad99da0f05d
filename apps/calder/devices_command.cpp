// SPDX-License-Identifier: MIT
#include "devices_command.hpp"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>
#include <vector>

#include "calder/error.hpp"
#include "run_options.hpp"

#if defined(CALDER_APP_HAS_GPU)
#include "calder/gpu.hpp"
#endif

namespace calder::app {

namespace {

// The device index of a --device value: -1 for "gpu" (the first, or
// CALDER_GPU_DEVICE's), N for "gpu:N"; nullopt for "cpu".
std::optional<int> gpu_index(const std::string& value) {
  if (value == "cpu") return std::nullopt;
  if (value == "gpu") return -1;
  if (value.starts_with("gpu:") && value.size() > 4 && value.size() <= 8 &&
      value.find_first_not_of("0123456789", 4) == std::string::npos) {
    return std::stoi(value.substr(4));
  }
  throw InputError("--device: expected cpu, gpu or gpu:N (N a device of 'calder devices'), got '" +
                   value + "'");
}

#if defined(CALDER_APP_HAS_GPU)
std::string mebibytes(std::uint64_t bytes) { return std::to_string(bytes >> 20) + " MiB"; }
#endif

}  // namespace

CLI::App* add_devices_command(CLI::App& app) {
  return app.add_subcommand("devices",
                            "List the devices Vulkan sees, for --device gpu:N (calder::gpu)");
}

void devices_command(std::ostream& out) {
#if defined(CALDER_APP_HAS_GPU)
  std::string why;
  const std::vector<gpu::DeviceInfo> found = gpu::devices(&why);
  if (found.empty()) {
    out << "no Vulkan device: " << why << '\n';
    return;
  }
  for (const gpu::DeviceInfo& d : found) {
    out << "gpu:" << d.index << "  " << d.name << "  (" << d.type << ", Vulkan " << d.api_version
        << ", float64 " << (d.float64 ? "yes" : "no") << ", " << mebibytes(d.memory_bytes)
        << (d.compute ? "" : ", no compute queue") << ")\n";
  }
#else
  (void)out;
  throw InputError("devices: this calder was built without calder::gpu (CALDER_WITH_GPU=OFF)");
#endif
}

void add_device_option(CLI::App& command, std::optional<std::string>& device) {
  command
      .add_option("--device", device,
                  "Where the steps run: cpu (default), gpu (the first Vulkan device, or "
                  "CALDER_GPU_DEVICE's) or gpu:N (see 'calder devices'). The GPU runs the "
                  "float32 and float64 arithmetics of the per-body fields")
      ->type_name("cpu|gpu|gpu:N");
}

#if defined(CALDER_APP_HAS_GPU)
namespace {

// The bodies must fit the device before the run, not fail at its first
// frame: the largest buffer holds 4 numbers a body (x, y, vx, vy), all of
// them 10 (with the accelerations and the bodies' properties), and the
// upload stages as much again in host-visible memory. A scene that resets
// may rebuild more bodies than it starts with (budget_bodies).
void check_device_memory(const std::string& device, const Simulation& simulation,
                         const gpu::DeviceInfo& info) {
  const double n =
      static_cast<double>(budget_bodies(simulation.scene(), simulation.world().body_count()));
  const double real = simulation.world().arithmetic() == Arithmetic::float32 ? 4.0 : 8.0;
  const double largest = 4.0 * n * real;
  const double total = 2.0 * 10.0 * n * real;
  const auto refuse = [&](const char* what, double need, double have) {
    char text[160];
    std::snprintf(text, sizeof text, "%.0f bodies need %s of %.3g MB, the device has %.3g MB", n,
                  what, need / 1e6, have / 1e6);
    throw InputError("--device " + device + ": " + text + " (" + info.name +
                     "); use fewer bodies or the CPU");
  };
  if (info.max_buffer_bytes != 0 && largest > static_cast<double>(info.max_buffer_bytes)) {
    refuse("a buffer", largest, static_cast<double>(info.max_buffer_bytes));
  }
  if (info.memory_bytes != 0 && total > static_cast<double>(info.memory_bytes)) {
    refuse("memory", total, static_cast<double>(info.memory_bytes));
  }
}

}  // namespace
#endif

void use_device(const std::optional<std::string>& device, Simulation& simulation) {
  if (!device) return;
  const std::optional<int> index = gpu_index(*device);
  if (!index) return;
#if defined(CALDER_APP_HAS_GPU)
  try {
    gpu::install(*index);
  } catch (const Error& e) {
    throw InputError("--device " + *device + ": " + e.what());
  }
  const std::string why = gpu::unsupported(simulation.world(), *gpu::installed());
  if (!why.empty()) {
    throw InputError("--device " + *device + ": " + why + " (scene " + simulation.scene().name +
                     ")");
  }
  check_device_memory(*device, simulation, gpu::installed()->info());
#else
  (void)simulation;
  throw InputError("--device " + *device +
                   ": this calder was built without calder::gpu (CALDER_WITH_GPU=OFF)");
#endif
}

}  // namespace calder::app
