// SPDX-License-Identifier: MIT
// calder::scene_file from an installed calder: a built-in scene written as TOML
// and read back writes the same TOML again (a round trip).
#include <calder/scene.hpp>
#include <calder/scene_file.hpp>
#include <cstdio>
#include <string>

int main() {
  const calder::Scene scene = calder::builtin_scene("example-2.1");
  const std::string toml = calder::to_toml(scene);
  const std::string again = calder::to_toml(calder::parse_scene(toml, "consumer.toml"));
  if (toml.empty() || again != toml) {
    std::fprintf(stderr, "consumer_scene_file: the TOML round trip changed the scene\n");
    return 1;
  }
  std::printf("consumer_scene_file: ok (%zu bytes of TOML)\n", toml.size());
  return 0;
}
