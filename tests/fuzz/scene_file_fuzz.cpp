// SPDX-License-Identifier: MIT
// libFuzzer target: the scene-file reader, then the simulation it describes
// for a few frames. Bad input must end in calder::Error (a one-line message),
// never a crash, a leak, a hang or undefined behaviour.
#include <calder/error.hpp>
#include <calder/scene.hpp>
#include <calder/scene_file.hpp>
#include <cstddef>
#include <cstdint>
#include <new>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    calder::Scene scene = calder::parse_scene(text, "fuzz.toml");
    // Bound the work of one input: few bodies, few frames (the reader's own
    // limits allow 10^7 of each; the command's work budget is tested apart).
    std::size_t bodies = 0;
    for (const calder::BodyGroup& group : scene.bodies) bodies += group.count;
    if (bodies > 200) return 0;
    calder::Simulation simulation(std::move(scene));
    for (int frame = 0; frame < 5; ++frame) simulation.step();
  } catch (const calder::Error&) {
    // Refused with a message: what bad input should get.
  }
  return 0;
}
