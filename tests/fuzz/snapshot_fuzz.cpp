// SPDX-License-Identifier: MIT
// libFuzzer target: the snapshot reader (calder run FILE.snap, Simulation.load,
// the page's drop), then a few frames of what it read. Bad input must end in
// InputError, never a crash, a hang or a huge allocation.
//
// Each input is read twice: as it is (the framing: header, lengths,
// checksums), then with every section's CRC-32 made right, so that mutations
// reach the sections' decoders instead of stopping at a checksum.
#include <calder/error.hpp>
#include <calder/scene.hpp>
#include <calder/snapshot.hpp>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace {

std::uint64_t le(const std::vector<std::uint8_t>& b, std::size_t at, int n) {
  std::uint64_t v = 0;
  for (int i = n - 1; i >= 0; --i) v = (v << 8U) | b[at + static_cast<std::size_t>(i)];
  return v;
}

// The input with each section's CRC-32 recomputed (docs/SNAPSHOTS.md's framing).
std::vector<std::uint8_t> fixed_checksums(std::vector<std::uint8_t> b) {
  std::size_t at = 16;
  while (b.size() >= at + 16) {
    const std::uint64_t length = le(b, at + 8, 8);
    if (length > b.size() - at - 16) break;
    const std::uint32_t crc = calder::crc32(std::span(b).subspan(at + 16, length));
    for (int i = 0; i < 4; ++i) {
      b[at + 4 + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(crc >> (8 * i));
    }
    at += 16 + ((length + 7) / 8) * 8;
  }
  return b;
}

void read_and_step(const std::vector<std::uint8_t>& bytes) {
  try {
    calder::Simulation simulation = calder::simulation_from_snapshot(bytes, "fuzz.snap");
    std::size_t generated = 0;  // what a press that resets would build
    for (const calder::BodyGroup& group : simulation.scene().bodies) generated += group.count;
    if (generated > 10'000 || simulation.world().body_count() > 10'000) return;
    for (int frame = 0; frame < 3; ++frame) simulation.step();
  } catch (const calder::Error&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::vector<std::uint8_t> bytes(data, data + size);
  read_and_step(bytes);
  read_and_step(fixed_checksums(bytes));
  return 0;
}
