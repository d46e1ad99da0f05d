// SPDX-License-Identifier: MIT
// libFuzzer target: a snapshot whose scene is the fuzzer's. The input is the
// payload of the SCEN section of a valid snapshot (example-2.9 at frame 0,
// its checksum made right), so that every mutation reaches the scene's
// decoder and then the one validator that scene files go through too
// (Scene::validate and the fields' checks): a scene a snapshot may carry is
// one a scene file may say. What it accepts must be written as a scene file
// and read back by the scene-file reader, and a few frames stepped; bad
// input must end in InputError, never a crash, a hang or a huge allocation.
#include <calder/error.hpp>
#include <calder/scene.hpp>
#include <calder/scene_file.hpp>
#include <calder/snapshot.hpp>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <string>
#include <vector>

namespace {

std::uint64_t le(const std::vector<std::uint8_t>& b, std::size_t at, int n) {
  std::uint64_t v = 0;
  for (int i = n - 1; i >= 0; --i) v = (v << 8U) | b[at + static_cast<std::size_t>(i)];
  return v;
}

void store(std::vector<std::uint8_t>& b, std::size_t at, std::uint64_t v, int n) {
  for (int i = 0; i < n; ++i)
    b[at + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(v >> (8 * i));
}

// The snapshot of `base` with its SCEN payload replaced by `scene`.
std::vector<std::uint8_t> with_scene(const std::vector<std::uint8_t>& base,
                                     std::span<const std::uint8_t> scene) {
  std::vector<std::uint8_t> out(base.begin(), base.begin() + 16);
  std::size_t at = 16;
  while (at + 16 <= base.size()) {
    const std::uint64_t length = le(base, at + 8, 8);
    const std::size_t padded = ((length + 7) / 8) * 8;
    const bool is_scene = base[at] == 'S' && base[at + 1] == 'C' && base[at + 2] == 'E';
    std::vector<std::uint8_t> payload(base.begin() + static_cast<std::ptrdiff_t>(at + 16),
                                      base.begin() + static_cast<std::ptrdiff_t>(at + 16 + length));
    if (is_scene) payload.assign(scene.begin(), scene.end());
    const std::size_t head = out.size();
    out.insert(out.end(), base.begin() + static_cast<std::ptrdiff_t>(at),
               base.begin() + static_cast<std::ptrdiff_t>(at + 16));
    store(out, head + 4, calder::crc32(payload), 4);
    store(out, head + 8, payload.size(), 8);
    out.insert(out.end(), payload.begin(), payload.end());
    out.resize(out.size() + (8 - payload.size() % 8) % 8, 0);
    at += 16 + padded;
  }
  return out;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::vector<std::uint8_t> base =
      calder::to_snapshot(calder::Simulation(calder::builtin_scene("example-2.9")));
  const std::vector<std::uint8_t> bytes = with_scene(base, std::span(data, size));
  try {
    calder::Simulation simulation = calder::simulation_from_snapshot(bytes, "fuzz.snap");
    // Accepted: the scene-file reader accepts the same scene (one validator).
    const calder::Scene scene = simulation.scene();
    try {
      (void)calder::parse_scene(calder::to_toml(scene), "fuzz.toml");
    } catch (const calder::Error&) {
      std::abort();  // a scene a snapshot may carry that a scene file may not
    }
    std::size_t generated = 0;  // what a press that resets would build
    for (const calder::BodyGroup& group : scene.bodies) generated += group.count;
    if (generated > 10'000 || simulation.world().body_count() > 10'000) return 0;
    for (int frame = 0; frame < 3; ++frame) simulation.step();
  } catch (const calder::Error&) {
  }
  return 0;
}
