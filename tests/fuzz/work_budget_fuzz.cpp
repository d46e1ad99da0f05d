// SPDX-License-Identifier: MIT
// libFuzzer target: the command's work budget (apps/calder/run_options.hpp)
// against what a scene really costs. A scene file is read and checked as
// `calder run` checks it, at a budget of 2 * 10^6 units a frame (the
// command's 10^12 over 500,000 frames); a scene accepted then runs two frames
// and the summary's diagnostics. Every cost that grows with the input must be
// in the budget: an accepted input that takes longer than libFuzzer's
// -timeout (10 s, thousands of times what 2 * 10^6 units take) is a cost the
// budget misses, reported as a timeout.
#include <calder/diagnostics.hpp>
#include <calder/error.hpp>
#include <calder/nbody.hpp>
#include <calder/scene.hpp>
#include <calder/scene_file.hpp>
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <utility>

#include "run_options.hpp"
#include "summary.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    calder::app::PreparedInput input;
    input.source = "fuzz.toml";
    input.scene = calder::parse_scene(text, "fuzz.toml");
    calder::app::limit_threads(input.scene, input.source);
    constexpr std::int64_t kBudgetFrames = 500000;  // 10^12 / 500,000 = 2 * 10^6 a frame
    input.scene.frames = kBudgetFrames;
    std::size_t bodies = 0;
    for (const calder::BodyGroup& group : input.scene.bodies) bodies += group.count;
    calder::app::check_work_budget(input.scene, bodies, input.source);
    calder::Simulation simulation = calder::app::start_simulation(input);
    calder::app::check_world_work(
        input, simulation,
        {.once = static_cast<double>(calder::app::summary_potential_cost(simulation.world()))});
    for (int frame = 0; frame < 2; ++frame) simulation.step();
    (void)calder::bounded_potential_energy(simulation.world(), 1U << 16U);
  } catch (const calder::Error&) {
    // Refused (bad input, over the budget) or failed: what the command reports.
  }
  return 0;
}
