// SPDX-License-Identifier: MIT
// libFuzzer target: the --state CSV reader (calder run --state FILE), then
// the bodies it makes for a scene. Bad input must end in InputError.
#include <calder/error.hpp>
#include <calder/scene.hpp>
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "errors.hpp"
#include "run_options.hpp"
#include "state_csv.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  try {
    const auto rows = calder::app::parse_state_csv(in, "fuzz.csv");
    calder::Scene scene = calder::builtin_scene("example-2.8");
    calder::Simulation simulation(scene);
    simulation.set_bodies(calder::app::bodies_from_state(rows, scene));
    for (int frame = 0; frame < 3; ++frame) simulation.step();
  } catch (const calder::app::InputError&) {
  } catch (const calder::Error&) {
  }
  return 0;
}
