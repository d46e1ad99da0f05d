// SPDX-License-Identifier: MIT
// Uses an installed calder: one body of mass 2 pushed by a force (2, 0) for one
// frame. Acceleration 1, so semi-implicit Euler gives v = 1, then x = 1. And
// the library's version is the headers' version.
#include <calder/calder.hpp>
#include <cstdio>

int main() {
  calder::World world;
  const auto id = world.add_body(calder::BodyDef{.position = {0, 0}, .mass = 2.0});
  world.apply_force(id, {2, 0});
  world.step();
  const double x = world.position(id).x;
  if (x != 1.0) {
    std::fprintf(stderr, "calder_consumer: expected x == 1 after one step, got %.17g\n", x);
    return 1;
  }
  if (calder::version() != CALDER_VERSION_STRING) {
    std::fprintf(stderr, "calder_consumer: headers say %s, the library %.*s\n",
                 CALDER_VERSION_STRING, static_cast<int>(calder::version().size()),
                 calder::version().data());
    return 1;
  }
  std::printf("calder_consumer: ok (x = %g, calder %s)\n", x, CALDER_VERSION_STRING);
  return 0;
}
