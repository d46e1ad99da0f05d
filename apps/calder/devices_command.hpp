// SPDX-License-Identifier: MIT
// calder command: `calder devices` (what Vulkan sees) and `--device` on
// `calder run` (where the scene's steps run: cpu, or gpu through calder::gpu).
#pragma once

#include <optional>
#include <ostream>
#include <string>

#include "calder/scene.hpp"

namespace CLI {
class App;
}

namespace calder::app {

// Adds the `devices` verb to the application.
CLI::App* add_devices_command(CLI::App& app);
// Lists the Vulkan devices, one line each: index, name, type, Vulkan version,
// float64, memory; or says why there are none (still exit 0: a report).
// Throws InputError when calder was built without calder::gpu.
void devices_command(std::ostream& out);

// Adds --device cpu|gpu|gpu:N to a verb.
void add_device_option(CLI::App& command, std::optional<std::string>& device);
// Applies --device before the run: gpu opens the device (calder::gpu::install)
// and checks that the GPU's kernels can step the scene's world, so that every
// step runs there. Throws InputError naming --device and the problem (no
// device, a world the GPU can't run, a build without calder::gpu): never a
// silent run on the CPU.
void use_device(const std::optional<std::string>& device, Simulation& simulation);

}  // namespace calder::app
