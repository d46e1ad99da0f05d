// Uses an installed calder: one body of mass 2 pushed by a force (2, 0) for one
// frame. Acceleration 1, so semi-implicit Euler gives v = 1, then x = 1.
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
  std::printf("calder_consumer: ok (x = %g)\n", x);
  return 0;
}
