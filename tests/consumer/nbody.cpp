// SPDX-License-Identifier: MIT
// calder::nbody from an installed calder: two bodies 5 apart, G = 1, no
// softening. Newton: body 0 (at the origin) accelerates toward body 1 (mass 2,
// at (3, 4)) by 2 / 25 along (3, 4) / 5 = (0.048, 0.064), from the kernels
// called directly and from a world's MutualAttraction with method direct,
// which linking calder::nbody is enough for (no call registers them).
#include <calder/calder.hpp>
#include <calder/nbody.hpp>
#include <cmath>
#include <cstdio>
#include <vector>

namespace {

bool is_expected(const char* what, double ax, double ay) {
  if (std::abs(ax - 0.048) > 1e-12 || std::abs(ay - 0.064) > 1e-12) {
    std::fprintf(stderr, "consumer_nbody: %s: expected (0.048, 0.064), got (%.17g, %.17g)\n", what,
                 ax, ay);
    return false;
  }
  return true;
}

}  // namespace

int main() {
  const std::vector<double> x{0, 3}, y{0, 4}, mass{1, 2};
  std::vector<double> ax(2, 0.0), ay(2, 0.0);
  calder::nbody::direct_accelerations(x, y, mass, ax, ay);
  if (!is_expected("direct_accelerations", ax[0], ay[0])) return 1;

  try {
    calder::World world;
    const calder::BodyId first = world.add_body({.position = {0, 0}, .mass = 1});
    world.add_body({.position = {3, 4}, .mass = 2});
    world.add(calder::MutualAttraction{.law = calder::AttractionLaw::newtonian(),
                                       .method = calder::NBodyMethod::direct});
    world.step();  // from rest, dt = 1: the velocity after one step is the acceleration
    if (!is_expected("World with method direct", world.velocity(first).x,
                     world.velocity(first).y)) {
      return 1;
    }
  } catch (const calder::Error& e) {
    std::fprintf(stderr, "consumer_nbody: %s\n", e.what());
    return 1;
  }
  std::printf("consumer_nbody: ok (kernels %s)\n", calder::nbody::kernel_name());
  return 0;
}
