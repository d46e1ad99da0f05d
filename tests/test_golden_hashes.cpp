// SPDX-License-Identifier: MIT
// The golden hashes: every built-in scene, seeds 0, 1 and 42, its default
// frames, gives the state hash recorded in tests/golden/state_hashes.txt, in
// this build (GCC, Clang, the sanitizer build), as in WebAssembly and Python,
// which check the same file. The file was written by the calder command
// (scripts/golden-hashes); a change that alters a bit must rewrite it and say
// why in CHANGELOG.md.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "calder/bulk.hpp"
#include "calder/diagnostics.hpp"
#include "calder/nbody.hpp"
#include "calder/scene.hpp"

namespace {

struct Golden {
  std::string scene;
  std::uint32_t seed = 0;
  std::int64_t frames = 0;
  std::string hash;
};

std::vector<Golden> golden_lines() {
  std::ifstream in(std::string(CALDER_SOURCE_DIR) + "/tests/golden/state_hashes.txt");
  EXPECT_TRUE(in.good()) << "tests/golden/state_hashes.txt is missing";
  std::vector<Golden> lines;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream words(line);
    Golden g;
    words >> g.scene >> g.seed >> g.frames >> g.hash;
    EXPECT_FALSE(words.fail()) << "tests/golden/state_hashes.txt: bad line '" << line << "'";
    lines.push_back(g);
  }
  return lines;
}

std::string hex16(std::uint64_t value) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(value));
  return text;
}

TEST(GoldenHashes, EveryBuiltinSceneAndSeedGivesTheRecordedHash) {
  // The kernels linking calder::nbody and calder::bulk made the defaults, as
  // the command, the Python module and the page run scenes (other tests in
  // this process may have replaced them).
  calder::set_mutual_attraction_backend(calder::nbody::mutual_attraction);
  calder::set_step_batch_backend(calder::bulk::step_batch);
  const std::vector<Golden> lines = golden_lines();
  std::vector<std::string> covered;
  for (const Golden& g : lines) {
    SCOPED_TRACE(g.scene + " --seed " + std::to_string(g.seed));
    calder::Simulation simulation(calder::builtin_scene(g.scene), g.seed);
    while (simulation.frame() < g.frames) simulation.step();
    EXPECT_EQ(hex16(calder::state_hash(simulation.world())), g.hash)
        << "after " << g.frames << " frames; if the change is meant, rewrite the file with "
        << "scripts/golden-hashes and say why in CHANGELOG.md";
    if (covered.empty() || covered.back() != g.scene) covered.push_back(g.scene);
  }
  // The file covers every built-in scene, three seeds each.
  std::vector<std::string> names;
  for (const calder::SceneInfo& info : calder::builtin_scenes()) names.push_back(info.name);
  EXPECT_EQ(covered, names);
  EXPECT_EQ(lines.size(), 3 * names.size());
}

}  // namespace
